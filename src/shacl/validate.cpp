#include "shacl/validate.hpp"

#include <algorithm>
#include <cctype>
#include <memory>
#include <optional>
#include <string>
#include <unordered_map>
#include <unordered_set>

#include "rdf/xsd.hpp"
#include "shacl/literal.hpp"
#include "vocab/w3c.hpp"

namespace mospec::shacl {

namespace {

using rdf::TermId;

constexpr TermId kAbsent{UINT32_MAX - 1};

enum class PathSource : uint8_t { None, Shape, Predicate };

// A result before it is rendered into the report's term table. Terms are
// validation ids (see Validator).
struct RawResult {
  TermId focus;
  TermId value = TermId::any();
  uint32_t shape = 0;
  uint32_t constraint = 0;  // index into the shape's constraints
  Component component = Component::Class;
  PathSource path = PathSource::None;
  TermId predicate;  // PathSource::Predicate
  // SHACL-SPARQL: the sh:sparql node (shapes-graph id) and the messages made
  // from ?message or the constraint's sh:message (used instead of the shape's).
  TermId source_constraint = TermId::any();
  TermId component_node = TermId::any();  // SPARQL-based constraint component (shapes id)
  bool own_messages = false;
  std::vector<std::pair<std::string, std::string>> messages;  // (text, language)
  // SHACL-SPARQL: the other data nodes the result row projects (?upper), by
  // variable name, so the report can say where each is written.
  std::vector<std::pair<std::string, TermId>> related;
};

// Where a shape's results go: collected for the report, or (conformance
// checking) just noticed, stopping at the first.
struct Sink {
  std::vector<RawResult>* out = nullptr;
  bool found = false;
  bool done() const { return out == nullptr && found; }
  void add(RawResult r) {
    found = true;
    if (out != nullptr) out->push_back(std::move(r));
  }
};

uint64_t pair_key(uint32_t a, TermId b) {
  return (uint64_t{a} << 32) | b.index;
}

// Validation ids: ids of the data graph's terms, plus ids from base_ upwards
// for terms the shapes mention that the data graph lacks (e.g. an
// sh:targetNode that appears in no triple). Dataset lookups treat ids past
// the data's term table as absent, so those terms simply have no triples.
class Validator {
 public:
  Validator(const Shapes& shapes, const rdf::Dataset& data, const ValidateOptions& options)
      : shapes_(shapes),
        data_(data),
        dt_(data.terms()),
        st_(shapes.graph().terms()),
        same_(&shapes.graph() == &data),
        base_(static_cast<uint32_t>(data.terms().size())),
        options_(options) {
    budget_ = options.sparql_budget != nullptr ? options.sparql_budget
                                               : &own_budget_.emplace(options.sparql_limits);
    auto find = [&](std::string_view iri) {
      TermId id = dt_.find_iri(iri);
      return id.is_any() ? kAbsent : id;
    };
    type_ = find(vocab::rdf::type);
    subclass_ = find(vocab::rdfs::subClassOf);
    if (!same_) {
      to_data_.assign(st_.size(), kAbsent);
      for (TermId s : shapes.referenced_terms()) {
        TermId d = dt_.find_equivalent(st_, s);
        if (d.is_any()) {
          d = outside(extra_.import(st_, s));
        }
        to_data_[s.index] = d;
      }
    }
    paths_.resize(shapes.shapes().size());
    bound_.resize(shapes.shapes().size());
    for (uint32_t i = 0; i < shapes.shapes().size(); ++i) {
      const Shape& s = shapes[i];
      if (s.path) paths_[i] = same_ ? s.path : translate(*s.path);
      // Set-valued parameters, translated and sorted once.
      bound_[i].resize(s.constraints.size());
      for (size_t k = 0; k < s.constraints.size(); ++k) {
        const Constraint& c = s.constraints[k];
        if (c.component != Component::In && c.component != Component::Closed) continue;
        auto& set = bound_[i][k];
        for (TermId t : c.terms) set.push_back(map(t));
        std::sort(set.begin(), set.end());
      }
    }
  }

  Report run() {
    std::vector<RawResult> raw;
    Sink sink{&raw};
    for (uint32_t i = 0; i < shapes_.shapes().size(); ++i) {
      const Shape& s = shapes_[i];
      if (!s.has_targets() || s.deactivated) continue;
      for (TermId focus : focus_nodes(s)) validate_shape(i, focus, sink);
    }
    return render(raw);
  }

  // The first result of validating `focus` against `shape` as text ("value:
  // message"), empty when it conforms (for check_component_parameters).
  std::string first_failure(uint32_t shape, TermId focus) {
    std::vector<RawResult> out;
    Sink sink{&out};
    validate_shape(shape, focus, sink);
    if (out.empty()) return {};
    const RawResult& r = out[0];
    std::string text = r.value.is_any() ? std::string() : show(r.value) + ": ";
    const Shape& s = shapes_[r.shape];
    text += s.messages.empty() ? default_message(r) : std::string(st_[s.messages[0]].value);
    return text;
  }

  std::vector<size_t> focus_counts() {
    std::vector<size_t> out(shapes_.shapes().size(), 0);
    for (uint32_t i = 0; i < shapes_.shapes().size(); ++i)
      if (shapes_[i].has_targets()) out[i] = focus_nodes(shapes_[i]).size();
    return out;
  }

 private:
  // The validation id of a term of extra_.
  TermId outside(TermId x) {
    auto [it, inserted] = outside_ids_.try_emplace(x.index);
    if (inserted) {
      it->second = TermId{base_ + static_cast<uint32_t>(overlay_.size())};
      overlay_.push_back(x);
    }
    return it->second;
  }

  TermId map(TermId shape_term) const { return same_ ? shape_term : to_data_[shape_term.index]; }

  const rdf::Term& term(TermId v) const {
    return v.index < base_ ? dt_[v] : extra_[overlay_[v.index - base_]];
  }

  sparql::PathPtr translate(const sparql::Path& p) const {
    if (p.kind == sparql::Path::Kind::Predicate) return sparql::Path::iri(map(p.predicate));
    std::vector<sparql::PathPtr> items;
    for (const auto& item : p.items) items.push_back(translate(*item));
    return sparql::Path::make(p.kind, std::move(items));
  }

  // ---- data access -------------------------------------------------------

  void objects(TermId s, TermId p, std::vector<TermId>& out) const {
    out.clear();
    data_.scan(s, p, TermId::any(), TermId::any(), [&](const rdf::Quad& q, uint32_t) {
      out.push_back(q.object);
      return true;
    });
    dedupe(out);
  }

  static void dedupe(std::vector<TermId>& v) {
    if (v.size() < 2) return;
    std::sort(v.begin(), v.end());
    v.erase(std::unique(v.begin(), v.end()), v.end());
  }

  void value_nodes(uint32_t shape, TermId focus, std::vector<TermId>& out) const {
    const sparql::PathPtr& path = paths_[shape];
    if (!path) {
      out.assign(1, focus);
      return;
    }
    if (path->kind == sparql::Path::Kind::Predicate) {
      objects(focus, path->predicate, out);
      return;
    }
    try {
      sparql::evaluate_path(data_, *path, focus, out, TermId::any(), budget_, &path_workspace_);
    } catch (const Error& e) {
      if (e.code() != "sparql-limit") throw;
      limit_reached(shapes_[shape].where,
                    "sh:path " + path_to_sparql(st_, *shapes_[shape].path) + " of shape " +
                        shapes_.describe(shape) + " from focus node " + show(focus),
                    e);
    }
    dedupe(out);
  }

  // A SPARQL constraint or a path that exceeded its sparql::Limits: the same
  // code, located at the shape (or constraint) that asked for the work.
  [[noreturn]] void limit_reached(SourceLoc where, const std::string& what, const Error& e) const {
    std::string file =
        shapes_.files() != nullptr && where.known() ? shapes_.files()->path(where.file) : "";
    throw Error(e.code(), what + ": " + e.diagnostic().message, file, where.line, where.column);
  }

  // Every class that is rdfs:subClassOf* `cls` in the data graph, sorted.
  const std::vector<TermId>& subclasses(TermId cls) {
    auto [it, inserted] = subclasses_.try_emplace(cls.index);
    if (!inserted) return it->second;
    std::vector<TermId> all{cls};
    for (size_t i = 0; i < all.size(); ++i) {
      data_.scan(TermId::any(), subclass_, all[i], TermId::any(),
                 [&](const rdf::Quad& q, uint32_t) {
                   if (std::find(all.begin(), all.end(), q.subject) == all.end())
                     all.push_back(q.subject);
                   return true;
                 });
    }
    std::sort(all.begin(), all.end());
    it->second = std::move(all);
    return it->second;
  }

  bool is_instance(TermId node, TermId cls) {
    if (term(node).is_literal()) return false;
    const std::vector<TermId>& classes = subclasses(cls);
    bool found = false;
    data_.scan(node, type_, TermId::any(), TermId::any(), [&](const rdf::Quad& q, uint32_t) {
      found = std::binary_search(classes.begin(), classes.end(), q.object);
      return !found;
    });
    return found;
  }

  std::vector<TermId> focus_nodes(const Shape& s) {
    std::vector<TermId> out;
    std::unordered_set<uint32_t> seen;
    auto add = [&](TermId t) {
      if (seen.insert(t.index).second) out.push_back(t);
    };
    for (TermId t : s.target_nodes) add(map(t));
    for (TermId c : s.target_classes) {
      for (TermId cls : subclasses(map(c)))
        data_.scan(TermId::any(), type_, cls, TermId::any(), [&](const rdf::Quad& q, uint32_t) {
          add(q.subject);
          return true;
        });
    }
    for (TermId p : s.target_subjects_of)
      data_.scan(TermId::any(), map(p), TermId::any(), TermId::any(),
                 [&](const rdf::Quad& q, uint32_t) {
                   add(q.subject);
                   return true;
                 });
    for (TermId p : s.target_objects_of)
      data_.scan(TermId::any(), map(p), TermId::any(), TermId::any(),
                 [&](const rdf::Quad& q, uint32_t) {
                   add(q.object);
                   return true;
                 });
    return out;
  }

  // ---- literal helpers ---------------------------------------------------

  std::string_view datatype_iri(TermId v) const {
    const rdf::Term& t = term(v);
    const rdf::TermTable& table = v.index < base_ ? dt_ : extra_;
    return table[t.datatype].value;
  }

  LiteralView literal(TermId v) const {
    const rdf::Term& t = term(v);
    return {t.value, datatype_iri(v), t.language};
  }

  LiteralView shape_literal(TermId s) const {
    const rdf::Term& t = st_[s];
    return {t.value, st_[t.datatype].value, t.language};
  }

  bool has_datatype(TermId v, TermId datatype_in_shapes) {
    const rdf::Term& t = term(v);
    if (!t.is_literal()) return false;
    if (v.index < base_ && !same_) {
      if (t.datatype != map(datatype_in_shapes)) return false;
    } else if (v.index < base_) {
      if (t.datatype != datatype_in_shapes) return false;
    } else if (datatype_iri(v) != st_[datatype_in_shapes].value) {
      return false;
    }
    if (v.index >= base_) return check_well_formed(v);
    // Cached per literal: the check parses the lexical form.
    if (well_formed_.size() < base_) well_formed_.assign(base_, 0);
    uint8_t& cached = well_formed_[v.index];
    if (cached == 0) cached = check_well_formed(v) ? 1 : 2;
    return cached == 1;
  }

  bool check_well_formed(TermId v) const {
    const rdf::Term& t = term(v);
    rdf::xsd::Datatype info = rdf::xsd::classify(datatype_iri(v));
    if (info.kind == rdf::xsd::Kind::LangString) return !t.language.empty();
    return rdf::xsd::well_formed(t.value, info);
  }

  std::string_view str(TermId v) const { return term(v).value; }

  // ---- validation --------------------------------------------------------

  bool conforms(uint32_t shape, TermId focus) {
    const uint64_t key = pair_key(shape, focus);
    if (auto it = conforms_cache_.find(key); it != conforms_cache_.end()) return it->second;
    Sink probe;
    validate_shape(shape, focus, probe);
    conforms_cache_.emplace(key, !probe.found);
    return !probe.found;
  }

  void validate_shape(uint32_t shape, TermId focus, Sink& sink) {
    const Shape& s = shapes_[shape];
    if (s.deactivated) return;
    const uint64_t key = pair_key(shape, focus);
    if (!active_.insert(key).second) recursion(shape, focus);
    if (stack_.size() >= kMaxDepth) too_deep(shape, focus);
    stack_.push_back(shape);
    std::vector<TermId> values;
    value_nodes(shape, focus, values);
    for (uint32_t k = 0; k < s.constraints.size() && !sink.done(); ++k)
      evaluate(shape, k, focus, values, sink);
    stack_.pop_back();
    active_.erase(key);
  }

  // Shapes that reach themselves over ever new data nodes (a recursive shape
  // along a long chain) nest one call per node, and so does a long chain of
  // shapes written innermost first; stop before the stack does. One level
  // takes about 1.2 KiB of stack in a release build (several times that under
  // ASan); the compiler's own limit (256) keeps non-recursive chains below.
  static constexpr size_t kMaxDepth = 512;

  [[noreturn]] void too_deep(uint32_t shape, TermId focus) {
    const Shape& s = shapes_[shape];
    std::string file =
        shapes_.files() != nullptr && s.where.known() ? shapes_.files()->path(s.where.file) : "";
    throw Error("shacl-recursion",
                "shapes nest deeper than " + std::to_string(kMaxDepth) + " levels at shape " +
                    shapes_.describe(shape) + " (focus node " + show(focus) +
                    "): a recursive shape follows a long chain in the data",
                file, s.where.line, s.where.column);
  }

  [[noreturn]] void recursion(uint32_t shape, TermId focus) {
    std::string cycle;
    auto start = std::find(stack_.begin(), stack_.end(), shape);
    for (auto it = start; it != stack_.end(); ++it) cycle += shapes_.describe(*it) + " -> ";
    cycle += shapes_.describe(shape);
    const Shape& s = shapes_[shape];
    std::string file =
        shapes_.files() != nullptr && s.where.known() ? shapes_.files()->path(s.where.file) : "";
    throw Error("shacl-recursion",
                "recursive shape: " + cycle + " while validating focus node " + show(focus) +
                    " (recursive shapes are not supported)",
                file, s.where.line, s.where.column);
  }

  std::string show(TermId v) const {
    return v.index < base_ ? rdf::to_ntriples(dt_, v)
                           : rdf::to_ntriples(extra_, overlay_[v.index - base_]);
  }

  void evaluate(uint32_t shape, uint32_t k, TermId focus, const std::vector<TermId>& values,
                Sink& sink) {
    const Shape& s = shapes_[shape];
    const Constraint& c = s.constraints[k];
    const PathSource path = s.is_property ? PathSource::Shape : PathSource::None;
    auto report = [&](TermId value) {
      RawResult r;
      r.focus = focus;
      r.value = value;
      r.shape = shape;
      r.constraint = k;
      r.component = c.component;
      r.path = path;
      sink.add(r);
    };
    auto each = [&](auto&& fails) {
      for (TermId v : values) {
        if (sink.done()) return;
        if (fails(v)) report(v);
      }
    };
    switch (c.component) {
      case Component::Class: {
        TermId cls = map(c.term);
        each([&](TermId v) { return !is_instance(v, cls); });
        return;
      }
      case Component::Datatype:
        each([&](TermId v) { return !has_datatype(v, c.term); });
        return;
      case Component::NodeKind:
        each([&](TermId v) {
          const rdf::Term& t = term(v);
          uint8_t kind = t.is_blank() ? kBlankNode : t.is_iri() ? kIri : kLiteral;
          return (c.node_kinds & kind) == 0;
        });
        return;
      case Component::MinCount:
        if (static_cast<int64_t>(values.size()) < c.number) report(TermId::any());
        return;
      case Component::MaxCount:
        if (static_cast<int64_t>(values.size()) > c.number) report(TermId::any());
        return;
      case Component::MinExclusive:
      case Component::MinInclusive:
      case Component::MaxExclusive:
      case Component::MaxInclusive: {
        const LiteralView bound = shape_literal(c.term);
        each([&](TermId v) {
          if (!term(v).is_literal()) return true;
          Order o = compare_literals(bound, literal(v));
          switch (c.component) {
            case Component::MinExclusive:
              return o != Order::Less;
            case Component::MinInclusive:
              return o != Order::Less && o != Order::Equal;
            case Component::MaxExclusive:
              return o != Order::Greater;
            default:
              return o != Order::Greater && o != Order::Equal;
          }
        });
        return;
      }
      case Component::MinLength:
      case Component::MaxLength:
        each([&](TermId v) {
          if (term(v).is_blank()) return true;
          int64_t n = static_cast<int64_t>(utf8_length(str(v)));
          return c.component == Component::MinLength ? n < c.number : n > c.number;
        });
        return;
      case Component::Pattern:
        each([&](TermId v) {
          if (term(v).is_blank()) return true;
          std::string_view text = str(v);
          return !c.regex->search(text);
        });
        return;
      case Component::LanguageIn:
        each([&](TermId v) {
          const rdf::Term& t = term(v);
          if (!t.is_literal() || t.language.empty()) return true;
          for (const std::string& range : c.ranges)
            if (lang_matches(t.language, range)) return false;
          return true;
        });
        return;
      case Component::UniqueLang: {
        std::vector<std::string> tags;
        for (TermId v : values) {
          std::string tag(term(v).language);
          if (tag.empty()) continue;
          for (char& ch : tag) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
          tags.push_back(std::move(tag));
        }
        std::sort(tags.begin(), tags.end());
        for (size_t i = 0; i + 1 < tags.size(); ++i) {
          if (tags[i] != tags[i + 1]) continue;
          report(TermId::any());
          while (i + 1 < tags.size() && tags[i] == tags[i + 1]) ++i;
        }
        return;
      }
      case Component::Equals: {
        std::vector<TermId> others;
        objects(focus, map(c.term), others);
        std::vector<TermId> sorted = values;
        dedupe(sorted);
        each([&](TermId v) { return !std::binary_search(others.begin(), others.end(), v); });
        for (TermId o : others)
          if (!sink.done() && !std::binary_search(sorted.begin(), sorted.end(), o)) report(o);
        return;
      }
      case Component::Disjoint: {
        std::vector<TermId> others;
        objects(focus, map(c.term), others);
        each([&](TermId v) { return std::binary_search(others.begin(), others.end(), v); });
        return;
      }
      case Component::LessThan:
      case Component::LessThanOrEquals: {
        std::vector<TermId> others;
        objects(focus, map(c.term), others);
        for (TermId v : values) {
          for (TermId o : others) {
            if (sink.done()) return;
            Order ord = term(v).is_literal() && term(o).is_literal()
                            ? compare_literals(literal(v), literal(o))
                            : Order::Incomparable;
            bool ok = ord == Order::Less ||
                      (c.component == Component::LessThanOrEquals && ord == Order::Equal);
            if (!ok) report(v);
          }
        }
        return;
      }
      case Component::Not:
        each([&](TermId v) { return conforms(c.shapes[0], v); });
        return;
      case Component::And:
        each([&](TermId v) {
          for (uint32_t m : c.shapes)
            if (!conforms(m, v)) return true;
          return false;
        });
        return;
      case Component::Or:
        each([&](TermId v) {
          for (uint32_t m : c.shapes)
            if (conforms(m, v)) return false;
          return true;
        });
        return;
      case Component::Xone:
        each([&](TermId v) {
          int n = 0;
          for (uint32_t m : c.shapes) n += conforms(m, v) ? 1 : 0;
          return n != 1;
        });
        return;
      case Component::Node:
        each([&](TermId v) { return !conforms(c.shapes[0], v); });
        return;
      case Component::Property:
        for (TermId v : values) {
          if (sink.done()) return;
          validate_shape(c.shapes[0], v, sink);
        }
        return;
      case Component::QualifiedMinCount:
      case Component::QualifiedMaxCount: {
        int64_t n = 0;
        for (TermId v : values) {
          if (!conforms(c.shapes[0], v)) continue;
          bool sibling = false;
          for (uint32_t sib : c.siblings)
            if (conforms(sib, v)) {
              sibling = true;
              break;
            }
          if (!sibling) ++n;
        }
        bool fails = c.component == Component::QualifiedMinCount ? n < c.number : n > c.number;
        if (fails) report(TermId::any());
        return;
      }
      case Component::Closed: {
        const std::vector<TermId>& allowed = bound_[shape][k];
        std::vector<std::pair<TermId, TermId>> extra;  // (predicate, object)
        for (TermId v : values) {
          extra.clear();
          data_.scan(v, TermId::any(), TermId::any(), TermId::any(),
                     [&](const rdf::Quad& q, uint32_t) {
                       if (!std::binary_search(allowed.begin(), allowed.end(), q.predicate))
                         extra.emplace_back(q.predicate, q.object);
                       return true;
                     });
          // A triple may sit in several graphs; report it once.
          std::sort(extra.begin(), extra.end());
          extra.erase(std::unique(extra.begin(), extra.end()), extra.end());
          for (auto [predicate, object] : extra) {
            if (sink.done()) return;
            RawResult r;
            r.focus = focus;
            r.value = object;
            r.shape = shape;
            r.constraint = k;
            r.component = c.component;
            r.path = PathSource::Predicate;
            r.predicate = predicate;
            sink.add(std::move(r));
          }
        }
        return;
      }
      case Component::HasValue: {
        TermId wanted = map(c.term);
        if (std::find(values.begin(), values.end(), wanted) == values.end()) report(TermId::any());
        return;
      }
      case Component::In: {
        const std::vector<TermId>& members = bound_[shape][k];
        each([&](TermId v) { return !std::binary_search(members.begin(), members.end(), v); });
        return;
      }
      case Component::Sparql:
      case Component::SparqlComponent:
        evaluate_sparql(shape, k, focus, values, sink);
        return;
    }
  }

  // ---- SHACL-SPARQL -----------------------------------------------------

  // Evaluator ids: data ids as they are, every other term imported.
  TermId to_eval(TermId v) {
    if (v.index < base_) return v;
    return eval_->import(extra_, overlay_[v.index - base_]);
  }

  TermId from_eval(TermId e) {
    if (e.index < base_) return e;
    auto [table, id] = eval_->locate(e);
    return outside(extra_.import(*table, id));
  }

  // A term as message text: a literal's lexical form, else N-Triples.
  std::string eval_text(TermId v) const {
    const rdf::Term& t = eval_->term(v);
    return t.is_literal() ? std::string(t.value) : eval_->to_ntriples(v);
  }

  std::string shape_text(TermId v) const {
    const rdf::Term& t = st_[v];
    return t.is_literal() ? std::string(t.value) : rdf::to_ntriples(st_, v);
  }

  // {?var} / {$var} in a message, replaced by lookup(var) (left as written
  // when the lookup has no value).
  template <typename Lookup>
  static std::string substitute(std::string_view text, const Lookup& lookup) {
    std::string out;
    for (size_t i = 0; i < text.size(); ++i) {
      if (text[i] == '{' && i + 2 < text.size() && (text[i + 1] == '?' || text[i + 1] == '$')) {
        size_t close = text.find('}', i + 2);
        if (close != std::string_view::npos) {
          if (std::optional<std::string> value = lookup(text.substr(i + 2, close - i - 2))) {
            out += *value;
            i = close;
            continue;
          }
        }
      }
      out += text[i];
    }
    return out;
  }

  // "SPARQL constraint _:b" or "validator _:v of constraint component <C>".
  std::string describe_sparql(const SparqlConstraint& q) const {
    if (q.component.is_any()) return "SPARQL constraint " + rdf::to_ntriples(st_, q.node);
    return "validator " + rdf::to_ntriples(st_, q.node) + " of constraint component " +
           rdf::to_ntriples(st_, q.component);
  }

  // A parameter of a SPARQL-based constraint component, for messages.
  std::optional<std::string> parameter_text(const SparqlConstraint& q,
                                            std::string_view name) const {
    for (const auto& [param, value] : q.parameters)
      if (param == name) return shape_text(value);
    return std::nullopt;
  }

  void evaluate_sparql(uint32_t shape, uint32_t k, TermId focus, const std::vector<TermId>& values,
                       Sink& sink) {
    const Shape& s = shapes_[shape];
    const SparqlConstraint& q = *s.constraints[k].sparql;
    if (!eval_) {
      eval_ = std::make_unique<sparql::Evaluator>(data_);
      eval_->set_limits(budget_->limits());
      eval_->set_budget(budget_);
    }
    std::vector<sparql::Binding> bindings{{"this", to_eval(focus)}};
    if (q.binds_current_shape) bindings.push_back({"currentShape", eval_->import(st_, s.node)});
    for (const auto& [name, value] : q.parameters)
      bindings.push_back({name, eval_->import(st_, value)});
    auto result = [&]() {
      RawResult r;
      r.focus = focus;
      r.shape = shape;
      r.constraint = k;
      r.component = s.constraints[k].component;
      if (q.component.is_any()) r.source_constraint = q.node;  // sh:sparql only
      r.component_node = q.component;
      r.own_messages = true;
      return r;
    };
    if (q.ask) {
      // SHACL 6.3: one ASK per value node; false means the value node fails.
      bindings.push_back({"value", TermId::any()});
      for (TermId v : values) {
        if (sink.done()) return;
        bindings.back().value = to_eval(v);
        bool conforms = false;
        try {
          conforms = eval_->ask(q.query, bindings);
        } catch (const Error& e) {
          if (e.code() != "sparql-limit") throw;
          limit_reached(s.constraints[k].where,
                        describe_sparql(q) + " of shape " + shapes_.describe(shape) +
                            " on focus node " + show(focus) + ", value node " + show(v),
                        e);
        }
        if (conforms) continue;
        RawResult r = result();
        r.value = v;
        if (s.is_property) r.path = PathSource::Shape;
        for (TermId m : q.messages)
          r.messages.emplace_back(
              substitute(st_[m].value,
                         [&](std::string_view name) -> std::optional<std::string> {
                           if (name == "this") return eval_text(bindings[0].value);
                           if (name == "value") return eval_text(bindings.back().value);
                           return parameter_text(q, name);
                         }),
              std::string(st_[m].language));
        sink.add(std::move(r));
      }
      return;
    }
    sparql::ResultSet rows;
    try {
      eval_->select(q.query, bindings, rows);
    } catch (const Error& e) {
      if (e.code() != "sparql-limit") throw;
      limit_reached(s.constraints[k].where,
                    describe_sparql(q) + " of shape " + shapes_.describe(shape) +
                        " on focus node " + show(focus),
                    e);
    }
    const int value_col = rows.column("value"), path_col = rows.column("path"),
              message_col = rows.column("message"), failure_col = rows.column("failure");
    auto bound = [&](int col, size_t row) {
      return col >= 0 && rows.at(row, static_cast<size_t>(col)) != sparql::kUnbound;
    };
    for (size_t row = 0; row < rows.size() && !sink.done(); ++row) {
      if (bound(failure_col, row)) {
        const rdf::Term& f = eval_->term(rows.at(row, static_cast<size_t>(failure_col)));
        if (f.is_literal() && (f.value == "true" || f.value == "1")) {
          const SourceLoc& at = s.constraints[k].where;
          std::string file =
              shapes_.files() != nullptr && at.known() ? shapes_.files()->path(at.file) : "";
          throw Error("shacl-failure",
                      describe_sparql(q) + " of shape " + shapes_.describe(shape) +
                          " reported a failure for focus node " + show(focus),
                      file, at.line, at.column);
        }
      }
      RawResult r = result();
      if (bound(value_col, row))
        r.value = from_eval(rows.at(row, static_cast<size_t>(value_col)));
      else if (!s.is_property)
        r.value = focus;
      TermId path =
          bound(path_col, row) ? rows.at(row, static_cast<size_t>(path_col)) : sparql::kUnbound;
      if (path != sparql::kUnbound && eval_->term(path).is_iri()) {
        r.path = PathSource::Predicate;
        r.predicate = from_eval(path);
      } else if (s.is_property) {
        r.path = PathSource::Shape;
      }
      for (size_t c = 0; c < rows.variables.size(); ++c) {
        const std::string& name = rows.variables[c];
        if (name == "this" || name == "value" || name == "path" || name == "message" ||
            name == "failure" || !bound(static_cast<int>(c), row))
          continue;
        const TermId node = from_eval(rows.at(row, c));
        if (node.index < base_ && !dt_[node].is_literal()) r.related.emplace_back(name, node);
      }
      if (bound(message_col, row)) {
        const rdf::Term& m = eval_->term(rows.at(row, static_cast<size_t>(message_col)));
        r.messages.emplace_back(std::string(m.value), std::string(m.language));
      } else {
        for (TermId m : q.messages)
          r.messages.emplace_back(
              substitute(st_[m].value,
                         [&](std::string_view name) -> std::optional<std::string> {
                           int col = rows.column(name);
                           if (col >= 0) {
                             TermId v = rows.at(row, static_cast<size_t>(col));
                             return v == sparql::kUnbound ? std::string() : eval_text(v);
                           }
                           return parameter_text(q, name);
                         }),
              std::string(st_[m].language));
      }
      sink.add(std::move(r));
    }
  }

  // ---- report ------------------------------------------------------------

  TermId import(Report& r, TermId v) const {
    if (v.index >= base_) {
      const TermId x = overlay_[v.index - base_];
      if (extra_[x].is_blank() && !same_) return r.terms.blank("s_" + std::string(extra_[x].value));
      return r.terms.import(extra_, x);
    }
    const rdf::Term& t = dt_[v];
    // Blank nodes of two tables may share labels; keep the two apart.
    if (t.is_blank() && !same_) return r.terms.blank("d_" + std::string(t.value));
    return r.terms.import(dt_, v);
  }

  TermId import_shape_term(Report& r, TermId s) const {
    const rdf::Term& t = st_[s];
    if (t.is_blank() && !same_) return r.terms.blank("s_" + std::string(t.value));
    return r.terms.import(st_, s);
  }

  sparql::PathPtr import_path(Report& r, const sparql::Path& p) const {
    if (p.kind == sparql::Path::Kind::Predicate)
      return sparql::Path::iri(import_shape_term(r, p.predicate));
    std::vector<sparql::PathPtr> items;
    for (const auto& item : p.items) items.push_back(import_path(r, *item));
    return sparql::Path::make(p.kind, std::move(items));
  }

  std::string default_message(const RawResult& raw) const {
    const Shape& s = shapes_[raw.shape];
    const Constraint& c = s.constraints[raw.constraint];
    auto shape_term = [&](TermId t) { return rdf::to_ntriples(st_, t); };
    auto count = [](int64_t n) { return std::to_string(n) + (n == 1 ? " value" : " values"); };
    switch (c.component) {
      case Component::Class:
        return "value is not an instance of " + shape_term(c.term);
      case Component::Datatype:
        return "value does not have datatype " + shape_term(c.term);
      case Component::NodeKind: {
        std::string kinds;
        for (auto [bit, name] :
             {std::pair{kBlankNode, "blank node"}, {kIri, "IRI"}, {kLiteral, "literal"}})
          if ((c.node_kinds & bit) != 0) kinds += (kinds.empty() ? "" : " or ") + std::string(name);
        return "value is not a " + kinds;
      }
      case Component::MinCount:
        return "fewer than " + count(c.number);
      case Component::MaxCount:
        return "more than " + count(c.number);
      case Component::MinExclusive:
        return "value is not > " + shape_term(c.term);
      case Component::MinInclusive:
        return "value is not >= " + shape_term(c.term);
      case Component::MaxExclusive:
        return "value is not < " + shape_term(c.term);
      case Component::MaxInclusive:
        return "value is not <= " + shape_term(c.term);
      case Component::MinLength:
        return "value is shorter than " + std::to_string(c.number) + " characters";
      case Component::MaxLength:
        return "value is longer than " + std::to_string(c.number) + " characters";
      case Component::Pattern:
        return "value does not match the sh:pattern";
      case Component::LanguageIn:
        return "language tag is not in sh:languageIn";
      case Component::UniqueLang:
        return "a language tag is used more than once";
      case Component::Equals:
        return "values differ from those of " + shape_term(c.term);
      case Component::Disjoint:
        return "value is also a value of " + shape_term(c.term);
      case Component::LessThan:
        return "value is not less than the values of " + shape_term(c.term);
      case Component::LessThanOrEquals:
        return "value is not less than or equal to the values of " + shape_term(c.term);
      case Component::Not:
        return "value conforms to " + shapes_.describe(c.shapes[0]) + " (sh:not)";
      case Component::And:
        return "value does not conform to every shape of sh:and";
      case Component::Or:
        return "value conforms to none of the shapes of sh:or";
      case Component::Xone:
        return "value does not conform to exactly one shape of sh:xone";
      case Component::Node:
        return "value does not conform to " + shapes_.describe(c.shapes[0]);
      case Component::Property:
        return "property shape failed";
      case Component::QualifiedMinCount:
        return "fewer than " + count(c.number) + " conform to " + shapes_.describe(c.shapes[0]);
      case Component::QualifiedMaxCount:
        return "more than " + count(c.number) + " conform to " + shapes_.describe(c.shapes[0]);
      case Component::Closed:
        return "predicate is not allowed (closed shape)";
      case Component::HasValue:
        return "missing value " + shape_term(c.term);
      case Component::In:
        return "value is not in sh:in";
      case Component::Sparql:
        return "violates SPARQL constraint " + rdf::to_ntriples(st_, c.sparql->node);
      case Component::SparqlComponent: {
        // The component's label template (untagged or English first), with
        // its parameters filled in.
        const SparqlConstraint& q = *c.sparql;
        for (std::string_view want : {std::string_view(), std::string_view("en")})
          for (TermId label : q.labels)
            if (st_[label].language == want)
              return substitute(st_[label].value,
                                [&](std::string_view name) { return parameter_text(q, name); });
        if (!q.labels.empty())
          return substitute(st_[q.labels[0]].value,
                            [&](std::string_view name) { return parameter_text(q, name); });
        return "violates constraint component " + rdf::to_ntriples(st_, q.component);
      }
    }
    return {};
  }

  // Where the focus node is written: the caller's answer, else the first
  // located triple that has it as subject (or, failing that, as object).
  SourceLoc locate(TermId focus) const {
    if (options_.locate) return options_.locate(focus).value_or(SourceLoc{});
    SourceLoc found;
    auto visit = [&](const rdf::Quad&, uint32_t i) {
      found = data_.location(i);
      return !found.known();
    };
    data_.scan(focus, TermId::any(), TermId::any(), TermId::any(), visit);
    // A node that is never a subject is at least mentioned as an object.
    if (!found.known()) data_.scan(TermId::any(), TermId::any(), focus, TermId::any(), visit);
    return found;
  }

  // Where a node a result names is written, as the user reads it. A node the
  // data describes (a subject) is where it is described. A node that is only
  // ever an object, shared by many nodes (a unit, a quantity kind), has no
  // place of its own: it is located where the result's nodes use it, the
  // focus first, then the value, then a node the focus names (the
  // constrained quantity of a constraint), so a note never points at an
  // unrelated node in another file that happens to use it first.
  SourceLoc locate_near(TermId node, TermId focus, TermId value) const {
    if (options_.locate) return locate(node);
    bool described = false;
    data_.scan(node, TermId::any(), TermId::any(), TermId::any(), [&](const rdf::Quad&, uint32_t) {
      described = true;
      return false;
    });
    if (described) return locate(node);
    const auto used_by = [&](TermId user) {
      SourceLoc found;
      if (user.is_any() || user.index >= base_ || dt_[user].is_literal()) return found;
      data_.scan(user, TermId::any(), node, TermId::any(), [&](const rdf::Quad&, uint32_t i) {
        found = data_.location(i);
        return !found.known();
      });
      return found;
    };
    for (TermId user : {focus, value}) {
      if (SourceLoc at = used_by(user); at.known()) return at;
    }
    SourceLoc found;
    data_.scan(focus, TermId::any(), TermId::any(), TermId::any(),
               [&](const rdf::Quad& q, uint32_t) {
                 if (q.object == node || q.object == focus) return true;
                 found = used_by(q.object);
                 return !found.known();
               });
    return found.known() ? found : locate(node);
  }

  Report render(const std::vector<RawResult>& raw) const {
    Report report;
    report.results.reserve(raw.size());
    for (const RawResult& x : raw) {
      const Shape& s = shapes_[x.shape];
      Result r;
      r.focus = import(report, x.focus);
      if (!x.value.is_any()) r.value = import(report, x.value);
      r.shape = import_shape_term(report, s.node);
      r.component = x.component;
      if (x.path == PathSource::Shape) r.path = import_path(report, *s.path);
      if (x.path == PathSource::Predicate) r.path = sparql::Path::iri(import(report, x.predicate));
      r.level = s.level;
      if (s.level == Level::Other) r.severity = import_shape_term(report, s.severity);
      // SHACL-SPARQL results carry their own messages (?message, the
      // constraint's, validator's or component's); without any, the shape's.
      if (x.own_messages && !x.messages.empty()) {
        for (const auto& [text, language] : x.messages)
          r.messages.push_back(report.terms.literal(text, TermId::default_graph(), language));
      } else {
        for (TermId m : s.messages) r.messages.push_back(import_shape_term(report, m));
      }
      if (!x.source_constraint.is_any())
        r.source_constraint = import_shape_term(report, x.source_constraint);
      if (!x.component_node.is_any())
        r.component_node = import_shape_term(report, x.component_node);
      if (r.messages.empty()) r.default_message = default_message(x);
      if (x.focus.index < base_) r.focus_loc = locate(x.focus);
      // Where the value is written, unless that is only where the focus uses
      // it (a node nothing describes is located at its first use).
      if (!x.value.is_any() && x.value != x.focus && x.value.index < base_ &&
          !dt_[x.value].is_literal()) {
        const SourceLoc at = locate_near(x.value, x.focus, TermId::any());
        if (!(at.file == r.focus_loc.file && at.line == r.focus_loc.line &&
              at.column == r.focus_loc.column))
          r.value_loc = at;
      }
      for (const auto& [name, node] : x.related) {
        if (SourceLoc at = locate_near(node, x.focus, x.value); at.known())
          r.related.push_back({name, import(report, node), at});
      }
      r.shape_loc = s.where;
      report.results.push_back(std::move(r));
    }
    report.sort();
    return report;
  }

  const Shapes& shapes_;
  const rdf::Dataset& data_;
  const rdf::TermTable& dt_;
  const rdf::TermTable& st_;
  const bool same_;
  const uint32_t base_;
  const ValidateOptions& options_;
  TermId type_, subclass_;
  std::vector<TermId> to_data_;
  // Terms outside the data graph (validation ids from base_ up) live in extra_.
  rdf::TermTable extra_;
  std::vector<TermId> overlay_;                       // validation id - base_ -> id in extra_
  std::unordered_map<uint32_t, TermId> outside_ids_;  // id in extra_ -> validation id
  std::vector<sparql::PathPtr> paths_;
  // Buffers every sh:path reuses (value_nodes() is const: they hold no result).
  mutable sparql::PathWorkspace path_workspace_;
  std::vector<std::vector<std::vector<TermId>>> bound_;
  std::unordered_map<uint32_t, std::vector<TermId>> subclasses_;
  std::vector<uint8_t> well_formed_;
  std::unordered_map<uint64_t, bool> conforms_cache_;
  std::unordered_set<uint64_t> active_;
  std::vector<uint32_t> stack_;
  std::unique_ptr<sparql::Evaluator> eval_;
  // One budget for every SPARQL evaluation and path of the run (or the
  // caller's, shared by the whole command).
  std::optional<sparql::Budget> own_budget_;
  sparql::Budget* budget_ = nullptr;
};

}  // namespace

Report validate(const Shapes& shapes, const rdf::Dataset& data, const ValidateOptions& options) {
  return Validator(shapes, data, options).run();
}

namespace detail {

void check_component_parameters(const Shapes& shapes) {
  const ValidateOptions options;
  std::unique_ptr<Validator> validator;  // made when a declaration has constraints
  std::unordered_set<uint64_t> done;     // (shape, parameter shape)
  for (uint32_t i = 0; i < shapes.shapes().size(); ++i) {
    const Shape& s = shapes[i];
    for (const Constraint& c : s.constraints) {
      if (c.component != Component::SparqlComponent) continue;
      for (uint32_t p : c.sparql->parameter_shapes) {
        if (!done.insert(pair_key(p, TermId{i})).second) continue;
        if (!validator) validator = std::make_unique<Validator>(shapes, shapes.graph(), options);
        const std::string failure = validator->first_failure(p, s.node);
        if (failure.empty()) continue;
        const Shape& declaration = shapes[p];
        const SourceFiles* files = shapes.files();
        std::string file = files != nullptr && c.where.known() ? files->path(c.where.file) : "";
        const rdf::TermTable& t = shapes.graph().terms();
        throw Error("shacl-ill-formed",
                    "shape " + shapes.describe(i) + ": a value of parameter " +
                        (declaration.path ? path_to_sparql(t, *declaration.path) : "?") +
                        " of constraint component " + rdf::to_ntriples(t, c.sparql->component) +
                        " does not conform to the parameter's declaration" +
                        (declaration.where.known()
                             ? " (at " + describe_location(files, declaration.where) + ")"
                             : std::string()) +
                        ": " + failure,
                    file, c.where.line, c.where.column);
      }
    }
  }
}

}  // namespace detail

std::vector<size_t> count_focus_nodes(const Shapes& shapes, const rdf::Dataset& data) {
  ValidateOptions options;
  return Validator(shapes, data, options).focus_counts();
}

}  // namespace mospec::shacl
