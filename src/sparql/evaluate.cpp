// Stage 3: evaluating the algebra over a dataset.
//
// Evaluation is a backtracking join over one solution row (a TermId per
// variable): an op binds variables in place, calls its continuation, and
// unbinds them, so no intermediate solution sequence is materialised. Every op
// is evaluated as a join with the bindings it receives, which is exact for
// triple patterns and paths (substitution) and made exact for the rest by
// hiding the received bindings of variables the op mentions but does not
// certainly bind (filters inside the op must not see them) and checking
// compatibility with them afterwards (see Op::hide).
//
// Pre-bound variables (SHACL) and the solution an EXISTS pattern is evaluated
// with are "pinned": never hidden, i.e. they hold in every sub-pattern, which
// is SHACL's Replace(...) definition and SPARQL's substitute(...) for EXISTS.
//
// Basic graph patterns pick their join order when entered, from the
// bindings present at that point and per-pattern match counts computed once
// per (query, dataset): the most selective pattern first. Filters placed on a
// BGP run inside its loop as soon as their variables are bound.
#include <algorithm>
#include <cmath>
#include <deque>
#include <functional>
#include <map>
#include <optional>
#include <unordered_map>
#include <unordered_set>

#include "rdf/iri.hpp"
#include "sparql/algebra.hpp"
#include "sparql/query.hpp"
#include "sparql/value.hpp"
#include "vocab/w3c.hpp"

namespace mospec::sparql {

using rdf::TermId;

namespace detail {

namespace {

constexpr uint32_t kConstTier = 0x80000000u;
constexpr uint32_t kComputedTier = 0xC0000000u;
constexpr uint32_t kTierMask = 0xC0000000u;
// The table of computed terms is dropped at the start of an evaluation once it
// holds this many terms, so a long validation run does not grow it forever.
constexpr size_t kComputedLimit = size_t{1} << 16;
// Patterns computed by expressions are compiled once each, up to this many.
constexpr size_t kRegexCacheLimit = 1024;
// Join ordering only needs to tell selective patterns from unselective ones,
// so match counts stop here (keeps preparing a query cheap on large data).
constexpr size_t kCountCap = 4096;
constexpr std::string_view kRdfLangString = vocab::rdf::langString;
constexpr std::string_view kXsdStringIri = vocab::xsd::string;

// A non-owning reference to a continuation (no allocation, unlike std::function).
class Cont {
 public:
  template <class F>
  requires(!std::is_same_v<std::remove_cvref_t<F>, Cont>) Cont(F& f)
      : obj_(&f), call_(&invoke<F>) {}  // NOLINT: implicit on purpose
  bool operator()() const { return call_(obj_); }

 private:
  template <class F>
  static bool invoke(void* o) {
    return (*static_cast<F*>(o))();
  }
  void* obj_;
  bool (*call_)(void*);
};

// SHACL's pre-binding (appendix "Pre-binding of Variables") is undefined for
// a query that assigns a pre-bound variable with AS, or has a sub-SELECT that
// does not return one the query uses (W3C SHACL tests pre-binding-006 and
// unsupported-sparql-004).
void check_prebound(const Plan& plan, std::string_view name) {
  for (const auto& [assigned, pos] : plan.assigned)
    if (plan.var_names[assigned] == name)
      throw QueryError("unsupported-sparql", pos.line, pos.column,
                       "AS ?" + std::string(name) + " assigns the pre-bound variable $" +
                           std::string(name) + " (not allowed with SHACL pre-binding)");
  if (!plan.names(name)) return;
  for (const auto& [names, pos] : plan.subselect_names)
    if (std::find(names.begin(), names.end(), name) == names.end())
      throw QueryError("unsupported-sparql", pos.line, pos.column,
                       "this sub-SELECT does not return the pre-bound variable $" +
                           std::string(name) +
                           " (SHACL pre-binding requires every sub-SELECT to return the "
                           "pre-bound variables the query uses)");
}

}  // namespace

struct OpState {
  std::vector<uint32_t> order;                       // Bgp: element by level
  std::vector<std::vector<uint32_t>> level_filters;  // Bgp: by level + 1
  std::vector<std::vector<TermId>> buffers;          // Bgp: path results by level
  std::vector<uint8_t> used;
};

struct Prepared {
  std::shared_ptr<const Plan> plan;
  std::vector<TermId> consts;               // plan term id -> engine id
  std::vector<PathPtr> paths;               // with engine ids
  std::vector<std::vector<double>> counts;  // by op, by element: matches of its constants
  std::vector<OpState> state;
};

class Engine {
 public:
  explicit Engine(const rdf::Dataset& data) : data_(data) {
    const auto quads = data.quads();
    for (const rdf::Quad& q : quads) {
      if (q.graph != quads[0].graph) {
        multi_graph_ = true;
        break;
      }
    }
  }

  const rdf::Dataset& data() const { return data_; }
  void set_limits(const Limits& limits) { limits_ = limits; }
  const Limits& limits() const { return limits_; }
  void set_budget(Budget* budget) { shared_budget_ = budget; }

  // ---- terms ----
  std::pair<const rdf::TermTable*, TermId> locate(TermId id) const {
    switch (id.index & kTierMask) {
      case kConstTier:
        return {&constants_, TermId{id.index - kConstTier}};
      case kComputedTier:
        return {&computed_, TermId{id.index - kComputedTier}};
      default:
        return {&data_.terms(), id};
    }
  }
  const rdf::Term& term(TermId id) const {
    auto [table, local] = locate(id);
    return (*table)[local];
  }

  TermId import(const rdf::TermTable& table, TermId id) {
    if (id.is_any()) return id;
    const TermId d = data_.terms().find_equivalent(table, id);
    if (!d.is_any()) return d;
    const TermId c = constants_.import(table, id);
    // Keep one id per term: a computed copy would now be a second id.
    if (!computed_.find_equivalent(table, id).is_any()) computed_ = rdf::TermTable();
    return TermId{kConstTier + c.index};
  }

  TermId intern_iri(std::string_view iri) {
    TermId t = data_.terms().find_iri(iri);
    if (!t.is_any()) return t;
    t = constants_.find_iri(iri);
    if (!t.is_any()) return TermId{kConstTier + t.index};
    return TermId{kComputedTier + computed_.iri(iri).index};
  }
  TermId intern_literal(std::string_view lex, std::string_view datatype, std::string_view lang) {
    TermId dt = data_.terms().find_iri(datatype);
    if (!dt.is_any()) {
      const TermId t = data_.terms().find_literal(lex, dt, lang);
      if (!t.is_any()) return t;
    }
    dt = constants_.find_iri(datatype);
    if (!dt.is_any()) {
      const TermId t = constants_.find_literal(lex, dt, lang);
      if (!t.is_any()) return TermId{kConstTier + t.index};
    }
    return TermId{kComputedTier + computed_.literal(lex, computed_.iri(datatype), lang).index};
  }

  // ---- entry points ----
  void run(const Query& query, std::span<const Binding> prebound, ResultSet* out, bool* found) {
    const std::shared_ptr<const Plan>& plan_ptr = query.shared_plan();
    P_ = &prepare(plan_ptr);
    plan_ = plan_ptr.get();
    const Plan& plan = *plan_;
    if (computed_.size() > kComputedLimit) computed_ = rdf::TermTable();
    const size_t nv = plan.var_names.size();
    row_.assign(nv, kUnbound);
    pinned_.assign(nv, 0);
    tmp_bound_.assign(nv, 0);
    level_of_.assign(nv, -1);
    saved_.clear();
    filled_.clear();
    arena_used_ = 0;
    sub_ready_.assign(plan.selects.size(), 0);
    sub_rows_.resize(plan.selects.size());
    sub_counts_.resize(plan.selects.size());
    if (shared_budget_ != nullptr) {
      budget_ = shared_budget_;
    } else {
      budget_ = &own_budget_.emplace(limits_);
    }
    for (const Binding& b : prebound) {
      std::string_view name = b.name;
      if (!name.empty() && (name[0] == '?' || name[0] == '$')) name.remove_prefix(1);
      check_prebound(plan, name);
      if (b.value == kUnbound) continue;
      // Also a sub-SELECT's own slot of the name: pre-binding holds in every
      // pattern (check_prebound made sure such a sub-SELECT projects it).
      for (Var v = 0; v < nv; ++v) {
        if (plan.var_names[v] != name) continue;
        row_[v] = b.value;
        pinned_[v] = 1;
      }
    }

    if (found == nullptr && plan.form == QueryForm::Ask) {
      bool any = false;
      run_ask(plan, &any);
      out->clear();
      out->rows = any ? 1 : 0;
      return;
    }
    if (found != nullptr) {
      run_ask(plan, found);
      return;
    }
    collect(plan, *out);
  }

  void run_ask(const Plan& plan, bool* found) {
    {
      *found = false;
      auto stop = [&]() {
        *found = true;
        return false;
      };
      eval(plan.root, Cont(stop));
    }
  }

 private:
  Prepared& prepare(const std::shared_ptr<const Plan>& plan_ptr) {
    auto it = prepared_.find(plan_ptr.get());
    if (it != prepared_.end()) return *it->second;
    const Plan& plan = *plan_ptr;
    auto p = std::make_unique<Prepared>();
    p->plan = plan_ptr;  // keeps the address from being reused while cached
    p->consts.resize(plan.terms.size(), TermId::default_graph());
    for (uint32_t i = 1; i < plan.terms.size(); ++i) p->consts[i] = import(plan.terms, TermId{i});
    for (const PathPtr& path : plan.paths) p->paths.push_back(map_path(*path, p->consts));
    p->counts.resize(plan.ops.size());
    p->state.resize(plan.ops.size());
    for (size_t o = 0; o < plan.ops.size(); ++o) {
      const Op& op = plan.ops[o];
      if (op.kind != OpKind::Bgp) continue;
      auto constant = [&](const Slot& s) { return s.is_var ? TermId::any() : p->consts[s.value]; };
      for (const PatternElem& e : op.elems) {
        double c = 0;
        if (e.path < 0)
          c = static_cast<double>(
              data_.count(constant(e.s), constant(e.p), constant(e.o), TermId::any(), kCountCap));
        p->counts[o].push_back(c);
      }
      OpState& st = p->state[o];
      st.order.resize(op.elems.size());
      st.used.resize(op.elems.size());
      st.level_filters.resize(op.elems.size() + 1);
      st.buffers.resize(op.elems.size());
    }
    Prepared& ref = *p;
    prepared_.emplace(plan_ptr.get(), std::move(p));
    return ref;
  }

  static PathPtr map_path(const Path& path, const std::vector<TermId>& consts) {
    auto out = std::make_shared<Path>();
    out->kind = path.kind;
    if (path.kind == Path::Kind::Predicate) out->predicate = consts[path.predicate.index];
    for (TermId t : path.negated) out->negated.push_back(consts[t.index]);
    for (TermId t : path.negated_inverse) out->negated_inverse.push_back(consts[t.index]);
    for (const PathPtr& item : path.items) out->items.push_back(map_path(*item, consts));
    return out;
  }

  // ---- results ----
  struct RowHash {
    const std::vector<TermId>* cells;
    size_t width;
    size_t operator()(size_t r) const {
      uint64_t h = 0x9E3779B97F4A7C15ull;
      for (size_t c = 0; c < width; ++c) h = (h ^ (*cells)[r * width + c].index) * 0x100000001B3ull;
      return static_cast<size_t>(h ^ (h >> 29));
    }
  };
  struct RowEq {
    const std::vector<TermId>* cells;
    size_t width;
    bool operator()(size_t a, size_t b) const {
      for (size_t c = 0; c < width; ++c)
        if ((*cells)[a * width + c] != (*cells)[b * width + c]) return false;
      return true;
    }
  };

  void collect(const Plan& plan, ResultSet& out) {
    out.clear();
    out.variables = plan.result_names;
    out.rows = collect_rows(plan, out.cells);
  }

  // The solutions of a query or sub-SELECT (S: Plan or Select), projected,
  // ordered, made distinct and sliced, appended to `cells`; returns how many.
  template <class S>
  size_t collect_rows(const S& plan, std::vector<TermId>& cells) {
    const size_t width = plan.result_vars.size();
    if (plan.limit == 0) return 0;
    // Only DISTINCT needs the set (no allocation per call otherwise).
    std::unordered_set<size_t, RowHash, RowEq> seen(0, RowHash{&cells, width},
                                                    RowEq{&cells, width});
    const bool ordered = !plan.order.empty();
    const size_t wanted = plan.limit < 0 ? SIZE_MAX : static_cast<size_t>(plan.offset + plan.limit);
    std::vector<TermId> keys;
    size_t rows = 0;
    auto sink = [&]() {
      // SELECT expressions extend the solution (18.2.4.4); an error leaves the variable unbound.
      size_t extended = 0;
      for (const auto& [v, x] : plan.projected_exprs) {
        if (row_[v] != kUnbound) continue;
        row_[v] = eval_term(x);
        filled_.push_back(v);
        ++extended;
      }
      for (Var v : plan.result_vars) cells.push_back(row_[v]);
      bool keep = true;
      if (ordered) {
        for (const OrderKey& k : plan.order) keys.push_back(eval_term(k.expr));
      } else if (plan.distinct && !seen.insert(rows).second) {
        keep = false;
        cells.resize(cells.size() - width);
      }
      if (keep) budget_->rows(++rows);
      for (size_t i = 0; i < extended; ++i) {
        row_[filled_.back()] = kUnbound;
        filled_.pop_back();
      }
      return ordered || rows < wanted;
    };
    if (plan.grouping.active) {
      eval_grouped(plan.grouping, plan.root, sink);
    } else {
      eval(plan.root, Cont(sink));
    }

    if (ordered) {
      const size_t nk = plan.order.size();
      std::vector<size_t> perm(rows);
      for (size_t i = 0; i < rows; ++i) perm[i] = i;
      // A sort of millions of rows takes seconds without a step of its own.
      uint64_t comparisons = 0;
      for (size_t n = rows; n > 1; n /= 2) comparisons += rows;
      budget_->bulk(Budget::Bulk::Sort, comparisons, [&] {
        std::stable_sort(perm.begin(), perm.end(), [&](size_t a, size_t b) {
          for (size_t k = 0; k < nk; ++k) {
            const int c = order(value_of(keys[a * nk + k]), value_of(keys[b * nk + k]));
            if (c != 0) return plan.order[k].descending ? c > 0 : c < 0;
          }
          return false;
        });
        return true;
      });
      std::vector<TermId> sorted;
      sorted.reserve(cells.size());
      for (size_t i : perm)
        sorted.insert(sorted.end(), cells.begin() + static_cast<ptrdiff_t>(i * width),
                      cells.begin() + static_cast<ptrdiff_t>((i + 1) * width));
      cells = std::move(sorted);
      if (plan.distinct) {
        seen.clear();
        size_t kept = 0;
        for (size_t i = 0; i < rows; ++i) {
          if (kept != i)
            std::copy_n(cells.begin() + static_cast<ptrdiff_t>(i * width), width,
                        cells.begin() + static_cast<ptrdiff_t>(kept * width));
          if (seen.insert(kept).second) ++kept;
        }
        rows = kept;
        cells.resize(rows * width);
      }
    }
    const size_t first = std::min(rows, static_cast<size_t>(plan.offset));
    size_t last = rows;
    if (plan.limit >= 0) last = std::min(rows, first + static_cast<size_t>(plan.limit));
    if (first > 0 || last < rows) {
      cells.erase(cells.begin() + static_cast<ptrdiff_t>(last * width), cells.end());
      cells.erase(cells.begin(), cells.begin() + static_cast<ptrdiff_t>(first * width));
    }
    return last - first;
  }

  // GROUP BY (18.2.4.1): the solutions of `root` in groups of equal keys
  // (unbound is a key value of its own), in the order of each group's first
  // solution; without GROUP BY, one group, even of no solutions. Each group's
  // one solution binds its keys and aggregates and is passed to `emit`.
  template <class F>
  void eval_grouped(const Grouping& g, uint32_t root, F& emit) {
    const size_t nk = g.keys.size(), na = g.aggregates.size();
    std::map<std::vector<TermId>, size_t> index;
    std::vector<const std::vector<TermId>*> keys;  // by group
    std::vector<std::vector<TermId>> values;       // by group * na + aggregate
    std::vector<TermId> key(nk);
    auto add = [&]() {
      budget_->tick();
      for (size_t i = 0; i < nk; ++i) key[i] = row_[g.keys[i]];
      auto [it, fresh] = index.try_emplace(key, keys.size());
      if (fresh) {
        keys.push_back(&it->first);
        values.resize(values.size() + na);
      }
      // An element that is an error (kUnbound) makes its aggregate one.
      for (size_t a = 0; a < na; ++a)
        values[it->second * na + a].push_back(eval_term(g.aggregates[a].expr));
      return true;
    };
    eval(root, Cont(add));
    if (keys.empty() && nk == 0) {
      keys.push_back(&index.try_emplace(key, 0).first->first);
      values.resize(na);
    }
    for (size_t grp = 0; grp < keys.size(); ++grp) {
      const size_t mark = filled_.size(), arena = arena_used_;
      auto bind = [&](Var v, TermId value) {
        if (value == kUnbound || row_[v] != kUnbound) return;
        row_[v] = value;
        filled_.push_back(v);
      };
      for (size_t i = 0; i < nk; ++i) bind(g.keys[i], (*keys[grp])[i]);
      for (size_t a = 0; a < na; ++a)
        bind(g.aggregates[a].var, group_concat(g.aggregates[a], values[grp * na + a]));
      const bool cont = emit();
      while (filled_.size() > mark) {
        row_[filled_.back()] = kUnbound;
        filled_.pop_back();
      }
      arena_used_ = arena;
      if (!cont) return;
    }
  }

  // GROUP_CONCAT (18.5.1.7) with CONCAT's typing: every element a string (the
  // language tag kept when all share it), else an error (kUnbound). SPARQL
  // leaves the order open; the strings are sorted by code point (then
  // language tag) so the result does not depend on the join order the
  // evaluator picks. DISTINCT keeps one of equal terms.
  TermId group_concat(const Aggregate& agg, std::vector<TermId>& elements) {
    std::vector<Value> vs;
    vs.reserve(elements.size());
    for (TermId id : elements) {
      Value v = value_of(id);
      if (!stringish(v)) return kUnbound;
      vs.push_back(v);
    }
    auto less = [](const Value& a, const Value& b) {
      if (a.str != b.str) return a.str < b.str;
      if (a.lang != b.lang) return a.lang < b.lang;
      return a.id < b.id;
    };
    budget_->bulk(Budget::Bulk::Sort, vs.size() * 2, [&] {
      std::sort(vs.begin(), vs.end(), less);
      return true;
    });
    if (agg.distinct)
      vs.erase(std::unique(vs.begin(), vs.end(),
                           [](const Value& a, const Value& b) { return a.id == b.id; }),
               vs.end());
    std::string text;
    std::string_view lang = vs.empty() ? std::string_view() : vs.front().lang;
    for (size_t i = 0; i < vs.size(); ++i) {
      if (i > 0) text += agg.separator;
      text += vs[i].str;
      budget_->bytes(vs[i].str.size() + agg.separator.size());
      if (vs[i].lang != lang) lang = {};
    }
    return to_term(Value::string(store(std::move(text)), lang));
  }

  // ---- ops ----
  bool eval(uint32_t op_index, Cont k) {
    const Op& op = plan_->ops[op_index];
    const size_t base = saved_.size();
    for (Var v : op.hide) {
      if (row_[v] != kUnbound && pinned_[v] == 0) {
        saved_.emplace_back(v, row_[v]);
        row_[v] = kUnbound;
      }
    }
    const size_t top = saved_.size();
    bool result;
    if (top == base) {
      result = eval_inner(op_index, k);
    } else {
      // The op's solutions are joined with the hidden bindings.
      auto rejoin = [&]() {
        for (size_t i = base; i < top; ++i) {
          const auto [v, value] = saved_[i];
          if (row_[v] != kUnbound && row_[v] != value) return true;
        }
        const size_t mark = filled_.size();
        for (size_t i = base; i < top; ++i) {
          const auto [v, value] = saved_[i];
          if (row_[v] == kUnbound) {
            row_[v] = value;
            filled_.push_back(v);
          }
        }
        const bool cont = k();
        while (filled_.size() > mark) {
          row_[filled_.back()] = kUnbound;
          filled_.pop_back();
        }
        return cont;
      };
      result = eval_inner(op_index, Cont(rejoin));
    }
    for (size_t i = base; i < top; ++i) row_[saved_[i].first] = saved_[i].second;
    saved_.resize(base);
    return result;
  }

  bool eval_inner(uint32_t op_index, Cont k) {
    const Op& op = plan_->ops[op_index];
    switch (op.kind) {
      case OpKind::Bgp:
        return eval_bgp(op_index, k);
      case OpKind::Group:
        return eval_steps(op, 0, k);
      case OpKind::Union:
        for (uint32_t c : op.children)
          if (!eval(c, k)) return false;
        return true;
      case OpKind::SubSelect:
        return eval_sub_select(op.select, k);
    }
    return true;
  }

  // Evaluated on its own (eval() hid the input's bindings of its variables,
  // except pinned ones), then each solution joined with the input. Its own
  // slots see only the pre-bound values, the same for the whole run, so its
  // solutions are computed once per run however often the join asks.
  bool eval_sub_select(uint32_t index, Cont k) {
    const Select& sel = plan_->selects[index];
    if (!sub_ready_[index]) {
      std::vector<TermId> cells;
      const size_t n = collect_rows(sel, cells);
      sub_rows_[index] = std::move(cells);
      sub_counts_[index] = n;
      sub_ready_[index] = 1;
    }
    const std::vector<TermId>& cells = sub_rows_[index];
    const size_t rows = sub_counts_[index];
    const size_t width = sel.result_vars.size();
    for (size_t r = 0; r < rows; ++r) {
      budget_->tick();
      const size_t mark = filled_.size();
      bool compatible = true;
      for (size_t c = 0; c < width && compatible; ++c) {
        const TermId value = cells[r * width + c];
        if (value == kUnbound) continue;
        const Var v = sel.outer_vars[c];
        if (row_[v] == kUnbound) {
          row_[v] = value;
          filled_.push_back(v);
        } else {
          compatible = row_[v] == value;
        }
      }
      const bool cont = !compatible || k();
      while (filled_.size() > mark) {
        row_[filled_.back()] = kUnbound;
        filled_.pop_back();
      }
      if (!cont) return false;
    }
    return true;
  }

  bool eval_steps(const Op& op, size_t i, Cont k) {
    if (i == op.steps.size()) return k();
    const Step& s = op.steps[i];
    auto next = [&]() { return eval_steps(op, i + 1, k); };
    switch (s.kind) {
      case Step::Kind::Filter:
        if (eval_ebv(s.expr) != Tri::True) return true;
        return next();
      case Step::Kind::Join:
        return eval(s.child, Cont(next));
      case Step::Kind::LeftJoin: {
        bool matched = false;
        auto right = [&]() {
          if (s.expr != kNone && eval_ebv(s.expr) != Tri::True) return true;
          matched = true;
          return next();
        };
        if (!eval(s.child, Cont(right))) return false;
        return matched || next();
      }
      case Step::Kind::Extend: {
        const TermId value = eval_term(s.expr);
        if (value == kUnbound) return next();  // an error leaves the variable unbound
        TermId& cell = row_[s.var];
        if (cell != kUnbound) return cell == value ? next() : true;
        cell = value;
        const bool cont = next();
        row_[s.var] = kUnbound;
        return cont;
      }
    }
    return true;
  }

  double estimate(const Op& op, const std::vector<double>& counts, size_t e) const {
    const PatternElem& pe = op.elems[e];
    auto bound_var = [&](const Slot& s) { return s.is_var && tmp_bound_[s.value] != 0; };
    auto known = [&](const Slot& s) { return !s.is_var || tmp_bound_[s.value] != 0; };
    if (pe.path >= 0) {
      if (known(pe.s)) return 10;
      if (known(pe.o)) return 20;
      return 1e15;
    }
    double c = counts[e];
    const bool sb = bound_var(pe.s), ob = bound_var(pe.o);
    if (sb && ob) {
      c = std::min(c, 1.0);
    } else if (sb) {
      c = std::min(c, 5.0);
    } else if (ob) {
      c = std::min(c, 25.0);
    }
    return c;
  }

  bool eval_bgp(uint32_t op_index, Cont k) {
    const Op& op = plan_->ops[op_index];
    OpState& st = P_->state[op_index];
    const std::vector<double>& counts = P_->counts[op_index];
    const size_t n = op.elems.size();
    for (Var v : op.vars) tmp_bound_[v] = row_[v] != kUnbound ? 1 : 0;
    std::fill(st.used.begin(), st.used.end(), 0);
    for (size_t level = 0; level < n; ++level) {
      size_t best = 0;
      double best_cost = 0;
      bool have = false;
      for (size_t e = 0; e < n; ++e) {
        if (st.used[e] != 0) continue;
        const double c = estimate(op, counts, e);
        if (!have || c < best_cost) {
          best = e;
          best_cost = c;
          have = true;
        }
      }
      st.used[best] = 1;
      st.order[level] = static_cast<uint32_t>(best);
      const PatternElem& pe = op.elems[best];
      for (const Slot* s : {&pe.s, &pe.p, &pe.o}) {
        if (!s->is_var || (s == &pe.p && pe.path >= 0) || tmp_bound_[s->value] != 0) continue;
        tmp_bound_[s->value] = 1;
        level_of_[s->value] = static_cast<int32_t>(level);
      }
    }
    for (auto& lf : st.level_filters) lf.clear();
    for (uint32_t f : op.filters) {
      int32_t level = -1;
      for (Var v : plan_->expr_vars[f]) level = std::max(level, level_of_[v]);
      st.level_filters[static_cast<size_t>(level + 1)].push_back(f);
    }
    for (Var v : op.vars) {
      tmp_bound_[v] = 0;
      level_of_[v] = -1;
    }
    for (uint32_t f : st.level_filters[0])
      if (eval_ebv(f) != Tri::True) return true;
    return bgp_level(op, st, 0, k);
  }

  bool filters_pass(const OpState& st, size_t level) {
    for (uint32_t f : st.level_filters[level + 1])
      if (eval_ebv(f) != Tri::True) return false;
    return true;
  }

  TermId slot_value(const Slot& s) const { return s.is_var ? row_[s.value] : P_->consts[s.value]; }

  // Binds a variable slot to `value` (or checks it); records what it bound.
  bool bind(const Slot& s, TermId value, Var* bound, int& nbound) {
    if (!s.is_var) return true;  // constants were part of the lookup
    TermId& cell = row_[s.value];
    if (cell == kUnbound) {
      cell = value;
      bound[nbound++] = s.value;
      return true;
    }
    return cell == value;
  }

  // With several graphs, the default graph is their union as a set of triples:
  // a triple is reported at its first occurrence only.
  // Remembered per quad (the dataset does not change under an evaluator, and
  // SHACL's queries scan the same quads again and again).
  bool duplicate(const rdf::Quad& q, uint32_t index) const {
    if (duplicate_.size() != data_.size()) duplicate_.assign(data_.size(), kUnknown);
    uint8_t& known = duplicate_[index];
    if (known != kUnknown) return known == kDuplicate;
    bool earlier = false;
    data_.scan(q.subject, q.predicate, q.object, TermId::any(), [&](const rdf::Quad&, uint32_t i) {
      earlier = i < index;
      return !earlier;
    });
    known = earlier ? kDuplicate : kFirst;
    return earlier;
  }

  bool bgp_level(const Op& op, OpState& st, size_t level, Cont k) {
    if (level == op.elems.size()) return k();
    const PatternElem& pe = op.elems[st.order[level]];
    const TermId s = slot_value(pe.s), o = slot_value(pe.o);
    const TermId s_key = s == kUnbound ? TermId::any() : s;
    const TermId o_key = o == kUnbound ? TermId::any() : o;
    bool cont = true;
    budget_->tick();  // the lookup itself, for scans that match nothing
    if (pe.path < 0) {
      const TermId p = slot_value(pe.p);
      data_.scan(s_key, p == kUnbound ? TermId::any() : p, o_key, TermId::any(),
                 [&](const rdf::Quad& q, uint32_t index) {
                   budget_->tick();
                   if (multi_graph_ && duplicate(q, index)) return true;
                   Var bound[3];
                   int nbound = 0;
                   if (bind(pe.s, q.subject, bound, nbound) &&
                       bind(pe.p, q.predicate, bound, nbound) &&
                       bind(pe.o, q.object, bound, nbound) && filters_pass(st, level))
                     cont = bgp_level(op, st, level + 1, k);
                   while (nbound > 0) row_[bound[--nbound]] = kUnbound;
                   return cont;
                 });
      return cont;
    }
    const Path& path = *P_->paths[static_cast<size_t>(pe.path)];
    std::vector<TermId>& buffer = st.buffers[level];
    auto each_end = [&](const Slot& end_slot, TermId start_value) {
      for (size_t i = 0; i < buffer.size() && cont; ++i) {
        budget_->tick();
        Var bound[3];
        int nbound = 0;
        if (bind(end_slot, buffer[i], bound, nbound) && filters_pass(st, level))
          cont = bgp_level(op, st, level + 1, k);
        while (nbound > 0) row_[bound[--nbound]] = kUnbound;
      }
      (void)start_value;
    };
    if (s != kUnbound) {
      evaluate_path(data_, path, s, buffer, TermId::any(), budget_, &path_workspace_);
      each_end(pe.o, s);
    } else if (o != kUnbound) {
      evaluate_path_inverse(data_, path, o, buffer, TermId::any(), budget_, &path_workspace_);
      each_end(pe.s, o);
    } else {
      // Neither end known: every node of the graph is a start (zero-length
      // paths match every subject and object).
      for (TermId start : all_nodes()) {
        if (!cont) break;
        evaluate_path(data_, path, start, buffer, TermId::any(), budget_, &path_workspace_);
        Var bound[3];
        int nbound = 0;
        if (bind(pe.s, start, bound, nbound)) each_end(pe.o, start);
        while (nbound > 0) row_[bound[--nbound]] = kUnbound;
      }
    }
    return cont;
  }

  const std::vector<TermId>& all_nodes() {
    if (!all_nodes_ready_) {
      std::vector<uint8_t> seen(data_.terms().size(), 0);
      for (const rdf::Quad& q : data_.quads()) {
        for (TermId t : {q.subject, q.object}) {
          if (seen[t.index] == 0) {
            seen[t.index] = 1;
            all_nodes_.push_back(t);
          }
        }
      }
      all_nodes_ready_ = true;
    }
    return all_nodes_;
  }

  // ---- expressions ----
  std::string_view store(std::string text) {
    if (arena_used_ == arena_.size()) arena_.emplace_back();
    std::string& slot = arena_[arena_used_++];
    slot = std::move(text);
    return slot;
  }

  Tri eval_ebv(uint32_t e) {
    const size_t mark = arena_used_;
    const Tri r = ebv(eval_expr(e));
    arena_used_ = mark;
    return r;
  }
  TermId eval_term(uint32_t e) {
    const size_t mark = arena_used_;
    const TermId r = to_term(eval_expr(e));
    arena_used_ = mark;
    return r;
  }

  Value value_of(TermId id) const {
    if (id == kUnbound) return Value::make_error();
    auto [table, local] = locate(id);
    const rdf::Term& t = (*table)[local];
    Value v;
    v.id = id;
    v.str = t.value;
    switch (t.kind) {
      case rdf::TermKind::Iri:
        v.kind = Value::Kind::Iri;
        return v;
      case rdf::TermKind::Blank:
        v.kind = Value::Kind::Blank;
        return v;
      case rdf::TermKind::Literal: {
        if (id.index >= kConstTier) {
          return decode_literal(t.value, (*table)[t.datatype].value, t.language, id);
        }
        auto it = decoded_.find(id.index);
        if (it == decoded_.end()) {
          it = decoded_
                   .emplace(id.index,
                            decode_literal(t.value, (*table)[t.datatype].value, t.language, id))
                   .first;
        }
        return it->second;
      }
      default:
        return Value::make_error();
    }
  }

  TermId to_term(const Value& v) {
    if (!v.id.is_any()) return v.id;
    switch (v.kind) {
      case Value::Kind::Error:
        return kUnbound;
      case Value::Kind::Iri:
        return intern_iri(v.str);
      case Value::Kind::Blank:
        return kUnbound;  // blank nodes always come with an id
      case Value::Kind::String:
        return intern_literal(v.str, kXsdStringIri, {});
      case Value::Kind::LangString:
        return intern_literal(v.str, kRdfLangString, v.lang);
      case Value::Kind::Numeric:
      case Value::Kind::Bool:
        return intern_literal(canonical_lexical(v), datatype_of(v), {});
      case Value::Kind::DateTime:
      case Value::Kind::Literal:
        return intern_literal(v.str, v.datatype, {});
    }
    return kUnbound;
  }

  // The lexical form of a literal value (canonical for computed numbers).
  std::string_view lexical(const Value& v) {
    if ((v.kind == Value::Kind::Numeric || v.kind == Value::Kind::Bool) && v.id.is_any())
      return store(canonical_lexical(v));
    return v.str;
  }
  // CONTAINS in time linear in both strings (std::string_view::find can take
  // their product: "aaa...ab" in "aaa...a").
  static bool contains(std::string_view text, std::string_view needle) {
    if (needle.size() < 16) return text.find(needle) != std::string_view::npos;
    return std::search(text.begin(), text.end(),
                       std::boyer_moore_searcher(needle.begin(), needle.end())) != text.end();
  }
  static bool stringish(const Value& v) {
    return v.kind == Value::Kind::String || v.kind == Value::Kind::LangString;
  }

  Value eval_expr(uint32_t index) {
    const Expr& e = plan_->exprs[index];
    auto arg = [&](size_t i) { return eval_expr(e.args[i]); };
    switch (e.op) {
      case ExprOp::Const:
        return value_of(P_->consts[e.value]);
      case ExprOp::Var:
        return value_of(row_[e.value]);
      case ExprOp::Or: {
        const Tri a = ebv(arg(0));
        if (a == Tri::True) return Value::boolean(true);
        const Tri b = ebv(arg(1));
        if (b == Tri::True) return Value::boolean(true);
        if (a == Tri::False && b == Tri::False) return Value::boolean(false);
        return Value::make_error();
      }
      case ExprOp::And: {
        const Tri a = ebv(arg(0));
        if (a == Tri::False) return Value::boolean(false);
        const Tri b = ebv(arg(1));
        if (b == Tri::False) return Value::boolean(false);
        if (a == Tri::True && b == Tri::True) return Value::boolean(true);
        return Value::make_error();
      }
      case ExprOp::Not: {
        const Tri a = ebv(arg(0));
        if (a == Tri::Error) return Value::make_error();
        return Value::boolean(a == Tri::False);
      }
      case ExprOp::Eq:
      case ExprOp::Ne: {
        const Tri t = term_equal(e);
        if (t == Tri::Error) return Value::make_error();
        return Value::boolean((t == Tri::True) == (e.op == ExprOp::Eq));
      }
      case ExprOp::Lt:
      case ExprOp::Gt:
      case ExprOp::Le:
      case ExprOp::Ge: {
        const int c = compare(arg(0), arg(1));
        if (c == 3) return Value::make_error();
        if (c == 2) return Value::boolean(false);
        switch (e.op) {
          case ExprOp::Lt:
            return Value::boolean(c < 0);
          case ExprOp::Gt:
            return Value::boolean(c > 0);
          case ExprOp::Le:
            return Value::boolean(c <= 0);
          default:
            return Value::boolean(c >= 0);
        }
      }
      case ExprOp::In:
      case ExprOp::NotIn: {
        const Value x = arg(0);
        if (x.error()) return Value::make_error();
        bool error = false;
        for (size_t i = 1; i < e.args.size(); ++i) {
          const Tri t = equal(x, arg(i));
          if (t == Tri::True) return Value::boolean(e.op == ExprOp::In);
          if (t == Tri::Error) error = true;
        }
        if (error) return Value::make_error();
        return Value::boolean(e.op == ExprOp::NotIn);
      }
      case ExprOp::Add:
        return arithmetic('+', arg(0), arg(1));
      case ExprOp::Sub:
        return arithmetic('-', arg(0), arg(1));
      case ExprOp::Mul:
        return arithmetic('*', arg(0), arg(1));
      case ExprOp::Div:
        return arithmetic('/', arg(0), arg(1));
      case ExprOp::Neg: {
        Value v = arg(0);
        if (v.kind != Value::Kind::Numeric) return Value::make_error();
        if (v.num == Num::Integer) {
          if (v.i == INT64_MIN) return Value::make_error();
          return Value::integer(-v.i);
        }
        return Value::number(v.num, -v.d);
      }
      case ExprOp::Plus: {
        Value v = arg(0);
        if (v.kind != Value::Kind::Numeric) return Value::make_error();
        return v;
      }
      case ExprOp::Exists:
      case ExprOp::NotExists: {
        const bool found = exists(e.value);
        return Value::boolean(found == (e.op == ExprOp::Exists));
      }
      case ExprOp::Bound:
        return Value::boolean(row_[plan_->exprs[e.args[0]].value] != kUnbound);
      case ExprOp::If: {
        const Tri c = ebv(arg(0));
        if (c == Tri::Error) return Value::make_error();
        return c == Tri::True ? arg(1) : arg(2);
      }
      case ExprOp::Coalesce:
        for (size_t i = 0; i < e.args.size(); ++i) {
          Value v = arg(i);
          if (!v.error()) return v;
        }
        return Value::make_error();
      case ExprOp::Abs:
      case ExprOp::Ceil:
      case ExprOp::Floor:
      case ExprOp::Round: {
        Value v = arg(0);
        if (v.kind != Value::Kind::Numeric) return Value::make_error();
        if (v.num == Num::Integer) {
          if (e.op == ExprOp::Abs && v.i < 0) {
            if (v.i == INT64_MIN) return Value::make_error();
            return Value::integer(-v.i);
          }
          return Value::integer(v.i);
        }
        long double r = v.d;
        switch (e.op) {
          case ExprOp::Abs:
            r = std::fabs(r);
            break;
          case ExprOp::Ceil:
            r = std::ceil(r);
            break;
          case ExprOp::Floor:
            r = std::floor(r);
            break;
          default:
            r = std::floor(r + 0.5L);
            break;  // fn:round: halves toward +INF
        }
        return Value::number(v.num, r);
      }
      case ExprOp::IsIri:
      case ExprOp::IsBlank:
      case ExprOp::IsLiteral:
      case ExprOp::IsNumeric: {
        const Value v = arg(0);
        if (v.error()) return Value::make_error();
        switch (e.op) {
          case ExprOp::IsIri:
            return Value::boolean(v.kind == Value::Kind::Iri);
          case ExprOp::IsBlank:
            return Value::boolean(v.kind == Value::Kind::Blank);
          case ExprOp::IsLiteral:
            return Value::boolean(v.is_literal());
          default:
            return Value::boolean(v.kind == Value::Kind::Numeric);
        }
      }
      case ExprOp::Str:
      case ExprOp::CastString: {
        const Value v = arg(0);
        if (v.kind == Value::Kind::Iri) return Value::string(v.str);
        if (!v.is_literal()) return Value::make_error();
        return Value::string(lexical(v));
      }
      case ExprOp::Lang: {
        const Value v = arg(0);
        if (!v.is_literal()) return Value::make_error();
        return Value::string(v.lang);
      }
      case ExprOp::Datatype: {
        const Value v = arg(0);
        if (!v.is_literal()) return Value::make_error();
        Value r;
        r.kind = Value::Kind::Iri;
        switch (v.kind) {
          case Value::Kind::String:
            r.str = kXsdStringIri;
            break;
          case Value::Kind::LangString:
            r.str = kRdfLangString;
            break;
          case Value::Kind::Numeric:
          case Value::Kind::Bool:
            r.str = v.id.is_any() ? datatype_of(v) : v.datatype;
            break;
          default:
            r.str = v.datatype;
            break;
        }
        return r;
      }
      case ExprOp::Iri: {
        const Value v = arg(0);
        if (v.kind == Value::Kind::Iri) return v;
        if (v.kind != Value::Kind::String) return Value::make_error();
        Value r;
        r.kind = Value::Kind::Iri;
        r.str = plan_->base.empty() || rdf::is_absolute_iri(v.str)
                    ? v.str
                    : store(rdf::resolve_iri(plan_->base, v.str));
        return r;
      }
      case ExprOp::Regex:
        return regex(e);
      case ExprOp::StrStarts:
      case ExprOp::StrEnds:
      case ExprOp::Contains: {
        const Value a = arg(0), b = arg(1);
        if (!stringish(a) || !stringish(b)) return Value::make_error();
        // Argument compatibility (17.4.3.1.2): b's language, if any, must be a's.
        if (!b.lang.empty() && a.lang != b.lang) return Value::make_error();
        budget_->bytes(a.str.size() + b.str.size());
        switch (e.op) {
          case ExprOp::StrStarts:
            return Value::boolean(a.str.starts_with(b.str));
          case ExprOp::StrEnds:
            return Value::boolean(a.str.ends_with(b.str));
          default:
            return Value::boolean(contains(a.str, b.str));
        }
      }
      case ExprOp::StrLen: {
        const Value v = arg(0);
        if (!stringish(v)) return Value::make_error();
        budget_->bytes(v.str.size());
        int64_t n = 0;
        for (char c : v.str)
          if ((static_cast<unsigned char>(c) & 0xC0) != 0x80) ++n;
        return Value::integer(n);
      }
      case ExprOp::Ucase:
      case ExprOp::Lcase: {
        const Value v = arg(0);
        if (!stringish(v)) return Value::make_error();
        budget_->bytes(v.str.size());
        std::string s(v.str);
        for (char& c : s)
          c = static_cast<char>(e.op == ExprOp::Ucase
                                    ? std::toupper(static_cast<unsigned char>(c))
                                    : std::tolower(static_cast<unsigned char>(c)));
        return Value::string(store(std::move(s)), v.lang);
      }
      case ExprOp::Concat: {
        std::string s;
        std::string_view lang;
        bool same_lang = true;
        for (size_t i = 0; i < e.args.size(); ++i) {
          const Value v = arg(i);
          if (!stringish(v)) return Value::make_error();
          budget_->bytes(v.str.size());
          if (i == 0) {
            lang = v.lang;
          } else if (v.lang != lang) {
            same_lang = false;
          }
          s += v.str;
        }
        return Value::string(store(std::move(s)), same_lang ? lang : std::string_view());
      }
      case ExprOp::LangMatches: {
        const Value tag = arg(0), range = arg(1);
        if (tag.kind != Value::Kind::String || range.kind != Value::Kind::String)
          return Value::make_error();
        if (range.str == "*") return Value::boolean(!tag.str.empty());
        if (tag.str.size() < range.str.size()) return Value::boolean(false);
        for (size_t i = 0; i < range.str.size(); ++i)
          if (std::tolower(static_cast<unsigned char>(tag.str[i])) !=
              std::tolower(static_cast<unsigned char>(range.str[i])))
            return Value::boolean(false);
        return Value::boolean(tag.str.size() == range.str.size() ||
                              tag.str[range.str.size()] == '-');
      }
      case ExprOp::SameTerm: {
        const TermId a = to_term(arg(0)), b = to_term(arg(1));
        if (a == kUnbound || b == kUnbound) return Value::make_error();
        return Value::boolean(a == b);
      }
      case ExprOp::CastInteger:
      case ExprOp::CastDecimal:
      case ExprOp::CastDouble:
      case ExprOp::CastFloat:
      case ExprOp::CastBoolean:
        return cast(e.op, arg(0));
    }
    return Value::make_error();
  }

  // '=' with a shortcut for terms: two ids that differ and are not both
  // literals are different terms, with no decoding needed.
  Tri term_equal(const Expr& e) {
    const Expr& a = plan_->exprs[e.args[0]];
    const Expr& b = plan_->exprs[e.args[1]];
    auto id_of = [&](const Expr& x) {
      if (x.op == ExprOp::Var) return row_[x.value];
      if (x.op == ExprOp::Const) return P_->consts[x.value];
      return TermId::any();
    };
    const TermId ia = id_of(a), ib = id_of(b);
    if (!ia.is_any() && !ib.is_any()) {
      const bool la = term(ia).is_literal(), lb = term(ib).is_literal();
      if (!la || !lb) return tri(ia == ib);
    }
    return equal(eval_expr(e.args[0]), eval_expr(e.args[1]));
  }

  Value cast(ExprOp op, const Value& v) {
    auto from_string = [&](std::string_view datatype) {
      Value r = decode_literal(v.str, datatype, {}, TermId::any());
      return r.kind == Value::Kind::Numeric || r.kind == Value::Kind::Bool ? r
                                                                           : Value::make_error();
    };
    const Num target = op == ExprOp::CastInteger   ? Num::Integer
                       : op == ExprOp::CastDecimal ? Num::Decimal
                       : op == ExprOp::CastFloat   ? Num::Float
                                                   : Num::Double;
    if (v.kind == Value::Kind::String) {
      switch (op) {
        case ExprOp::CastInteger:
          return from_string(vocab::xsd::integer);
        case ExprOp::CastDecimal:
          return from_string(vocab::xsd::decimal);
        case ExprOp::CastFloat:
          return from_string(vocab::xsd::float_);
        case ExprOp::CastDouble:
          return from_string(vocab::xsd::double_);
        default:
          return from_string(vocab::xsd::boolean);
      }
    }
    if (v.kind == Value::Kind::Bool) {
      if (op == ExprOp::CastBoolean) return Value::boolean(v.b);
      return target == Num::Integer ? Value::integer(v.b ? 1 : 0)
                                    : Value::number(target, v.b ? 1 : 0);
    }
    if (v.kind != Value::Kind::Numeric) return Value::make_error();
    const long double x = v.as_long_double();
    if (op == ExprOp::CastBoolean) return Value::boolean(!(x == 0 || std::isnan(x)));
    if ((target == Num::Integer || target == Num::Decimal) && !std::isfinite(x))
      return Value::make_error();
    if (target == Num::Integer) {
      if (v.num == Num::Integer) return Value::integer(v.i);
      const long double t = std::trunc(x);
      if (t < -9.2e18L || t > 9.2e18L) return Value::make_error();
      return Value::integer(static_cast<int64_t>(t));
    }
    long double r = x;
    if (target == Num::Float) r = static_cast<float>(r);
    if (target == Num::Double) r = static_cast<double>(r);
    return Value::number(target, r);
  }

  Value regex(const Expr& e) {
    const Value text = eval_expr(e.args[0]);
    if (!stringish(text)) return Value::make_error();
    const Regex* re = nullptr;
    if (e.regex >= 0) {
      re = &plan_->regexes[static_cast<size_t>(e.regex)];
    } else {
      const Value pattern = eval_expr(e.args[1]);
      Value flags = Value::string("");
      if (e.args.size() > 2) flags = eval_expr(e.args[2]);
      if (pattern.kind != Value::Kind::String || flags.kind != Value::Kind::String)
        return Value::make_error();
      std::string key(flags.str);
      key += '\n';
      key += pattern.str;
      auto it = regex_cache_.find(key);
      if (it == regex_cache_.end()) {
        // Patterns computed per solution could grow the cache without bound.
        if (regex_cache_.size() >= kRegexCacheLimit) regex_cache_.clear();
        std::optional<Regex> entry;
        try {
          entry.emplace(pattern.str, flags.str);
        } catch (const RegexError&) {
          // An invalid computed pattern is an expression error (17.3).
        }
        it = regex_cache_.emplace(std::move(key), std::move(entry)).first;
      }
      if (!it->second) return Value::make_error();
      re = &*it->second;
    }
    // RE2 is linear in the text: its cost is the text's length, charged (and
    // checked against the time left) before the match starts.
    return Value::boolean(budget_->regex(text.str.size(), [&] { return re->search(text.str); }));
  }

  bool exists(uint32_t op_index) {
    // Substitution (17.4.1.4): everything bound now holds inside the pattern.
    const size_t mark = pins_.size();
    for (Var v = 0; v < row_.size(); ++v) {
      if (row_[v] != kUnbound && pinned_[v] == 0) {
        pinned_[v] = 1;
        pins_.push_back(v);
      }
    }
    bool found = false;
    auto stop = [&]() {
      found = true;
      return false;
    };
    eval(op_index, Cont(stop));
    while (pins_.size() > mark) {
      pinned_[pins_.back()] = 0;
      pins_.pop_back();
    }
    return found;
  }

  const rdf::Dataset& data_;
  bool multi_graph_ = false;
  rdf::TermTable constants_;  // query constants and imported terms the data lacks
  rdf::TermTable computed_;   // terms computed by expressions
  std::unordered_map<const Plan*, std::unique_ptr<Prepared>> prepared_;
  std::unordered_map<std::string, std::optional<Regex>> regex_cache_;
  std::vector<TermId> all_nodes_;
  bool all_nodes_ready_ = false;
  // The dataset's literals as decoded so far (numbers parsed, datatypes
  // checked): decode_literal depends on the term alone and the dataset does
  // not change under an evaluator, while SHACL runs hundreds of queries over
  // the same values.
  mutable std::unordered_map<uint32_t, Value> decoded_;
  // By quad index: whether an earlier quad states the same triple (duplicate()).
  static constexpr uint8_t kUnknown = 0, kFirst = 1, kDuplicate = 2;
  mutable std::vector<uint8_t> duplicate_;
  Limits limits_;
  Budget* shared_budget_ = nullptr;
  PathWorkspace path_workspace_;  // buffers every property path reuses

  // Per evaluation.
  std::optional<Budget> own_budget_;
  Budget* budget_ = nullptr;  // the shared budget, else own_budget_
  Prepared* P_ = nullptr;
  const Plan* plan_ = nullptr;
  std::vector<TermId> row_;
  std::vector<uint8_t> pinned_;
  std::vector<Var> pins_;
  std::vector<uint8_t> tmp_bound_;
  std::vector<int32_t> level_of_;
  std::vector<std::pair<Var, TermId>> saved_;
  std::vector<Var> filled_;
  std::deque<std::string> arena_;
  size_t arena_used_ = 0;
  // Sub-SELECT solutions of this run, by Plan::selects index.
  std::vector<uint8_t> sub_ready_;
  std::vector<std::vector<TermId>> sub_rows_;
  std::vector<size_t> sub_counts_;
};

}  // namespace detail

// ---- public API ----

QueryForm Query::form() const {
  return plan_->form;
}
const std::vector<std::string>& Query::variables() const {
  return plan_->result_names;
}
bool Query::mentions(std::string_view name) const {
  return plan_->names(name);
}
std::string Query::algebra() const {
  return detail::to_sse(*plan_);
}

void Query::check_prebinding(std::span<const std::string_view> names) const {
  for (std::string_view name : names) {
    if (!name.empty() && (name[0] == '?' || name[0] == '$')) name.remove_prefix(1);
    detail::check_prebound(*plan_, name);
  }
}

Query parse_query(std::string_view text, const PrefixMap& prefixes, std::string_view base_iri) {
  return Query(detail::build_plan(ast::parse(text, prefixes, base_iri)));
}

int ResultSet::column(std::string_view name) const {
  for (size_t i = 0; i < variables.size(); ++i)
    if (variables[i] == name) return static_cast<int>(i);
  return -1;
}

Evaluator::Evaluator(const rdf::Dataset& data) : engine_(std::make_unique<detail::Engine>(data)) {}
Evaluator::~Evaluator() = default;
Evaluator::Evaluator(Evaluator&&) noexcept = default;
Evaluator& Evaluator::operator=(Evaluator&&) noexcept = default;

void Evaluator::select(const Query& query, std::span<const Binding> prebound, ResultSet& out) {
  engine_->run(query, prebound, &out, nullptr);
}

bool Evaluator::ask(const Query& query, std::span<const Binding> prebound) {
  bool found = false;
  engine_->run(query, prebound, nullptr, &found);
  return found;
}

std::pair<const rdf::TermTable*, TermId> Evaluator::locate(TermId id) const {
  return engine_->locate(id);
}
const rdf::Term& Evaluator::term(TermId id) const {
  return engine_->term(id);
}
std::string Evaluator::to_ntriples(TermId id) const {
  if (id == kUnbound) return "UNDEF";
  auto [table, local] = engine_->locate(id);
  return rdf::to_ntriples(*table, local);
}
TermId Evaluator::import(const rdf::TermTable& table, TermId id) {
  return engine_->import(table, id);
}
const rdf::Dataset& Evaluator::data() const {
  return engine_->data();
}
void Evaluator::set_limits(const Limits& limits) {
  engine_->set_limits(limits);
}
const Limits& Evaluator::limits() const {
  return engine_->limits();
}
void Evaluator::set_budget(Budget* budget) {
  engine_->set_budget(budget);
}

}  // namespace mospec::sparql
