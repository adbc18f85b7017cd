// Stage 2: syntax tree -> algebra (SPARQL 1.1 section 18.2).
#include "sparql/algebra.hpp"

#include <algorithm>
#include <unordered_map>

#include "vocab/w3c.hpp"

namespace mospec::sparql::detail {

namespace {

constexpr std::string_view kSyntax = "sparql-syntax";
constexpr std::string_view kUnsupported = "unsupported-sparql";
constexpr std::string_view kRdf = vocab::rdf::ns;
constexpr std::string_view kXsd = vocab::xsd::ns;

struct Builtin {
  const char* name;
  ExprOp op;
  int min_args, max_args;  // max -1: any number
};
constexpr Builtin kBuiltins[] = {
    {"BOUND", ExprOp::Bound, 1, 1},
    {"IF", ExprOp::If, 3, 3},
    {"COALESCE", ExprOp::Coalesce, 0, -1},
    {"ABS", ExprOp::Abs, 1, 1},
    {"CEIL", ExprOp::Ceil, 1, 1},
    {"FLOOR", ExprOp::Floor, 1, 1},
    {"ROUND", ExprOp::Round, 1, 1},
    {"ISIRI", ExprOp::IsIri, 1, 1},
    {"ISURI", ExprOp::IsIri, 1, 1},
    {"ISBLANK", ExprOp::IsBlank, 1, 1},
    {"ISLITERAL", ExprOp::IsLiteral, 1, 1},
    {"ISNUMERIC", ExprOp::IsNumeric, 1, 1},
    {"STR", ExprOp::Str, 1, 1},
    {"LANG", ExprOp::Lang, 1, 1},
    {"DATATYPE", ExprOp::Datatype, 1, 1},
    {"IRI", ExprOp::Iri, 1, 1},
    {"URI", ExprOp::Iri, 1, 1},
    {"REGEX", ExprOp::Regex, 2, 3},
    {"STRSTARTS", ExprOp::StrStarts, 2, 2},
    {"STRENDS", ExprOp::StrEnds, 2, 2},
    {"CONTAINS", ExprOp::Contains, 2, 2},
    {"STRLEN", ExprOp::StrLen, 1, 1},
    {"UCASE", ExprOp::Ucase, 1, 1},
    {"LCASE", ExprOp::Lcase, 1, 1},
    {"CONCAT", ExprOp::Concat, 0, -1},
    {"LANGMATCHES", ExprOp::LangMatches, 2, 2},
    {"SAMETERM", ExprOp::SameTerm, 2, 2},
};
constexpr const char* kKnownUnsupported[] = {
    "BNODE",     "RAND",     "NOW",      "UUID",    "STRUUID",        "MD5",     "SHA1",
    "SHA256",    "SHA384",   "SHA512",   "YEAR",    "MONTH",          "DAY",     "HOURS",
    "MINUTES",   "SECONDS",  "TIMEZONE", "TZ",      "ENCODE_FOR_URI", "REPLACE", "SUBSTR",
    "STRBEFORE", "STRAFTER", "STRDT",    "STRLANG",
};

struct Cast {
  const char* local;
  ExprOp op;
};
constexpr Cast kCasts[] = {
    {"string", ExprOp::CastString},   {"integer", ExprOp::CastInteger},
    {"decimal", ExprOp::CastDecimal}, {"double", ExprOp::CastDouble},
    {"float", ExprOp::CastFloat},     {"boolean", ExprOp::CastBoolean},
};

class Builder {
 public:
  explicit Builder(Plan& plan) : plan_(plan) {}

  void build(ast::Query& q) {
    plan_.form = q.form;
    plan_.base = q.base;
    plan_.distinct = q.distinct;
    plan_.limit = q.limit;
    plan_.offset = q.offset;
    // Projected variables are created first so that they keep low slots.
    for (const ast::Projection& pr : q.projection)
      if (!pr.has_expr) var(pr.var.value);
    plan_.root = group(q.where, nullptr);
    const VarSet& scope = scope_[plan_.root];
    if (q.form == QueryForm::Ask && !q.group_by.empty())
      ast::fail(kUnsupported, q.group_pos, "GROUP BY in an ASK query is not supported");
    if (q.form == QueryForm::Select) {
      project(q, scope, plan_.result_vars, plan_.result_names, plan_.projected_exprs,
              plan_.grouping);
    }
    for (const ast::OrderKey& k : q.order) plan_.order.push_back({expr(k.expr), k.descending});
  }

 private:
  // ---- variables and constants ----
  Var new_var(std::string name, bool hidden) {
    plan_.var_names.push_back(std::move(name));
    plan_.hidden.push_back(hidden);
    return static_cast<Var>(plan_.var_names.size() - 1);
  }
  Var var(const std::string& name) {
    auto it = vars_.find(name);
    if (it != vars_.end()) return it->second;
    const Var v = new_var(name, false);
    vars_.emplace(name, v);
    return v;
  }
  Var fresh() { return new_var("_:#" + std::to_string(fresh_count_++), true); }

  uint32_t constant(const ast::Term& t) {
    switch (t.kind) {
      case ast::Term::Kind::Iri:
      case ast::Term::Kind::Nil:
        return plan_.terms.iri(t.value).index;
      case ast::Term::Kind::Literal:
        if (!t.language.empty()) return plan_.terms.literal(t.value, {}, t.language).index;
        if (t.datatype.empty()) return plan_.terms.literal(t.value).index;
        return plan_.terms.literal(t.value, t.datatype).index;
      default:
        return 0;
    }
  }

  Slot slot(const ast::Term& t) {
    switch (t.kind) {
      case ast::Term::Kind::Var:
        return Slot{true, var(t.value)};
      case ast::Term::Kind::Blank: {
        if (t.value.empty()) return Slot{true, fresh()};
        auto it = blank_labels_.find(t.value);
        if (it != blank_labels_.end()) {
          if (it->second.second != bgp_serial_)
            ast::fail(kSyntax, t.pos,
                      "blank node _:" + t.value +
                          " is used in two different basic graph patterns (SPARQL 1.1, 4.1.4)");
          return Slot{true, it->second.first};
        }
        const Var v = new_var("_:" + t.value, true);
        blank_labels_.emplace(t.value, std::make_pair(v, bgp_serial_));
        return Slot{true, v};
      }
      default:
        return Slot{false, constant(t)};
    }
  }

  // ---- triples and paths ----
  PathPtr make_path(const ast::Path& p) {
    switch (p.kind) {
      case ast::Path::Kind::Iri:
        return Path::iri(plan_.terms.iri(p.value));
      case ast::Path::Kind::Negated: {
        auto neg = std::make_shared<Path>();
        neg->kind = Path::Kind::NegatedSet;
        for (const ast::Path& item : p.items) {
          if (item.kind == ast::Path::Kind::Inverse) {
            neg->negated_inverse.push_back(plan_.terms.iri(item.items[0].value));
          } else {
            neg->negated.push_back(plan_.terms.iri(item.value));
          }
        }
        return neg;
      }
      default: {
        std::vector<PathPtr> items;
        for (const ast::Path& item : p.items) items.push_back(make_path(item));
        Path::Kind k = Path::Kind::Sequence;
        switch (p.kind) {
          case ast::Path::Kind::Inverse:
            k = Path::Kind::Inverse;
            break;
          case ast::Path::Kind::Sequence:
            k = Path::Kind::Sequence;
            break;
          case ast::Path::Kind::Alternative:
            k = Path::Kind::Alternative;
            break;
          case ast::Path::Kind::ZeroOrMore:
            k = Path::Kind::ZeroOrMore;
            break;
          case ast::Path::Kind::OneOrMore:
            k = Path::Kind::OneOrMore;
            break;
          case ast::Path::Kind::ZeroOrOne:
            k = Path::Kind::ZeroOrOne;
            break;
          default:
            break;
        }
        return Path::make(k, std::move(items));
      }
    }
  }

  // 18.2.2.4: links and inverse links become triple patterns, sequences are
  // split with a fresh variable, everything else stays a path pattern.
  void add_path(Slot s, const ast::Path& p, Slot o, std::vector<PatternElem>& out) {
    switch (p.kind) {
      case ast::Path::Kind::Var:
        out.push_back(PatternElem{s, Slot{true, var(p.value)}, o, -1, p.pos});
        return;
      case ast::Path::Kind::Iri:
        out.push_back(PatternElem{s, Slot{false, plan_.terms.iri(p.value).index}, o, -1, p.pos});
        return;
      case ast::Path::Kind::Inverse: {
        const ast::Path& inner = p.items[0];
        if (inner.kind == ast::Path::Kind::Iri || inner.kind == ast::Path::Kind::Inverse ||
            inner.kind == ast::Path::Kind::Sequence) {
          if (inner.kind == ast::Path::Kind::Sequence) {
            // ^(a/b) = ^b/^a
            ast::Path seq{ast::Path::Kind::Sequence, {}, {}, inner.pos};
            for (auto it = inner.items.rbegin(); it != inner.items.rend(); ++it)
              seq.items.push_back(ast::Path{ast::Path::Kind::Inverse, {}, {*it}, it->pos});
            add_path(s, seq, o, out);
          } else {
            add_path(o, inner, s, out);
          }
          return;
        }
        break;
      }
      case ast::Path::Kind::Sequence: {
        Slot cur = s;
        for (size_t i = 0; i + 1 < p.items.size(); ++i) {
          Slot mid{true, fresh()};
          add_path(cur, p.items[i], mid, out);
          cur = mid;
        }
        add_path(cur, p.items.back(), o, out);
        return;
      }
      default:
        break;
    }
    plan_.paths.push_back(make_path(p));
    PatternElem e{s, Slot{}, o, static_cast<int32_t>(plan_.paths.size() - 1), p.pos};
    out.push_back(e);
  }

  Slot node(const ast::Node& n, std::vector<PatternElem>& out) {
    switch (n.kind) {
      case ast::Node::Kind::Term:
        return slot(n.term);
      case ast::Node::Kind::BlankPropertyList: {
        Slot b{true, fresh()};
        properties(b, n.properties, out);
        return b;
      }
      case ast::Node::Kind::Collection: {
        const Slot first{false, plan_.terms.iri(std::string(kRdf) + "first").index};
        const Slot rest{false, plan_.terms.iri(std::string(kRdf) + "rest").index};
        const Slot nil{false, plan_.terms.iri(std::string(kRdf) + "nil").index};
        Slot head{true, fresh()};
        Slot cur = head;
        for (size_t i = 0; i < n.members.size(); ++i) {
          Slot m = node(n.members[i], out);
          out.push_back(PatternElem{cur, first, m, -1, n.members[i].pos});
          Slot next = i + 1 < n.members.size() ? Slot{true, fresh()} : nil;
          out.push_back(PatternElem{cur, rest, next, -1, n.members[i].pos});
          cur = next;
        }
        return head;
      }
    }
    return Slot{};
  }

  void properties(Slot s, const std::vector<ast::PropertyObjects>& props,
                  std::vector<PatternElem>& out) {
    for (const ast::PropertyObjects& po : props)
      for (const ast::Node& obj : po.objects) add_path(s, po.verb, node(obj, out), out);
  }

  // ---- ops ----
  uint32_t push(Op op, VarSet scope) {
    op.hide.clear();
    // A union joins each branch with the input separately and every branch
    // hides for itself, so the union itself needs no hiding (and branches that
    // bind a variable keep using the input's binding for their lookups).
    // A sub-SELECT is evaluated on its own (its LIMIT, DISTINCT and ORDER BY
    // apply before the join), so it sees none of the input's bindings.
    if (op.kind != OpKind::Union)
      for (Var v : op.mentioned.members())
        if (op.kind == OpKind::SubSelect || !op.certain.contains(v)) op.hide.push_back(v);
    plan_.ops.push_back(std::move(op));
    scope_.push_back(std::move(scope));
    return static_cast<uint32_t>(plan_.ops.size() - 1);
  }

  uint32_t bgp(std::vector<PatternElem> elems) {
    Op op;
    op.kind = OpKind::Bgp;
    VarSet vars;
    for (const PatternElem& e : elems)
      for (const Slot* sl : {&e.s, &e.p, &e.o})
        if (sl->is_var && !(sl == &e.p && e.path >= 0)) vars.insert(sl->value);
    op.elems = std::move(elems);
    op.vars = vars.members();
    op.certain = vars;
    op.mentioned = vars;
    return push(std::move(op), vars);
  }

  // Translates a group. With `filters_out`, the group's filters are handed
  // back (OPTIONAL turns them into the LeftJoin condition) instead of placed.
  uint32_t group(const ast::Group& g, std::vector<uint32_t>* filters_out) {
    std::vector<Step> steps;
    std::vector<uint32_t> filters;
    std::vector<PatternElem> pending;
    VarSet in_scope;  // for the BIND rule (18.2.1)
    VarSet certain, mentioned;
    std::vector<VarSet> certain_after;  // by step
    auto add_step = [&](Step s) {
      if (s.kind == Step::Kind::Join) {
        const Op& child = plan_.ops[s.child];
        certain.insert_all(child.certain);
        mentioned.insert_all(child.mentioned);
        in_scope.insert_all(scope_[s.child]);
      } else if (s.kind == Step::Kind::LeftJoin) {
        mentioned.insert_all(plan_.ops[s.child].mentioned);
        in_scope.insert_all(scope_[s.child]);
      }
      steps.push_back(s);
      certain_after.push_back(certain);
    };
    auto flush = [&]() {
      if (pending.empty()) return;
      add_step(Step{Step::Kind::Join, bgp(std::move(pending)), kNone, kNone});
      pending.clear();
      ++bgp_serial_;
    };
    for (const ast::Element& e : g.elements) {
      switch (e.kind) {
        case ast::Element::Kind::Triples:
          for (const ast::Triples& t : e.triples) {
            Slot s = node(t.subject, pending);
            properties(s, t.properties, pending);
          }
          break;
        case ast::Element::Kind::Filter:
          filters.push_back(expr(e.expr));
          break;
        case ast::Element::Kind::Group:
          flush();
          add_step(Step{Step::Kind::Join, group(e.groups[0], nullptr), kNone, kNone});
          break;
        case ast::Element::Kind::Union: {
          flush();
          Op u;
          u.kind = OpKind::Union;
          VarSet scope;
          bool first = true;
          for (const ast::Group& alt : e.groups) {
            const uint32_t c = group(alt, nullptr);
            u.children.push_back(c);
            if (first) {
              u.certain = plan_.ops[c].certain;
            } else {
              u.certain.intersect(plan_.ops[c].certain);
            }
            first = false;
            u.mentioned.insert_all(plan_.ops[c].mentioned);
            scope.insert_all(scope_[c]);
          }
          add_step(Step{Step::Kind::Join, push(std::move(u), scope), kNone, kNone});
          break;
        }
        case ast::Element::Kind::Optional: {
          flush();
          std::vector<uint32_t> conds;
          const uint32_t c = group(e.groups[0], &conds);
          uint32_t cond = kNone;
          for (uint32_t f : conds) cond = cond == kNone ? f : conjunction(cond, f);
          if (cond != kNone)
            for (Var v : plan_.expr_vars[cond]) mentioned.insert(v);
          add_step(Step{Step::Kind::LeftJoin, c, cond, kNone});
          break;
        }
        case ast::Element::Kind::SubSelect:
          flush();
          add_step(Step{Step::Kind::Join, sub_select(e), kNone, kNone});
          break;
        case ast::Element::Kind::Bind: {
          flush();
          const Var v = var(e.var.value);
          if (in_scope.contains(v))
            ast::fail(kSyntax, e.var.pos,
                      "BIND ... AS ?" + e.var.value + ": variable ?" + e.var.value +
                          " is already in scope in this group (SPARQL 1.1, 18.2.1)");
          const uint32_t x = expr(e.expr);
          for (Var w : plan_.expr_vars[x]) mentioned.insert(w);
          mentioned.insert(v);
          in_scope.insert(v);
          plan_.assigned.emplace_back(v, e.var.pos);
          add_step(Step{Step::Kind::Extend, kNone, x, v});
          break;
        }
      }
    }
    flush();

    Op op;
    op.kind = OpKind::Group;
    op.certain = certain;
    for (uint32_t f : filters)
      for (Var v : plan_.expr_vars[f]) mentioned.insert(v);
    op.mentioned = mentioned;
    if (filters_out != nullptr) {
      *filters_out = filters;
      op.steps = std::move(steps);
      return push(std::move(op), in_scope);
    }
    // Filter placement (see algebra.hpp): `bindable` is what the group binds.
    VarSet bindable = in_scope;
    std::vector<std::vector<uint32_t>> after(steps.size() + 1);  // after[k+1]: after step k
    for (uint32_t f : filters) {
      size_t place = steps.size();  // default: on top of everything
      bool need_any = false;
      VarSet need;
      for (Var v : plan_.expr_vars[f]) {
        if (bindable.contains(v)) {
          need.insert(v);
          need_any = true;
        }
      }
      if (!need_any) {
        place = 0;
      } else {
        for (size_t k = 0; k < steps.size(); ++k) {
          if (need.subset_of(certain_after[k])) {
            place = k + 1;
            break;
          }
        }
      }
      after[place].push_back(f);
    }
    for (size_t k = 0; k <= steps.size(); ++k) {
      if (k > 0) {
        const Step& s = steps[k - 1];
        if (s.kind == Step::Kind::Join && plan_.ops[s.child].kind == OpKind::Bgp) {
          // Checked inside the BGP's join loop as soon as their variables are bound.
          auto& bf = plan_.ops[s.child].filters;
          bf.insert(bf.end(), after[k].begin(), after[k].end());
          op.steps.push_back(s);
          continue;
        }
        op.steps.push_back(s);
      }
      for (uint32_t f : after[k]) op.steps.push_back(Step{Step::Kind::Filter, kNone, f, kNone});
    }
    return push(std::move(op), in_scope);
  }

  // A SELECT's columns, for the query and its sub-SELECTs alike: every
  // visible variable in scope for `*`, else the projection, whose
  // `(expr AS ?v)` may not name a variable already in scope. A grouped
  // SELECT (GROUP BY, or an aggregate) may project only its keys, its
  // aggregates and expressions of those (18.2.4.1).
  void project(const ast::Query& q, const VarSet& scope, std::vector<Var>& result_vars,
               std::vector<std::string>& names,
               std::vector<std::pair<Var, uint32_t>>& projected_exprs, Grouping& grouping) {
    grouping.active = !q.group_by.empty();
    for (const ast::Projection& pr : q.projection)
      if (pr.has_expr && pr.expr.kind == ast::Expr::Kind::Aggregate) grouping.active = true;
    if (q.star) {
      if (grouping.active)
        ast::fail(kSyntax, q.group_pos,
                  "SELECT * cannot be grouped: name the GROUP BY variables and aggregates");
      for (Var v = 0; v < plan_.var_names.size(); ++v) {
        if (!plan_.hidden[v] && scope.contains(v)) {
          result_vars.push_back(v);
          names.push_back(plan_.var_names[v]);
        }
      }
      return;
    }
    VarSet projected = scope;
    if (grouping.active) {
      projected = VarSet();
      for (const ast::Term& k : q.group_by) {
        const Var v = var(k.value);
        grouping.keys.push_back(v);
        projected.insert(v);
      }
    }
    for (const ast::Projection& pr : q.projection) {
      const Var v = var(pr.var.value);
      if (pr.has_expr) {
        if (projected.contains(v) || scope.contains(v))
          ast::fail(
              kSyntax, pr.var.pos,
              "(... AS ?" + pr.var.value + "): variable ?" + pr.var.value + " is already in scope");
        if (pr.expr.kind == ast::Expr::Kind::Aggregate) {
          grouping.aggregates.push_back(
              Aggregate{v, expr(pr.expr.args[0]), pr.expr.distinct, pr.expr.separator});
        } else {
          const uint32_t x = expr(pr.expr);
          if (grouping.active)
            for (Var u : plan_.expr_vars[x])
              if (!projected.contains(u)) ungrouped(pr.expr.pos, u);
          projected_exprs.emplace_back(v, x);
        }
        plan_.assigned.emplace_back(v, pr.var.pos);
        projected.insert(v);
      } else if (grouping.active && !projected.contains(v)) {
        ungrouped(pr.var.pos, v);
      }
      result_vars.push_back(v);
      names.push_back(pr.var.value);
    }
  }
  [[noreturn]] void ungrouped(ast::Pos pos, Var v) const {
    ast::fail(kSyntax, pos,
              "?" + plan_.var_names[v] +
                  " is neither a GROUP BY variable nor an aggregate's result (a grouped SELECT "
                  "projects only those)");
  }

  // A sub-SELECT, built with a variable scope of its own: its variables that
  // it does not project are not the enclosing query's (18.2.1).
  uint32_t sub_select(const ast::Element& e) {
    const ast::Query& q = *e.sub;
    auto outer_vars = std::move(vars_);
    vars_.clear();
    auto outer_blanks = std::move(blank_labels_);
    blank_labels_.clear();
    Select sel;
    sel.distinct = q.distinct;
    sel.limit = q.limit;
    sel.offset = q.offset;
    for (const ast::Projection& pr : q.projection)
      if (!pr.has_expr) var(pr.var.value);
    sel.root = group(q.where, nullptr);
    const VarSet scope = scope_[sel.root];
    std::vector<std::string> names;
    project(q, scope, sel.result_vars, names, sel.projected_exprs, sel.grouping);
    for (const ast::OrderKey& k : q.order) sel.order.push_back({expr(k.expr), k.descending});
    const VarSet certain = plan_.ops[sel.root].certain;
    for (const auto& [name, v] : vars_) plan_.hidden[v] = true;
    plan_.subselect_names.emplace_back(names, e.pos);
    vars_ = std::move(outer_vars);
    blank_labels_ = std::move(outer_blanks);

    Op op;
    op.kind = OpKind::SubSelect;
    VarSet outer_scope;
    for (size_t c = 0; c < names.size(); ++c) {
      const Var o = var(names[c]);
      sel.outer_vars.push_back(o);
      outer_scope.insert(o);
      op.mentioned.insert(o);
      if (certain.contains(sel.result_vars[c])) op.certain.insert(o);
    }
    op.select = static_cast<uint32_t>(plan_.selects.size());
    plan_.selects.push_back(std::move(sel));
    return push(std::move(op), outer_scope);
  }

  // ---- expressions ----
  uint32_t push_expr(Expr e, std::vector<Var> vars) {
    plan_.exprs.push_back(std::move(e));
    plan_.expr_vars.push_back(std::move(vars));
    return static_cast<uint32_t>(plan_.exprs.size() - 1);
  }
  uint32_t conjunction(uint32_t a, uint32_t b) {
    Expr e;
    e.op = ExprOp::And;
    e.args = {a, b};
    VarSet vs;
    for (uint32_t x : {a, b})
      for (Var v : plan_.expr_vars[x]) vs.insert(v);
    return push_expr(std::move(e), vs.members());
  }

  uint32_t expr(const ast::Expr& a) {
    Expr e;
    e.pos = a.pos;
    VarSet vs;
    auto arg = [&](const ast::Expr& x) {
      const uint32_t i = expr(x);
      e.args.push_back(i);
      for (Var v : plan_.expr_vars[i]) vs.insert(v);
    };
    switch (a.kind) {
      case ast::Expr::Kind::Term:
        if (a.term.kind == ast::Term::Kind::Var) {
          e.op = ExprOp::Var;
          e.value = var(a.term.value);
          vs.insert(e.value);
        } else {
          e.op = ExprOp::Const;
          e.value = constant(a.term);
        }
        break;
      case ast::Expr::Kind::Or:
      case ast::Expr::Kind::And:
      case ast::Expr::Kind::Not:
      case ast::Expr::Kind::Negate:
      case ast::Expr::Kind::Plus:
      case ast::Expr::Kind::In:
      case ast::Expr::Kind::NotIn:
        e.op = a.kind == ast::Expr::Kind::Or       ? ExprOp::Or
               : a.kind == ast::Expr::Kind::And    ? ExprOp::And
               : a.kind == ast::Expr::Kind::Not    ? ExprOp::Not
               : a.kind == ast::Expr::Kind::Negate ? ExprOp::Neg
               : a.kind == ast::Expr::Kind::Plus   ? ExprOp::Plus
               : a.kind == ast::Expr::Kind::In     ? ExprOp::In
                                                   : ExprOp::NotIn;
        for (const ast::Expr& x : a.args) arg(x);
        break;
      case ast::Expr::Kind::Compare:
        e.op = a.name == "="    ? ExprOp::Eq
               : a.name == "!=" ? ExprOp::Ne
               : a.name == "<"  ? ExprOp::Lt
               : a.name == ">"  ? ExprOp::Gt
               : a.name == "<=" ? ExprOp::Le
                                : ExprOp::Ge;
        for (const ast::Expr& x : a.args) arg(x);
        break;
      case ast::Expr::Kind::Arith:
        e.op = a.name == "+"   ? ExprOp::Add
               : a.name == "-" ? ExprOp::Sub
               : a.name == "*" ? ExprOp::Mul
                               : ExprOp::Div;
        for (const ast::Expr& x : a.args) arg(x);
        break;
      case ast::Expr::Kind::Exists:
      case ast::Expr::Kind::NotExists: {
        e.op = a.kind == ast::Expr::Kind::Exists ? ExprOp::Exists : ExprOp::NotExists;
        e.value = group(*a.pattern, nullptr);
        vs.insert_all(plan_.ops[e.value].mentioned);
        break;
      }
      case ast::Expr::Kind::Aggregate:
        ast::fail(kUnsupported, a.pos,
                  a.name + " is supported only as a whole SELECT expression, (" + a.name +
                      "(...) AS ?var)");
      case ast::Expr::Kind::Call:
        call(a, e);
        for (const ast::Expr& x : a.args) arg(x);
        if (e.op == ExprOp::Regex) regex(a, e);
        break;
    }
    return push_expr(std::move(e), vs.members());
  }

  void call(const ast::Expr& a, Expr& e) {
    auto arity = [&](int lo, int hi) {
      const int n = static_cast<int>(a.args.size());
      if (n < lo || (hi >= 0 && n > hi)) {
        std::string want = lo == hi ? std::to_string(lo)
                           : hi < 0 ? "at least " + std::to_string(lo)
                                    : std::to_string(lo) + " or " + std::to_string(hi);
        ast::fail(kSyntax, a.pos,
                  a.name + " expects " + want + " argument" + (want == "1" ? "" : "s") +
                      ", found " + std::to_string(n));
      }
    };
    if (a.is_iri) {
      if (a.name.starts_with(kXsd)) {
        const std::string_view local = std::string_view(a.name).substr(kXsd.size());
        for (const Cast& c : kCasts) {
          if (local == c.local) {
            e.op = c.op;
            arity(1, 1);
            return;
          }
        }
      }
      ast::fail(kUnsupported, a.pos, "function <" + a.name + "> is not supported");
    }
    for (const Builtin& b : kBuiltins) {
      if (a.name == b.name) {
        e.op = b.op;
        arity(b.min_args, b.max_args);
        return;
      }
    }
    for (const char* n : kKnownUnsupported)
      if (a.name == n) ast::fail(kUnsupported, a.pos, "function " + a.name + " is not supported");
    ast::fail(kSyntax, a.pos, "unknown function " + a.name);
  }

  void regex(const ast::Expr& a, Expr& e) {
    auto constant_string = [&](const ast::Expr& x) -> const std::string* {
      if (x.kind != ast::Expr::Kind::Term || x.term.kind != ast::Term::Kind::Literal)
        return nullptr;
      return &x.term.value;
    };
    const std::string* pattern = constant_string(a.args[1]);
    const std::string* flags = a.args.size() > 2 ? constant_string(a.args[2]) : nullptr;
    if (pattern == nullptr || (a.args.size() > 2 && flags == nullptr)) return;
    try {
      plan_.regexes.emplace_back(*pattern, flags ? *flags : std::string_view());
    } catch (const RegexError& error) {
      ast::fail(error.kind() == RegexError::Kind::Unsupported ? kUnsupported : kSyntax,
                error.kind() == RegexError::Kind::Flag ? a.args[2].pos : a.args[1].pos,
                error.what());
    }
    e.regex = static_cast<int32_t>(plan_.regexes.size() - 1);
  }

  Plan& plan_;
  std::unordered_map<std::string, Var> vars_;
  std::unordered_map<std::string, std::pair<Var, uint32_t>> blank_labels_;
  uint32_t bgp_serial_ = 0;
  uint32_t fresh_count_ = 0;
  std::vector<VarSet> scope_;  // by op: variables it can bind (in-scope, 18.2.1)
};

}  // namespace

namespace {

class Printer {
 public:
  explicit Printer(const Plan& plan) : plan_(plan) {}

  std::string query() {
    std::string out = plan_.form == QueryForm::Ask ? "(ask " : "(select (";
    if (plan_.form == QueryForm::Select) {
      for (size_t i = 0; i < plan_.result_vars.size(); ++i)
        out += (i > 0 ? " ?" : "?") + plan_.var_names[plan_.result_vars[i]];
      out += ") ";
    }
    return out + modified(plan_) + ")";
  }

 private:
  // The WHERE clause of a query or sub-SELECT with its solution modifiers.
  template <class S>
  std::string modified(const S& q) const {
    std::string body = op(q.root);
    if (q.grouping.active) {
      std::string keys;
      for (Var k : q.grouping.keys) keys += (keys.empty() ? "" : " ") + var(k);
      body = "(group (" + keys + ") " + body + ")";
      for (const Aggregate& a : q.grouping.aggregates)
        body = "(extend " + var(a.var) + " (group_concat " + (a.distinct ? "distinct " : "") +
               expr(a.expr) + " " + quoted(a.separator) + ") " + body + ")";
    }
    for (const auto& [v, x] : q.projected_exprs)
      body = "(extend ?" + plan_.var_names[v] + " " + expr(x) + " " + body + ")";
    if (!q.order.empty()) {
      std::string keys;
      for (const OrderKey& k : q.order)
        keys += (keys.empty() ? "" : " ") +
                (k.descending ? "(desc " + expr(k.expr) + ")" : expr(k.expr));
      body = "(order (" + keys + ") " + body + ")";
    }
    if (q.distinct) body = "(distinct " + body + ")";
    if (q.limit >= 0 || q.offset > 0)
      body = "(slice " + std::to_string(q.offset) + " " +
             (q.limit >= 0 ? std::to_string(q.limit) : "_") + " " + body + ")";
    return body;
  }

  std::string var(Var v) const { return "?" + plan_.var_names[v]; }
  static std::string quoted(std::string_view text) {
    std::string out = "\"";
    for (char c : text) {
      if (c == '"' || c == '\\') out += '\\';
      out += c;
    }
    return out + "\"";
  }
  std::string term(uint32_t id) const { return rdf::to_ntriples(plan_.terms, rdf::TermId{id}); }
  std::string slot(const Slot& s) const { return s.is_var ? var(s.value) : term(s.value); }

  std::string path(const Path& p) const {
    auto list = [&](const char* head) {
      std::string out = std::string("(") + head;
      for (const PathPtr& item : p.items) out.append(" ").append(path(*item));
      out.append(")");
      return out;
    };
    switch (p.kind) {
      case Path::Kind::Predicate:
        return term(p.predicate.index);
      case Path::Kind::Inverse:
        return list("inv");
      case Path::Kind::Sequence:
        return list("seq");
      case Path::Kind::Alternative:
        return list("alt");
      case Path::Kind::ZeroOrMore:
        return list("*");
      case Path::Kind::OneOrMore:
        return list("+");
      case Path::Kind::ZeroOrOne:
        return list("?");
      case Path::Kind::NegatedSet: {
        std::string out = "(!";
        for (rdf::TermId t : p.negated) out += " " + term(t.index);
        for (rdf::TermId t : p.negated_inverse) out += " ^" + term(t.index);
        return out + ")";
      }
    }
    return {};
  }

  std::string op(uint32_t index) const {
    const Op& o = plan_.ops[index];
    std::string out;
    switch (o.kind) {
      case OpKind::Bgp:
        out = "(bgp";
        for (const PatternElem& e : o.elems) {
          out += " (" + slot(e.s) + " " +
                 (e.path >= 0 ? path(*plan_.paths[static_cast<size_t>(e.path)]) : slot(e.p)) + " " +
                 slot(e.o) + ")";
        }
        for (uint32_t f : o.filters) out += " (filter " + expr(f) + ")";
        return out + ")";
      case OpKind::Union:
        out = "(union";
        for (uint32_t c : o.children) out += " " + op(c);
        return out + ")";
      case OpKind::SubSelect: {
        const Select& s = plan_.selects[o.select];
        out = "(project (";
        for (size_t i = 0; i < s.result_vars.size(); ++i)
          out += (i > 0 ? " " : "") + var(s.result_vars[i]);
        return out + ") " + modified(s) + ")";
      }
      case OpKind::Group:
        out = "(group";
        for (const Step& s : o.steps) {
          switch (s.kind) {
            case Step::Kind::Join:
              out += " (join " + op(s.child) + ")";
              break;
            case Step::Kind::LeftJoin:
              out +=
                  " (leftjoin " + op(s.child) + (s.expr != kNone ? " " + expr(s.expr) : "") + ")";
              break;
            case Step::Kind::Extend:
              out += " (extend " + var(s.var) + " " + expr(s.expr) + ")";
              break;
            case Step::Kind::Filter:
              out += " (filter " + expr(s.expr) + ")";
              break;
          }
        }
        return out + ")";
    }
    return out;
  }

  std::string expr(uint32_t index) const {
    const Expr& e = plan_.exprs[index];
    static const char* const kNames[] = {
        "const",       "var",        "||",          "&&",         "!",          "=",
        "!=",          "<",          ">",           "<=",         ">=",         "in",
        "notin",       "+",          "-",           "*",          "/",          "-",
        "+",           "exists",     "notexists",   "bound",      "if",         "coalesce",
        "abs",         "ceil",       "floor",       "round",      "isIRI",      "isBlank",
        "isLiteral",   "isNumeric",  "str",         "lang",       "datatype",   "iri",
        "regex",       "strstarts",  "strends",     "contains",   "strlen",     "ucase",
        "lcase",       "concat",     "langMatches", "sameTerm",   "xsd:string", "xsd:integer",
        "xsd:decimal", "xsd:double", "xsd:float",   "xsd:boolean"};
    switch (e.op) {
      case ExprOp::Const:
        return term(e.value);
      case ExprOp::Var:
        return var(e.value);
      case ExprOp::Exists:
      case ExprOp::NotExists:
        return std::string("(") + kNames[static_cast<size_t>(e.op)] + " " + op(e.value) + ")";
      default: {
        std::string out = std::string("(") + kNames[static_cast<size_t>(e.op)];
        for (uint32_t a : e.args) out += " " + expr(a);
        return out + ")";
      }
    }
  }

  const Plan& plan_;
};

}  // namespace

std::string to_sse(const Plan& plan) {
  return Printer(plan).query();
}

std::shared_ptr<Plan> build_plan(ast::Query&& query) {
  auto plan = std::make_shared<Plan>();
  Builder(*plan).build(query);
  return plan;
}

}  // namespace mospec::sparql::detail
