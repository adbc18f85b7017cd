#include "shacl/shapes.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <optional>
#include <unordered_map>
#include <unordered_set>

#include "shacl/literal.hpp"
#include "shacl/vocab.hpp"

namespace mospec::shacl {

namespace {

using rdf::TermId;

// Matches nothing in any dataset: Dataset::scan treats ids beyond its term
// table as absent, whereas TermId::any() would be a wildcard.
constexpr TermId kAbsent{UINT32_MAX - 1};

struct ComponentInfo {
  std::string_view iri;
  std::string_view name;
};

constexpr std::array<ComponentInfo, 30> kComponents{{
    {"http://www.w3.org/ns/shacl#ClassConstraintComponent", "sh:ClassConstraintComponent"},
    {"http://www.w3.org/ns/shacl#DatatypeConstraintComponent", "sh:DatatypeConstraintComponent"},
    {"http://www.w3.org/ns/shacl#NodeKindConstraintComponent", "sh:NodeKindConstraintComponent"},
    {"http://www.w3.org/ns/shacl#MinCountConstraintComponent", "sh:MinCountConstraintComponent"},
    {"http://www.w3.org/ns/shacl#MaxCountConstraintComponent", "sh:MaxCountConstraintComponent"},
    {"http://www.w3.org/ns/shacl#MinExclusiveConstraintComponent",
     "sh:MinExclusiveConstraintComponent"},
    {"http://www.w3.org/ns/shacl#MinInclusiveConstraintComponent",
     "sh:MinInclusiveConstraintComponent"},
    {"http://www.w3.org/ns/shacl#MaxExclusiveConstraintComponent",
     "sh:MaxExclusiveConstraintComponent"},
    {"http://www.w3.org/ns/shacl#MaxInclusiveConstraintComponent",
     "sh:MaxInclusiveConstraintComponent"},
    {"http://www.w3.org/ns/shacl#MinLengthConstraintComponent", "sh:MinLengthConstraintComponent"},
    {"http://www.w3.org/ns/shacl#MaxLengthConstraintComponent", "sh:MaxLengthConstraintComponent"},
    {"http://www.w3.org/ns/shacl#PatternConstraintComponent", "sh:PatternConstraintComponent"},
    {"http://www.w3.org/ns/shacl#LanguageInConstraintComponent",
     "sh:LanguageInConstraintComponent"},
    {"http://www.w3.org/ns/shacl#UniqueLangConstraintComponent",
     "sh:UniqueLangConstraintComponent"},
    {"http://www.w3.org/ns/shacl#EqualsConstraintComponent", "sh:EqualsConstraintComponent"},
    {"http://www.w3.org/ns/shacl#DisjointConstraintComponent", "sh:DisjointConstraintComponent"},
    {"http://www.w3.org/ns/shacl#LessThanConstraintComponent", "sh:LessThanConstraintComponent"},
    {"http://www.w3.org/ns/shacl#LessThanOrEqualsConstraintComponent",
     "sh:LessThanOrEqualsConstraintComponent"},
    {"http://www.w3.org/ns/shacl#NotConstraintComponent", "sh:NotConstraintComponent"},
    {"http://www.w3.org/ns/shacl#AndConstraintComponent", "sh:AndConstraintComponent"},
    {"http://www.w3.org/ns/shacl#OrConstraintComponent", "sh:OrConstraintComponent"},
    {"http://www.w3.org/ns/shacl#XoneConstraintComponent", "sh:XoneConstraintComponent"},
    {"http://www.w3.org/ns/shacl#NodeConstraintComponent", "sh:NodeConstraintComponent"},
    {"http://www.w3.org/ns/shacl#PropertyConstraintComponent", "sh:PropertyConstraintComponent"},
    {"http://www.w3.org/ns/shacl#QualifiedMinCountConstraintComponent",
     "sh:QualifiedMinCountConstraintComponent"},
    {"http://www.w3.org/ns/shacl#QualifiedMaxCountConstraintComponent",
     "sh:QualifiedMaxCountConstraintComponent"},
    {"http://www.w3.org/ns/shacl#ClosedConstraintComponent", "sh:ClosedConstraintComponent"},
    {"http://www.w3.org/ns/shacl#HasValueConstraintComponent", "sh:HasValueConstraintComponent"},
    {"http://www.w3.org/ns/shacl#InConstraintComponent", "sh:InConstraintComponent"},
    {"http://www.w3.org/ns/shacl#SPARQLConstraintComponent", "sh:SPARQLConstraintComponent"},
}};

std::string term_text(const rdf::TermTable& t, TermId id) {
  return rdf::to_ntriples(t, id);
}

}  // namespace

std::string_view component_iri(Component c) {
  return kComponents[static_cast<size_t>(c)].iri;
}
std::string_view component_name(Component c) {
  return kComponents[static_cast<size_t>(c)].name;
}

std::string describe_location(const SourceFiles* files, SourceLoc loc) {
  if (!loc.known()) return {};
  std::string out = files != nullptr ? files->path(loc.file) : std::string();
  if (out.empty()) out = "<input>";
  out += ':' + std::to_string(loc.line);
  if (loc.column != 0) out += ':' + std::to_string(loc.column);
  return out;
}

std::string path_to_sparql(const rdf::TermTable& terms, const sparql::Path& p) {
  using K = sparql::Path::Kind;
  auto item = [&](size_t i) {
    const sparql::Path& sub = *p.items[i];
    std::string s = path_to_sparql(terms, sub);
    return sub.kind == K::Predicate ? s : "(" + s + ")";
  };
  auto joined = [&](std::string_view sep) {
    std::string s;
    for (size_t i = 0; i < p.items.size(); ++i) {
      if (i != 0) s += sep;
      s += item(i);
    }
    return s;
  };
  switch (p.kind) {
    case K::Predicate:
      return rdf::to_ntriples(terms, p.predicate);
    case K::Inverse:
      return "^" + item(0);
    case K::Sequence:
      return joined("/");
    case K::Alternative:
      return joined("|");
    case K::ZeroOrMore:
      return item(0) + "*";
    case K::OneOrMore:
      return item(0) + "+";
    case K::ZeroOrOne:
      return item(0) + "?";
    case K::NegatedSet:
      return "!(...)";
  }
  return {};
}

std::string Shapes::describe(uint32_t shape) const {
  const Shape& s = shapes_[shape];
  const rdf::TermTable& t = graph_->terms();
  if (t[s.node].is_iri()) return "<" + std::string(t[s.node].value) + ">";
  std::string where = describe_location(files_, s.where);
  std::string out = "[]";
  if (s.is_property && s.path) out = "[sh:path " + path_to_sparql(t, *s.path) + "]";
  if (!where.empty()) out += " at " + where;
  return out;
}

class ShapesCompiler {
 public:
  ShapesCompiler(const rdf::Dataset& g, const SourceFiles* files) : g_(g), t_(g.terms()) {
    out_.graph_ = &g;
    out_.files_ = files;
    auto sh = [&](std::string_view iri) {
      TermId id = t_.find_iri(iri);
      return id.is_any() ? kAbsent : id;
    };
    type_ = sh(vocab::rdf_type);
    first_ = sh(vocab::rdf_first);
    rest_ = sh(vocab::rdf_rest);
    nil_ = sh(vocab::rdf_nil);
    subclass_ = sh(vocab::rdfs_subclass_of);
    rdfs_class_ = sh(vocab::rdfs_class);
    node_shape_ = sh(vocab::NodeShape);
    property_shape_ = sh(vocab::PropertyShape);
    violation_ = sh(vocab::Violation);
    warning_ = sh(vocab::Warning);
    info_ = sh(vocab::Info);
    for (auto [iri, slot] : std::initializer_list<std::pair<std::string_view, TermId*>>{
             {vocab::path, &path_},
             {vocab::targetNode, &target_node_},
             {vocab::targetClass, &target_class_},
             {vocab::targetSubjectsOf, &target_subjects_},
             {vocab::targetObjectsOf, &target_objects_},
             {vocab::deactivated, &deactivated_},
             {vocab::severity, &severity_},
             {vocab::message, &message_},
             {vocab::alternativePath, &alternative_},
             {vocab::inversePath, &inverse_},
             {vocab::zeroOrMorePath, &zero_or_more_},
             {vocab::oneOrMorePath, &one_or_more_},
             {vocab::zeroOrOnePath, &zero_or_one_},
             {vocab::flags, &flags_},
             {vocab::qualifiedValueShape, &qvs_},
             {vocab::qualifiedMinCount, &qmin_},
             {vocab::qualifiedMaxCount, &qmax_},
             {vocab::qualifiedValueShapesDisjoint, &qdisjoint_},
             {vocab::ignoredProperties, &ignored_},
             {vocab::property, &property_},
             {vocab::select, &select_},
             {vocab::prefixes, &prefixes_},
             {vocab::declare, &declare_},
             {vocab::prefix, &prefix_},
             {vocab::sh_namespace, &namespace_},
             {vocab::owl_imports, &owl_imports_},
             {vocab::BlankNode, &nk_blank_},
             {vocab::IRI, &nk_iri_},
             {vocab::Literal, &nk_literal_},
             {vocab::BlankNodeOrIRI, &nk_blank_iri_},
             {vocab::BlankNodeOrLiteral, &nk_blank_literal_},
             {vocab::IRIOrLiteral, &nk_iri_literal_},
         })
      *slot = sh(iri);
    for (auto [iri, c] : std::initializer_list<std::pair<std::string_view, Component>>{
             {vocab::sh_class, Component::Class},
             {vocab::datatype, Component::Datatype},
             {vocab::nodeKind, Component::NodeKind},
             {vocab::minCount, Component::MinCount},
             {vocab::maxCount, Component::MaxCount},
             {vocab::minExclusive, Component::MinExclusive},
             {vocab::minInclusive, Component::MinInclusive},
             {vocab::maxExclusive, Component::MaxExclusive},
             {vocab::maxInclusive, Component::MaxInclusive},
             {vocab::minLength, Component::MinLength},
             {vocab::maxLength, Component::MaxLength},
             {vocab::pattern, Component::Pattern},
             {vocab::languageIn, Component::LanguageIn},
             {vocab::uniqueLang, Component::UniqueLang},
             {vocab::equals, Component::Equals},
             {vocab::disjoint, Component::Disjoint},
             {vocab::lessThan, Component::LessThan},
             {vocab::lessThanOrEquals, Component::LessThanOrEquals},
             {vocab::sh_not, Component::Not},
             {vocab::sh_and, Component::And},
             {vocab::sh_or, Component::Or},
             {vocab::xone, Component::Xone},
             {vocab::node, Component::Node},
             {vocab::property, Component::Property},
             {vocab::closed, Component::Closed},
             {vocab::hasValue, Component::HasValue},
             {vocab::sh_in, Component::In},
             {vocab::sparql, Component::Sparql},
         }) {
      TermId id = sh(iri);
      if (id != kAbsent) params_.emplace(id.index, c);
    }
    for (TermId p : {qvs_, qmin_, qmax_})
      if (p != kAbsent) params_.emplace(p.index, Component::QualifiedMinCount);
  }

  Shapes run() {
    // Every node that the spec calls a shape, in the order it is first written.
    std::vector<std::pair<uint32_t, TermId>> candidates;
    std::unordered_set<uint32_t> seen;
    auto add = [&](TermId node, uint32_t quad) {
      if (t_[node].is_literal()) return;
      if (seen.insert(node.index).second) candidates.emplace_back(quad, node);
    };
    for (TermId cls : shape_classes()) {
      g_.scan(TermId::any(), type_, cls, TermId::any(), [&](const rdf::Quad& q, uint32_t i) {
        add(q.subject, i);
        return true;
      });
    }
    std::vector<TermId> subject_preds{target_node_, target_class_, target_subjects_,
                                      target_objects_};
    for (auto [p, c] : params_) subject_preds.push_back(TermId{p});
    for (TermId p : subject_preds) {
      g_.scan(TermId::any(), p, TermId::any(), TermId::any(), [&](const rdf::Quad& q, uint32_t i) {
        add(q.subject, i);
        return true;
      });
    }
    std::sort(candidates.begin(), candidates.end());
    for (auto& [quad, node] : candidates) compile(node);
    finish();
    return std::move(out_);
  }

 private:
  std::vector<TermId> shape_classes() {
    // SHACL instances of sh:NodeShape / sh:PropertyShape include instances of
    // their subclasses (rare, but cheap to honour).
    std::vector<TermId> classes;
    for (TermId c : {node_shape_, property_shape_})
      if (c != kAbsent) classes.push_back(c);
    for (size_t i = 0; i < classes.size(); ++i) {
      g_.scan(TermId::any(), subclass_, classes[i], TermId::any(),
              [&](const rdf::Quad& q, uint32_t) {
                if (std::find(classes.begin(), classes.end(), q.subject) == classes.end())
                  classes.push_back(q.subject);
                return true;
              });
    }
    return classes;
  }

  [[noreturn]] void fail(uint32_t shape, SourceLoc where, const std::string& message) {
    std::string file = out_.files_ != nullptr && where.known() ? out_.files_->path(where.file) : "";
    throw Error("shacl-ill-formed", "shape " + out_.describe(shape) + ": " + message, file,
                where.line, where.column);
  }

  std::string show(TermId id) const { return term_text(t_, id); }

  struct Value {
    TermId object;
    SourceLoc where;
  };

  std::vector<Value> values(TermId s, TermId p) const {
    std::vector<Value> out;
    g_.scan(s, p, TermId::any(), TermId::any(), [&](const rdf::Quad& q, uint32_t i) {
      // The same triple may sit in several graphs; SHACL sees one graph.
      for (const Value& v : out)
        if (v.object == q.object) return true;
      out.push_back({q.object, g_.location(i)});
      return true;
    });
    return out;
  }

  // Members of a well-formed SHACL list, or an error naming the shape.
  std::vector<TermId> list(uint32_t shape, TermId head, SourceLoc where, std::string_view param) {
    std::vector<TermId> members;
    std::unordered_set<uint32_t> visited;
    TermId node = head;
    while (node != nil_) {
      const rdf::Term& term = t_[node];
      if (term.is_literal())
        fail(shape, where, std::string(param) + " must be a SHACL list, got " + show(node));
      if (!visited.insert(node.index).second)
        fail(shape, where, std::string(param) + " is a cyclic list");
      auto firsts = values(node, first_);
      auto rests = values(node, rest_);
      if (firsts.size() != 1 || rests.size() != 1)
        fail(shape, where,
             std::string(param) +
                 " must be a SHACL list (each node needs exactly one rdf:first "
                 "and one rdf:rest), got " +
                 show(node));
      members.push_back(firsts[0].object);
      node = rests[0].object;
    }
    return members;
  }

  sparql::PathPtr parse_path(uint32_t shape, TermId node, SourceLoc where,
                             std::vector<uint32_t>& stack) {
    using K = sparql::Path::Kind;
    const rdf::Term& term = t_[node];
    if (term.is_iri()) {
      referenced_.push_back(node);
      return sparql::Path::iri(node);
    }
    if (!term.is_blank()) fail(shape, where, "sh:path value " + show(node) + " is not a path");
    if (std::find(stack.begin(), stack.end(), node.index) != stack.end())
      fail(shape, where, "sh:path " + show(node) + " refers to itself");
    stack.push_back(node.index);
    sparql::PathPtr result;
    if (g_.count(node, first_, TermId::any(), TermId::any(), 1) != 0) {
      auto members = list(shape, node, where, "sequence path");
      if (members.size() < 2)
        fail(shape, where, "a sequence path needs at least two members, got " + show(node));
      std::vector<sparql::PathPtr> items;
      for (TermId m : members) items.push_back(parse_path(shape, m, where, stack));
      result = sparql::Path::make(K::Sequence, std::move(items));
    } else {
      std::vector<std::pair<K, Value>> forms;
      for (auto [p, k] : {std::pair{alternative_, K::Alternative},
                          {inverse_, K::Inverse},
                          {zero_or_more_, K::ZeroOrMore},
                          {one_or_more_, K::OneOrMore},
                          {zero_or_one_, K::ZeroOrOne}})
        for (const Value& v : values(node, p)) forms.emplace_back(k, v);
      if (forms.size() != 1)
        fail(shape, where,
             "path node " + show(node) +
                 (forms.empty() ? " is neither a list nor has sh:alternativePath, sh:inversePath, "
                                  "sh:zeroOrMorePath, sh:oneOrMorePath or sh:zeroOrOnePath"
                                : " has more than one path form"));
      auto [kind, v] = forms[0];
      if (kind == K::Alternative) {
        auto members = list(shape, v.object, v.where, "sh:alternativePath");
        if (members.size() < 2)
          fail(shape, v.where, "sh:alternativePath needs at least two members");
        std::vector<sparql::PathPtr> items;
        for (TermId m : members) items.push_back(parse_path(shape, m, v.where, stack));
        result = sparql::Path::make(K::Alternative, std::move(items));
      } else {
        result = sparql::Path::make(kind, {parse_path(shape, v.object, v.where, stack)});
      }
    }
    stack.pop_back();
    return result;
  }

  // A non-negative xsd:integer parameter value.
  int64_t count_param(uint32_t shape, const Value& v, std::string_view param) {
    const rdf::Term& term = t_[v.object];
    if (term.is_literal()) {
      DatatypeInfo type = classify_datatype(t_[term.datatype].value);
      if (type.kind == Xsd::Integer && well_formed(term.value, type)) {
        std::string_view digits = term.value;
        if (!digits.empty() && digits[0] == '+') digits.remove_prefix(1);
        if (!digits.empty() && digits[0] != '-' && digits.size() <= 18) {
          int64_t n = 0;
          for (char c : digits) n = n * 10 + (c - '0');
          return n;
        }
      }
    }
    fail(shape, v.where,
         std::string(param) + " must be a non-negative xsd:integer, got " + show(v.object));
  }

  // true / false for xsd:boolean "true" / "false"; other boolean forms ("1")
  // leave the parameter inactive, as the W3C tests expect.
  std::optional<bool> bool_param(uint32_t shape, const Value& v, std::string_view param) {
    const rdf::Term& term = t_[v.object];
    if (!term.is_literal() || t_[term.datatype].value != vocab::xsd_boolean ||
        !well_formed(term.value, {Xsd::Boolean}))
      fail(shape, v.where, std::string(param) + " must be an xsd:boolean, got " + show(v.object));
    if (term.value == "true") return true;
    if (term.value == "false") return false;
    return std::nullopt;
  }

  uint32_t shape_ref(uint32_t shape, const Value& v, std::string_view param) {
    if (t_[v.object].is_literal())
      fail(shape, v.where, std::string(param) + " must name a shape, got " + show(v.object));
    return compile(v.object);
  }

  void at_most_one(uint32_t shape, const std::vector<Value>& vs, std::string_view param) {
    if (vs.size() > 1) fail(shape, vs[1].where, "more than one value for " + std::string(param));
  }

  TermId iri_param(uint32_t shape, const Value& v, std::string_view param) {
    if (!t_[v.object].is_iri())
      fail(shape, v.where, std::string(param) + " must be an IRI, got " + show(v.object));
    referenced_.push_back(v.object);
    return v.object;
  }

  std::shared_ptr<const sparql::Regex> compile_regex(uint32_t shape, const Value& pattern,
                                                     const std::vector<Value>& flags) {
    const rdf::Term& p = t_[pattern.object];
    if (!p.is_literal() || !p.language.empty())
      fail(shape, pattern.where,
           "sh:pattern must be a string literal, got " + show(pattern.object));
    std::string_view f;
    if (!flags.empty()) {
      const rdf::Term& ft = t_[flags[0].object];
      if (!ft.is_literal())
        fail(shape, flags[0].where,
             "sh:flags must be a string literal, got " + show(flags[0].object));
      f = ft.value;
    }
    try {
      return std::make_shared<const sparql::Regex>(p.value, f);
    } catch (const sparql::RegexError& e) {
      const bool flag = e.kind() == sparql::RegexError::Kind::Flag;
      fail(shape, flag ? flags[0].where : pattern.where,
           std::string(flag ? "sh:flags: " : "sh:pattern: ") + e.what());
    }
  }

  uint32_t compile(TermId node) {
    if (auto it = index_.find(node.index); it != index_.end()) return it->second;
    const uint32_t self = static_cast<uint32_t>(out_.shapes_.size());
    index_.emplace(node.index, self);
    {
      Shape s;
      s.node = node;
      g_.scan(node, TermId::any(), TermId::any(), TermId::any(), [&](const rdf::Quad&, uint32_t i) {
        s.where = g_.location(i);
        return false;
      });
      out_.shapes_.push_back(std::move(s));
    }
    // Shapes may be appended while this one compiles (referenced shapes), so
    // the shape is built locally and stored at the end.
    Shape s = out_.shapes_[self];

    auto paths = values(node, path_);
    if (!paths.empty()) {
      at_most_one(self, paths, "sh:path");
      s.is_property = true;
      s.path_node = paths[0].object;
      out_.shapes_[self].is_property = true;
      std::vector<uint32_t> stack;
      s.path = parse_path(self, paths[0].object, paths[0].where, stack);
      out_.shapes_[self].path = s.path;
    }

    for (const Value& v : values(node, deactivated_))
      if (bool_param(self, v, "sh:deactivated").value_or(false)) s.deactivated = true;
    auto severities = values(node, severity_);
    at_most_one(self, severities, "sh:severity");
    if (!severities.empty()) {
      TermId sev = iri_param(self, severities[0], "sh:severity");
      s.level = sev == violation_ ? Level::Violation
                : sev == warning_ ? Level::Warning
                : sev == info_    ? Level::Info
                                  : Level::Other;
      if (s.level == Level::Other) s.severity = sev;
    }
    for (const Value& v : values(node, message_)) {
      if (!t_[v.object].is_literal())
        fail(self, v.where, "sh:message must be a literal, got " + show(v.object));
      s.messages.push_back(v.object);
    }

    for (const Value& v : values(node, target_node_)) {
      s.target_nodes.push_back(v.object);
      referenced_.push_back(v.object);
    }
    for (const Value& v : values(node, target_class_))
      s.target_classes.push_back(iri_param(self, v, "sh:targetClass"));
    if (t_[node].is_iri() && rdfs_class_ != kAbsent &&
        g_.count(node, type_, rdfs_class_, TermId::any(), 1) != 0) {
      s.target_classes.push_back(node);
      referenced_.push_back(node);
    }
    for (const Value& v : values(node, target_subjects_))
      s.target_subjects_of.push_back(iri_param(self, v, "sh:targetSubjectsOf"));
    for (const Value& v : values(node, target_objects_))
      s.target_objects_of.push_back(iri_param(self, v, "sh:targetObjectsOf"));

    // Constraints, in the order their parameters are written.
    std::vector<std::pair<uint32_t, TermId>> predicates;
    std::unordered_set<uint32_t> seen;
    g_.scan(node, TermId::any(), TermId::any(), TermId::any(), [&](const rdf::Quad& q, uint32_t i) {
      if (params_.count(q.predicate.index) != 0 && seen.insert(q.predicate.index).second)
        predicates.emplace_back(i, q.predicate);
      return true;
    });
    for (auto& [quad, predicate] : predicates) {
      Component c = params_.at(predicate.index);
      add_constraints(self, s, c, predicate);
    }
    out_.shapes_[self] = std::move(s);
    return self;
  }

  void require_property_shape(uint32_t self, const Shape& s, const Value& v,
                              std::string_view param) {
    if (!s.is_property)
      fail(self, v.where, std::string(param) + " is only allowed in property shapes");
  }

  void add_constraints(uint32_t self, Shape& s, Component c, TermId predicate) {
    const std::string param = "sh:" + std::string(t_[predicate].value.substr(vocab::kSh.size()));
    auto vs = values(s.node, predicate);
    auto make = [&](const Value& v) {
      Constraint k;
      k.component = c;
      k.where = v.where;
      return k;
    };
    switch (c) {
      case Component::Class:
        for (const Value& v : vs) {
          Constraint k = make(v);
          k.term = iri_param(self, v, param);
          s.constraints.push_back(std::move(k));
        }
        return;
      case Component::Datatype: {
        at_most_one(self, vs, param);
        Constraint k = make(vs[0]);
        k.term = iri_param(self, vs[0], param);
        s.constraints.push_back(std::move(k));
        return;
      }
      case Component::NodeKind: {
        at_most_one(self, vs, param);
        Constraint k = make(vs[0]);
        TermId v = vs[0].object;
        k.node_kinds = v == nk_blank_           ? kBlankNode
                       : v == nk_iri_           ? kIri
                       : v == nk_literal_       ? kLiteral
                       : v == nk_blank_iri_     ? kBlankNode | kIri
                       : v == nk_blank_literal_ ? kBlankNode | kLiteral
                       : v == nk_iri_literal_   ? kIri | kLiteral
                                                : 0;
        if (k.node_kinds == 0)
          fail(self, vs[0].where,
               "sh:nodeKind must be one of sh:BlankNode, sh:IRI, sh:Literal, "
               "sh:BlankNodeOrIRI, sh:BlankNodeOrLiteral, sh:IRIOrLiteral; got " +
                   show(v));
        s.constraints.push_back(std::move(k));
        return;
      }
      case Component::MinCount:
      case Component::MaxCount:
      case Component::MinLength:
      case Component::MaxLength: {
        at_most_one(self, vs, param);
        if (c == Component::MinCount || c == Component::MaxCount)
          require_property_shape(self, s, vs[0], param);
        Constraint k = make(vs[0]);
        k.number = count_param(self, vs[0], param);
        s.constraints.push_back(std::move(k));
        return;
      }
      case Component::MinExclusive:
      case Component::MinInclusive:
      case Component::MaxExclusive:
      case Component::MaxInclusive: {
        at_most_one(self, vs, param);
        if (!t_[vs[0].object].is_literal())
          fail(self, vs[0].where, param + " must be a literal, got " + show(vs[0].object));
        Constraint k = make(vs[0]);
        k.term = vs[0].object;
        s.constraints.push_back(std::move(k));
        return;
      }
      case Component::Pattern: {
        at_most_one(self, vs, param);
        auto flags = values(s.node, flags_);
        at_most_one(self, flags, "sh:flags");
        Constraint k = make(vs[0]);
        k.regex = compile_regex(self, vs[0], flags);
        s.constraints.push_back(std::move(k));
        return;
      }
      case Component::LanguageIn: {
        at_most_one(self, vs, param);
        Constraint k = make(vs[0]);
        for (TermId m : list(self, vs[0].object, vs[0].where, param)) {
          const rdf::Term& term = t_[m];
          if (!term.is_literal() || term.datatype != rdf::TermTable::xsd_string())
            fail(self, vs[0].where, "sh:languageIn members must be strings, got " + show(m));
          k.ranges.emplace_back(term.value);
        }
        s.constraints.push_back(std::move(k));
        return;
      }
      case Component::UniqueLang: {
        at_most_one(self, vs, param);
        require_property_shape(self, s, vs[0], param);
        if (bool_param(self, vs[0], param).value_or(false)) s.constraints.push_back(make(vs[0]));
        return;
      }
      case Component::LessThan:
      case Component::LessThanOrEquals:
      case Component::Equals:
      case Component::Disjoint:
        for (const Value& v : vs) {
          if (c == Component::LessThan || c == Component::LessThanOrEquals)
            require_property_shape(self, s, v, param);
          Constraint k = make(v);
          k.term = iri_param(self, v, param);
          s.constraints.push_back(std::move(k));
        }
        return;
      case Component::Not:
      case Component::Node:
      case Component::Property:
        for (const Value& v : vs) {
          Constraint k = make(v);
          k.shapes.push_back(shape_ref(self, v, param));
          if (c == Component::Property && !out_.shapes_[k.shapes[0]].is_property)
            fail(self, v.where, "sh:property value " + show(v.object) + " has no sh:path");
          s.constraints.push_back(std::move(k));
        }
        return;
      case Component::And:
      case Component::Or:
      case Component::Xone:
        for (const Value& v : vs) {
          Constraint k = make(v);
          for (TermId m : list(self, v.object, v.where, param))
            k.shapes.push_back(shape_ref(self, Value{m, v.where}, param));
          s.constraints.push_back(std::move(k));
        }
        return;
      case Component::QualifiedMinCount:
      case Component::QualifiedMaxCount: {
        // One entry for the three qualified parameters; evaluate once.
        if (predicate != qvs_) return;
        at_most_one(self, vs, "sh:qualifiedValueShape");
        uint32_t shape = shape_ref(self, vs[0], "sh:qualifiedValueShape");
        auto mins = values(s.node, qmin_);
        auto maxs = values(s.node, qmax_);
        auto disjoint = values(s.node, qdisjoint_);
        at_most_one(self, mins, "sh:qualifiedMinCount");
        at_most_one(self, maxs, "sh:qualifiedMaxCount");
        at_most_one(self, disjoint, "sh:qualifiedValueShapesDisjoint");
        bool is_disjoint =
            !disjoint.empty() &&
            bool_param(self, disjoint[0], "sh:qualifiedValueShapesDisjoint").value_or(false);
        for (auto& [list, component] : {std::pair{&mins, Component::QualifiedMinCount},
                                        {&maxs, Component::QualifiedMaxCount}}) {
          if (list->empty()) continue;
          Constraint k = make((*list)[0]);
          k.component = component;
          k.number =
              count_param(self, (*list)[0],
                          component == Component::QualifiedMinCount ? "sh:qualifiedMinCount"
                                                                    : "sh:qualifiedMaxCount");
          k.shapes.push_back(shape);
          // Siblings are filled in by finish(); a non-empty marker says "disjoint".
          if (is_disjoint) k.siblings.push_back(UINT32_MAX);
          s.constraints.push_back(std::move(k));
        }
        return;
      }
      case Component::Closed: {
        at_most_one(self, vs, param);
        auto ignored = values(s.node, ignored_);
        at_most_one(self, ignored, "sh:ignoredProperties");
        if (!bool_param(self, vs[0], param).value_or(false)) return;
        Constraint k = make(vs[0]);
        if (!ignored.empty())
          for (TermId m : list(self, ignored[0].object, ignored[0].where, "sh:ignoredProperties"))
            k.terms.push_back(iri_param(self, Value{m, ignored[0].where}, "sh:ignoredProperties"));
        s.constraints.push_back(std::move(k));
        return;
      }
      case Component::HasValue:
        for (const Value& v : vs) {
          Constraint k = make(v);
          k.term = v.object;
          referenced_.push_back(v.object);
          s.constraints.push_back(std::move(k));
        }
        return;
      case Component::In: {
        at_most_one(self, vs, param);
        Constraint k = make(vs[0]);
        k.terms = list(self, vs[0].object, vs[0].where, param);
        for (TermId m : k.terms) referenced_.push_back(m);
        s.constraints.push_back(std::move(k));
        return;
      }
      case Component::Sparql:
        for (const Value& v : vs) {
          auto sparql = sparql_constraint(self, s, v);
          if (!sparql) continue;
          Constraint k = make(v);
          k.sparql = std::move(sparql);
          s.constraints.push_back(std::move(k));
        }
        return;
    }
  }

  // sh:prefixes/owl:imports*/sh:declare of a SPARQL-based constraint.
  sparql::PrefixMap prefixes(uint32_t shape, TermId constraint) {
    sparql::PrefixMap out;
    std::vector<TermId> todo;
    for (const Value& v : values(constraint, prefixes_)) todo.push_back(v.object);
    std::unordered_set<uint32_t> visited;
    while (!todo.empty()) {
      TermId node = todo.back();
      todo.pop_back();
      if (!visited.insert(node.index).second) continue;
      for (const Value& v : values(node, owl_imports_)) todo.push_back(v.object);
      for (const Value& d : values(node, declare_)) {
        auto names = values(d.object, prefix_);
        auto namespaces = values(d.object, namespace_);
        if (names.size() != 1 || namespaces.size() != 1 || !t_[names[0].object].is_literal() ||
            !t_[namespaces[0].object].is_literal())
          fail(shape, d.where,
               "prefix declaration " + show(d.object) +
                   " needs exactly one literal sh:prefix and one literal sh:namespace");
        std::string name(t_[names[0].object].value);
        std::string ns(t_[namespaces[0].object].value);
        auto [it, inserted] = out.emplace(name, ns);
        if (!inserted && it->second != ns)
          fail(shape, d.where,
               "prefix \"" + name + "\" is declared with two namespaces: <" + it->second +
                   "> and <" + ns + ">");
      }
    }
    return out;
  }

  std::shared_ptr<const SparqlConstraint> sparql_constraint(uint32_t self, const Shape& s,
                                                            const Value& v) {
    if (t_[v.object].is_literal())
      fail(self, v.where, "sh:sparql must be an IRI or blank node, got " + show(v.object));
    auto deactivated = values(v.object, deactivated_);
    at_most_one(self, deactivated, "sh:deactivated");
    if (!deactivated.empty() && bool_param(self, deactivated[0], "sh:deactivated").value_or(false))
      return nullptr;
    auto selects = values(v.object, select_);
    if (selects.size() != 1 || !t_[selects[0].object].is_literal())
      fail(self, selects.empty() ? v.where : selects[0].where,
           "SPARQL constraint " + show(v.object) + " needs exactly one sh:select string");
    const Value& select = selects[0];
    std::string text(t_[select.object].value);
    if (s.is_property) {
      // SHACL-SPARQL 5.3: $PATH stands for the shape's path in predicate position.
      const std::string path = "(" + path_to_sparql(t_, *s.path) + ")";
      std::string replaced;
      for (size_t i = 0; i < text.size(); ++i) {
        bool var = (text[i] == '$' || text[i] == '?') && text.compare(i + 1, 4, "PATH") == 0;
        size_t end = i + 5;
        if (var && (end >= text.size() ||
                    !(std::isalnum(static_cast<unsigned char>(text[end])) || text[end] == '_'))) {
          replaced += path;
          i = end - 1;
        } else {
          replaced += text[i];
        }
      }
      text = std::move(replaced);
    }
    auto where_query = [&](const std::string& what) {
      return "sh:select of SPARQL constraint " + show(v.object) + ": " + what;
    };
    std::optional<sparql::Query> query;
    try {
      query = sparql::parse_query(text, prefixes(self, v.object));
      if (query->form() != sparql::QueryForm::Select)
        fail(self, select.where, where_query("must be a SELECT query"));
      const auto& vars = query->variables();
      if (std::find(vars.begin(), vars.end(), "this") == vars.end())
        fail(self, select.where, where_query("must project $this"));
      if (query->mentions("shapesGraph"))
        fail(self, select.where,
             where_query("uses $shapesGraph, which mospec does not support (the shapes graph is "
                         "not a named graph of the data)"));
      const std::string_view prebound[] = {"this", "currentShape"};
      query->check_prebinding(prebound);
    } catch (const sparql::QueryError& e) {
      // Point into the shapes file: the quad is located just past the sh:select
      // literal, so a long string (""""..."""" with its newlines written out) starts
      // as many lines above as its value holds newlines; query line L is then
      // file line start + L - 1 (same column for L > 1). Written with escapes,
      // the estimate would be off, so the message also keeps the query position
      // and where the sh:select is written.
      std::string_view original = t_[select.object].value;
      const auto newlines =
          static_cast<uint32_t>(std::count(original.begin(), original.end(), '\n'));
      SourceLoc at = select.where;
      if (at.known() && e.line() != 0 && newlines < at.line && e.line() <= newlines + 1) {
        at.line = at.line - newlines + (e.line() - 1);
        at.column = e.line() > 1 ? e.column() : 0;
      }
      std::string what = "line " + std::to_string(e.line());
      what += ", column " + std::to_string(e.column());
      what += " of the query";
      const std::string literal_at = describe_location(out_.files_, select.where);
      if (!literal_at.empty()) what += " (sh:select ending at " + literal_at + ")";
      what += ": ";
      // The parser's message starts with its own "line L, column C: ".
      std::string_view message = e.diagnostic().message;
      if (size_t colon = message.find(": ");
          message.rfind("line ", 0) == 0 && colon != std::string_view::npos)
        message.remove_prefix(colon + 2);
      what += message;
      fail(self, at, where_query(what));
    }
    auto c = std::make_shared<SparqlConstraint>(SparqlConstraint{v.object, *query, {}, false});
    c->binds_current_shape = c->query.mentions("currentShape");
    for (const Value& m : values(v.object, message_)) {
      if (!t_[m.object].is_literal())
        fail(self, m.where, "sh:message must be a literal, got " + show(m.object));
      c->messages.push_back(m.object);
    }
    referenced_.push_back(v.object);
    return c;
  }

  // Cross-shape facts: closed shapes' allowed predicates and qualified siblings.
  void finish() {
    std::vector<std::vector<uint32_t>> parents(out_.shapes_.size());
    for (uint32_t i = 0; i < out_.shapes_.size(); ++i)
      for (const Constraint& k : out_.shapes_[i].constraints)
        if (k.component == Component::Property) parents[k.shapes[0]].push_back(i);
    for (uint32_t i = 0; i < out_.shapes_.size(); ++i) {
      Shape& s = out_.shapes_[i];
      for (Constraint& k : s.constraints) {
        if (k.component == Component::Closed) {
          std::vector<TermId> allowed = k.terms;
          for (const Constraint& p : s.constraints) {
            if (p.component != Component::Property) continue;
            const Shape& ps = out_.shapes_[p.shapes[0]];
            if (ps.path && ps.path->kind == sparql::Path::Kind::Predicate)
              allowed.push_back(ps.path->predicate);
          }
          std::sort(allowed.begin(), allowed.end());
          allowed.erase(std::unique(allowed.begin(), allowed.end()), allowed.end());
          k.terms = allowed;
        }
        if ((k.component == Component::QualifiedMinCount ||
             k.component == Component::QualifiedMaxCount) &&
            !k.siblings.empty()) {
          k.siblings.clear();
          for (uint32_t parent : parents[i])
            for (const Constraint& p : out_.shapes_[parent].constraints) {
              if (p.component != Component::Property) continue;
              for (const Constraint& q : out_.shapes_[p.shapes[0]].constraints)
                if ((q.component == Component::QualifiedMinCount ||
                     q.component == Component::QualifiedMaxCount) &&
                    q.shapes[0] != k.shapes[0] &&
                    std::find(k.siblings.begin(), k.siblings.end(), q.shapes[0]) ==
                        k.siblings.end())
                  k.siblings.push_back(q.shapes[0]);
            }
        }
      }
    }
    std::sort(referenced_.begin(), referenced_.end());
    referenced_.erase(std::unique(referenced_.begin(), referenced_.end()), referenced_.end());
    out_.referenced_ = std::move(referenced_);
  }

  const rdf::Dataset& g_;
  const rdf::TermTable& t_;
  Shapes out_;
  std::unordered_map<uint32_t, uint32_t> index_;
  std::unordered_map<uint32_t, Component> params_;
  std::vector<TermId> referenced_;
  TermId type_, first_, rest_, nil_, subclass_, rdfs_class_, node_shape_, property_shape_;
  TermId violation_, warning_, info_;
  TermId path_, target_node_, target_class_, target_subjects_, target_objects_, deactivated_,
      severity_, message_;
  TermId alternative_, inverse_, zero_or_more_, one_or_more_, zero_or_one_, flags_;
  TermId qvs_, qmin_, qmax_, qdisjoint_, ignored_, property_;
  TermId select_, prefixes_, declare_, prefix_, namespace_, owl_imports_;
  TermId nk_blank_, nk_iri_, nk_literal_, nk_blank_iri_, nk_blank_literal_, nk_iri_literal_;
};

Shapes Shapes::compile(const rdf::Dataset& graph, const SourceFiles* files) {
  return ShapesCompiler(graph, files).run();
}

}  // namespace mospec::shacl
