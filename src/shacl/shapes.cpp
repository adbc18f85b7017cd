#include "shacl/shapes.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <optional>
#include <span>
#include <tuple>
#include <unordered_map>
#include <unordered_set>

#include "rdf/xsd.hpp"
#include "shacl/literal.hpp"
#include "vocab/w3c.hpp"

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
    {MOSPEC_VOCAB_SH "ClassConstraintComponent", "sh:ClassConstraintComponent"},
    {MOSPEC_VOCAB_SH "DatatypeConstraintComponent", "sh:DatatypeConstraintComponent"},
    {MOSPEC_VOCAB_SH "NodeKindConstraintComponent", "sh:NodeKindConstraintComponent"},
    {MOSPEC_VOCAB_SH "MinCountConstraintComponent", "sh:MinCountConstraintComponent"},
    {MOSPEC_VOCAB_SH "MaxCountConstraintComponent", "sh:MaxCountConstraintComponent"},
    {MOSPEC_VOCAB_SH "MinExclusiveConstraintComponent", "sh:MinExclusiveConstraintComponent"},
    {MOSPEC_VOCAB_SH "MinInclusiveConstraintComponent", "sh:MinInclusiveConstraintComponent"},
    {MOSPEC_VOCAB_SH "MaxExclusiveConstraintComponent", "sh:MaxExclusiveConstraintComponent"},
    {MOSPEC_VOCAB_SH "MaxInclusiveConstraintComponent", "sh:MaxInclusiveConstraintComponent"},
    {MOSPEC_VOCAB_SH "MinLengthConstraintComponent", "sh:MinLengthConstraintComponent"},
    {MOSPEC_VOCAB_SH "MaxLengthConstraintComponent", "sh:MaxLengthConstraintComponent"},
    {MOSPEC_VOCAB_SH "PatternConstraintComponent", "sh:PatternConstraintComponent"},
    {MOSPEC_VOCAB_SH "LanguageInConstraintComponent", "sh:LanguageInConstraintComponent"},
    {MOSPEC_VOCAB_SH "UniqueLangConstraintComponent", "sh:UniqueLangConstraintComponent"},
    {MOSPEC_VOCAB_SH "EqualsConstraintComponent", "sh:EqualsConstraintComponent"},
    {MOSPEC_VOCAB_SH "DisjointConstraintComponent", "sh:DisjointConstraintComponent"},
    {MOSPEC_VOCAB_SH "LessThanConstraintComponent", "sh:LessThanConstraintComponent"},
    {MOSPEC_VOCAB_SH "LessThanOrEqualsConstraintComponent",
     "sh:LessThanOrEqualsConstraintComponent"},
    {MOSPEC_VOCAB_SH "NotConstraintComponent", "sh:NotConstraintComponent"},
    {MOSPEC_VOCAB_SH "AndConstraintComponent", "sh:AndConstraintComponent"},
    {MOSPEC_VOCAB_SH "OrConstraintComponent", "sh:OrConstraintComponent"},
    {MOSPEC_VOCAB_SH "XoneConstraintComponent", "sh:XoneConstraintComponent"},
    {MOSPEC_VOCAB_SH "NodeConstraintComponent", "sh:NodeConstraintComponent"},
    {MOSPEC_VOCAB_SH "PropertyConstraintComponent", "sh:PropertyConstraintComponent"},
    {MOSPEC_VOCAB_SH "QualifiedMinCountConstraintComponent",
     "sh:QualifiedMinCountConstraintComponent"},
    {MOSPEC_VOCAB_SH "QualifiedMaxCountConstraintComponent",
     "sh:QualifiedMaxCountConstraintComponent"},
    {MOSPEC_VOCAB_SH "ClosedConstraintComponent", "sh:ClosedConstraintComponent"},
    {MOSPEC_VOCAB_SH "HasValueConstraintComponent", "sh:HasValueConstraintComponent"},
    {MOSPEC_VOCAB_SH "InConstraintComponent", "sh:InConstraintComponent"},
    {MOSPEC_VOCAB_SH "SPARQLConstraintComponent", "sh:SPARQLConstraintComponent"},
}};

std::string term_text(const rdf::TermTable& t, TermId id) {
  return rdf::to_ntriples(t, id);
}

}  // namespace

std::string_view component_iri(Component c) {
  return c == Component::SparqlComponent ? std::string_view()
                                         : kComponents[static_cast<size_t>(c)].iri;
}
std::string_view component_name(Component c) {
  return c == Component::SparqlComponent ? std::string_view()
                                         : kComponents[static_cast<size_t>(c)].name;
}

std::string describe_location(const SourceFiles* files, SourceLoc loc) {
  if (!loc.known()) return {};
  std::string file = files != nullptr ? files->path(loc.file) : std::string();
  return format_place(file.empty() ? "<input>" : file, loc.line, loc.column);
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
    type_ = sh(vocab::rdf::type);
    first_ = sh(vocab::rdf::first);
    rest_ = sh(vocab::rdf::rest);
    nil_ = sh(vocab::rdf::nil);
    subclass_ = sh(vocab::rdfs::subClassOf);
    sparql_ = sh(vocab::sh::sparql);
    rdfs_class_ = sh(vocab::rdfs::Class);
    node_shape_ = sh(vocab::sh::NodeShape);
    property_shape_ = sh(vocab::sh::PropertyShape);
    violation_ = sh(vocab::sh::Violation);
    warning_ = sh(vocab::sh::Warning);
    info_ = sh(vocab::sh::Info);
    for (auto [iri, slot] : std::initializer_list<std::pair<std::string_view, TermId*>>{
             {vocab::sh::path, &path_},
             {vocab::sh::targetNode, &target_node_},
             {vocab::sh::targetClass, &target_class_},
             {vocab::sh::targetSubjectsOf, &target_subjects_},
             {vocab::sh::targetObjectsOf, &target_objects_},
             {vocab::sh::deactivated, &deactivated_},
             {vocab::sh::severity, &severity_},
             {vocab::sh::message, &message_},
             {vocab::sh::alternativePath, &alternative_},
             {vocab::sh::inversePath, &inverse_},
             {vocab::sh::zeroOrMorePath, &zero_or_more_},
             {vocab::sh::oneOrMorePath, &one_or_more_},
             {vocab::sh::zeroOrOnePath, &zero_or_one_},
             {vocab::sh::flags, &flags_},
             {vocab::sh::qualifiedValueShape, &qvs_},
             {vocab::sh::qualifiedMinCount, &qmin_},
             {vocab::sh::qualifiedMaxCount, &qmax_},
             {vocab::sh::qualifiedValueShapesDisjoint, &qdisjoint_},
             {vocab::sh::ignoredProperties, &ignored_},
             {vocab::sh::property, &property_},
             {vocab::sh::select, &select_},
             {vocab::sh::prefixes, &prefixes_},
             {vocab::sh::declare, &declare_},
             {vocab::sh::prefix, &prefix_},
             {vocab::sh::namespace_, &namespace_},
             {vocab::owl::imports, &owl_imports_},
             {vocab::sh::ConstraintComponent, &constraint_component_},
             {vocab::sh::parameter, &parameter_},
             {vocab::sh::optional, &optional_},
             {vocab::sh::validator, &validator_},
             {vocab::sh::nodeValidator, &node_validator_},
             {vocab::sh::propertyValidator, &property_validator_},
             {vocab::sh::ask, &ask_},
             {vocab::sh::labelTemplate, &label_template_},
             {vocab::sh::BlankNode, &nk_blank_},
             {vocab::sh::IRI, &nk_iri_},
             {vocab::sh::Literal, &nk_literal_},
             {vocab::sh::BlankNodeOrIRI, &nk_blank_iri_},
             {vocab::sh::BlankNodeOrLiteral, &nk_blank_literal_},
             {vocab::sh::IRIOrLiteral, &nk_iri_literal_},
         })
      *slot = sh(iri);
    for (auto [iri, c] : std::initializer_list<std::pair<std::string_view, Component>>{
             {vocab::sh::class_, Component::Class},
             {vocab::sh::datatype, Component::Datatype},
             {vocab::sh::nodeKind, Component::NodeKind},
             {vocab::sh::minCount, Component::MinCount},
             {vocab::sh::maxCount, Component::MaxCount},
             {vocab::sh::minExclusive, Component::MinExclusive},
             {vocab::sh::minInclusive, Component::MinInclusive},
             {vocab::sh::maxExclusive, Component::MaxExclusive},
             {vocab::sh::maxInclusive, Component::MaxInclusive},
             {vocab::sh::minLength, Component::MinLength},
             {vocab::sh::maxLength, Component::MaxLength},
             {vocab::sh::pattern, Component::Pattern},
             {vocab::sh::languageIn, Component::LanguageIn},
             {vocab::sh::uniqueLang, Component::UniqueLang},
             {vocab::sh::equals, Component::Equals},
             {vocab::sh::disjoint, Component::Disjoint},
             {vocab::sh::lessThan, Component::LessThan},
             {vocab::sh::lessThanOrEquals, Component::LessThanOrEquals},
             {vocab::sh::not_, Component::Not},
             {vocab::sh::and_, Component::And},
             {vocab::sh::or_, Component::Or},
             {vocab::sh::xone, Component::Xone},
             {vocab::sh::node, Component::Node},
             {vocab::sh::property, Component::Property},
             {vocab::sh::closed, Component::Closed},
             {vocab::sh::hasValue, Component::HasValue},
             {vocab::sh::in_, Component::In},
             {vocab::sh::sparql, Component::Sparql},
         }) {
      TermId id = sh(iri);
      if (id != kAbsent) params_.emplace(id.index, c);
    }
    for (TermId p : {qvs_, qmin_, qmax_})
      if (p != kAbsent) params_.emplace(p.index, Component::QualifiedMinCount);
    // What a shape may say in the SHACL namespace besides the parameters of
    // the core components: anything else is refused (check_shape_properties).
    for (auto [p, c] : params_) shape_properties_.insert(p);
    for (std::string_view iri :
         {vocab::sh::targetNode, vocab::sh::targetClass, vocab::sh::targetSubjectsOf,
          vocab::sh::targetObjectsOf, vocab::sh::path, vocab::sh::deactivated, vocab::sh::severity,
          vocab::sh::message, vocab::sh::flags, vocab::sh::qualifiedMinCount,
          vocab::sh::qualifiedMaxCount, vocab::sh::qualifiedValueShapesDisjoint,
          vocab::sh::ignoredProperties, vocab::sh::declare, vocab::sh::name, vocab::sh::description,
          vocab::sh::order, vocab::sh::group, vocab::sh::defaultValue})
      if (TermId id = sh(iri); id != kAbsent) shape_properties_.insert(id.index);
    // A shape's sh:prefixes serve the queries of its SPARQL constraints (prefixes()).
    if (TermId id = sh(vocab::sh::prefixes); id != kAbsent) shape_properties_.insert(id.index);
    auto allow = [&](std::unordered_set<uint32_t>& set,
                     std::initializer_list<std::string_view> iris) {
      for (std::string_view iri : iris)
        if (TermId id = sh(iri); id != kAbsent) set.insert(id.index);
    };
    allow(sparql_properties_,
          {vocab::sh::select, vocab::sh::message, vocab::sh::prefixes, vocab::sh::deactivated,
           vocab::sh::name, vocab::sh::description, vocab::sh::declare});
    allow(component_properties_,
          {vocab::sh::parameter, vocab::sh::validator, vocab::sh::nodeValidator,
           vocab::sh::propertyValidator, vocab::sh::message, vocab::sh::labelTemplate,
           vocab::sh::name, vocab::sh::description, vocab::sh::declare});
    allow(validator_properties_,
          {vocab::sh::select, vocab::sh::ask, vocab::sh::message, vocab::sh::prefixes,
           vocab::sh::name, vocab::sh::description, vocab::sh::declare});
  }

  Shapes run() {
    refuse_unsupported_constructs();
    declare_components();
    // Every node that the spec calls a shape, in the order it is first written.
    // Parameter declarations of constraint components are property shapes of
    // the component, not of the shapes graph: compiled when a shape uses them.
    std::vector<std::pair<uint32_t, TermId>> candidates;
    std::unordered_set<uint32_t> seen;
    auto add = [&](TermId node, uint32_t quad) {
      if (t_[node].is_literal() || parameter_nodes_.count(node.index) != 0) return;
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
    for (const auto& [p, components] : custom_params_) subject_preds.push_back(TermId{p});
    for (TermId p : subject_preds) {
      g_.scan(TermId::any(), p, TermId::any(), TermId::any(), [&](const rdf::Quad& q, uint32_t i) {
        add(q.subject, i);
        return true;
      });
    }
    std::sort(candidates.begin(), candidates.end());
    for (auto& [quad, node] : candidates) compile(node);
    finish();
    detail::check_component_parameters(out_);
    return std::move(out_);
  }

 private:
  std::vector<TermId> shape_classes() {
    // SHACL instances of sh:NodeShape / sh:PropertyShape include instances of
    // their subclasses (rare, but cheap to honour).
    return subclasses({node_shape_, property_shape_});
  }

  // The classes given (those present in the graph) and their rdfs:subClassOf*
  // subclasses in the shapes graph.
  std::vector<TermId> subclasses(std::initializer_list<TermId> roots) {
    std::vector<TermId> classes;
    for (TermId c : roots)
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

  [[noreturn]] void fail(uint32_t shape, SourceLoc where, const std::string& message,
                         DiagnosticCode code = "shacl-ill-formed") {
    std::string file = out_.files_ != nullptr && where.known() ? out_.files_->path(where.file) : "";
    throw Error(code, "shape " + out_.describe(shape) + ": " + message, file, where.line,
                where.column);
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
    if (stack.size() >= kMaxPathDepth)
      fail(shape, where,
           "sh:path nests deeper than " + std::to_string(kMaxPathDepth) +
               " levels (sh:inversePath, sh:alternativePath, sequence and repetition paths inside "
               "each other) at " +
               show(node) + "; write a flatter path",
           "shacl-too-deep");
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
      rdf::xsd::Datatype type = rdf::xsd::classify(t_[term.datatype].value);
      if (type.kind == rdf::xsd::Kind::Integer && rdf::xsd::well_formed(term.value, type)) {
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
    if (!term.is_literal() || t_[term.datatype].value != vocab::xsd::boolean ||
        !rdf::xsd::well_formed(term.value, {rdf::xsd::Kind::Boolean}))
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
    // A shape compiles the shapes it references first (sh:node, sh:not,
    // sh:and, sh:property, ...), one nested call each: bound the nesting
    // before the stack does.
    if (depth_ >= kMaxShapeDepth)
      fail(self, out_.shapes_[self].where,
           "shapes nest deeper than " + std::to_string(kMaxShapeDepth) +
               " levels (sh:node, sh:not, sh:and, sh:or, sh:xone, sh:property or "
               "sh:qualifiedValueShape referring to further shapes); split the chain or "
               "flatten it",
           "shacl-too-deep");
    ++depth_;
    struct Leave {
      int& depth;
      ~Leave() { --depth; }
    } leave{depth_};
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
    // Everything the shape says in the SHACL namespace is implemented or refused.
    // A shape may be its own SPARQL constraint (W3C test sparql/node/sparql-002:
    // `ex:S sh:sparql ex:S ; sh:select ...`): then it may say what either says.
    const bool also_constraint =
        sparql_ != kAbsent && g_.count(TermId::any(), sparql_, node, TermId::any(), 1) != 0;
    check_properties(node, shape_properties_, "a shape",
                     also_constraint ? &sparql_properties_ : nullptr);
    std::vector<std::pair<uint32_t, TermId>> predicates;
    std::vector<uint32_t> custom;  // custom components used, in the order written
    std::unordered_set<uint32_t> seen;
    g_.scan(node, TermId::any(), TermId::any(), TermId::any(), [&](const rdf::Quad& q, uint32_t i) {
      if (!seen.insert(q.predicate.index).second) return true;
      if (params_.count(q.predicate.index) != 0) predicates.emplace_back(i, q.predicate);
      if (auto it = custom_params_.find(q.predicate.index); it != custom_params_.end()) {
        for (uint32_t c : it->second)
          if (std::find(custom.begin(), custom.end(), c) == custom.end()) custom.push_back(c);
      }
      return true;
    });
    for (auto& [quad, predicate] : predicates) {
      Component c = params_.at(predicate.index);
      add_constraints(self, s, c, predicate);
    }
    // SHACL 6.2: a shape declares a component's constraint only when it has
    // values for all of its mandatory parameters; a value of an optional
    // parameter alone declares nothing (W3C test sparql/component/optional-001).
    for (uint32_t c : custom) add_component_constraints(self, s, c);
    out_.shapes_[self] = std::move(s);
    return self;
  }

  void require_property_shape(uint32_t self, const Shape& s, const Value& v,
                              std::string_view param) {
    if (!s.is_property)
      fail(self, v.where, std::string(param) + " is only allowed in property shapes");
  }

  void add_constraints(uint32_t self, Shape& s, Component c, TermId predicate) {
    const std::string param = "sh:" + std::string(t_[predicate].value.substr(vocab::sh::ns.size()));
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
      case Component::SparqlComponent:  // not a core parameter
        return;
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

  // sh:prefixes/owl:imports*/sh:declare of a SPARQL-based constraint or
  // validator, and of the shape that uses it (which SHACL leaves to
  // extensions; mospec lets a shape's prefixes serve all of its queries).
  sparql::PrefixMap prefixes(uint32_t shape, TermId shape_node, TermId constraint) {
    sparql::PrefixMap out;
    std::vector<TermId> todo;
    for (TermId holder : {constraint, shape_node}) {
      for (const Value& v : values(holder, prefixes_)) {
        if (t_[v.object].is_literal())
          fail(shape, v.where, "sh:prefixes must be an IRI or blank node, got " + show(v.object));
        todo.push_back(v.object);
      }
    }
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

  // The text of an sh:select / sh:ask, with $PATH replaced by the property
  // shape's path (SHACL-SPARQL 5.3: in predicate position).
  std::string query_text(const Shape& s, const Value& literal, bool substitute_path) const {
    std::string text(t_[literal.object].value);
    if (!s.is_property || !substitute_path) return text;
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
    return replaced;
  }

  // Parses the query of `holder` (an sh:sparql constraint or a validator)
  // written as `literal` (its sh:select or sh:ask), with the holder's
  // sh:prefixes. `what` names the holder in messages ("sh:select of SPARQL
  // constraint _:b"). Errors point into the shapes file.
  sparql::Query parse_sparql(uint32_t self, const Shape& s, TermId holder, const Value& literal,
                             sparql::QueryForm form, const std::string& what,
                             std::span<const std::string_view> prebound) {
    auto where_query = [&](const std::string& m) { return what + ": " + m; };
    // SHACL 5.3.1: a processor that does not support $shapesGraph must report
    // a failure for a query that uses it; thrown as a query error so that it
    // is located at the variable.
    const auto [graph_line, graph_column] =
        variable_position(t_[literal.object].value, "shapesGraph");
    const sparql::QueryError shapes_graph_error(
        "unsupported-sparql", graph_line, graph_column,
        "line " + std::to_string(graph_line) + ", column " + std::to_string(graph_column) +
            ": $shapesGraph is not supported (mospec does not query the shapes graph: it is not "
            "a named graph of the data)");
    try {
      try {
        sparql::Query query =
            sparql::parse_query(query_text(s, literal, form == sparql::QueryForm::Select),
                                prefixes(self, s.node, holder));
        if (query.form() != form)
          fail(self, literal.where,
               where_query(form == sparql::QueryForm::Select ? "must be a SELECT query"
                                                             : "must be an ASK query"));
        const auto& vars = query.variables();
        if (form == sparql::QueryForm::Select &&
            std::find(vars.begin(), vars.end(), "this") == vars.end())
          fail(self, literal.where, where_query("must project $this"));
        if (query.mentions("shapesGraph")) throw shapes_graph_error;
        query.check_prebinding(prebound);
        return query;
      } catch (const sparql::QueryError& e) {
        // GRAPH $shapesGraph { ... } fails at GRAPH: name the reason instead.
        if (e.code() == "unsupported-sparql" && graph_line != 0) throw shapes_graph_error;
        throw;
      }
    } catch (const sparql::QueryError& e) {
      // Point into the shapes file: the quad is located just past the sh:select
      // literal, so a long string (""""..."""" with its newlines written out) starts
      // as many lines above as its value holds newlines; query line L is then
      // file line start + L - 1 (same column for L > 1). Written with escapes,
      // the estimate would be off, so the message also keeps the query position
      // and where the sh:select is written.
      std::string_view original = t_[literal.object].value;
      const auto newlines =
          static_cast<uint32_t>(std::count(original.begin(), original.end(), '\n'));
      // On the query's first line the literal's opening quote is not known:
      // at its line's start, or, for a one-line literal, where it ends.
      SourceLoc at = literal.where;
      if (at.known() && e.line() != 0 && newlines < at.line && e.line() <= newlines + 1) {
        if (e.line() > 1) {
          at.line = at.line - newlines + (e.line() - 1);
          at.column = e.column();
        } else if (newlines > 0) {
          at.line = at.line - newlines;
          at.column = 1;
        }
      }
      std::string m = "line " + std::to_string(e.line());
      m += ", column " + std::to_string(e.column());
      m += " of the query";
      const std::string literal_at = describe_location(out_.files_, literal.where);
      if (!literal_at.empty())
        m += std::string(" (") + (form == sparql::QueryForm::Select ? "sh:select" : "sh:ask") +
             " ending at " + literal_at + ")";
      m += ": ";
      // The parser's message starts with its own "line L, column C: ".
      std::string_view message = e.diagnostic().message;
      if (size_t colon = message.find(": ");
          message.rfind("line ", 0) == 0 && colon != std::string_view::npos)
        message.remove_prefix(colon + 2);
      m += message;
      // What mospec does not implement is refused as such, never as a mistake of the shape.
      fail(self, at, where_query(m),
           e.code() == "unsupported-sparql" ? DiagnosticCode("unsupported-shacl")
                                            : DiagnosticCode("shacl-ill-formed"));
    }
  }

  // The 1-based line and column of the first ?name / $name in a query.
  static std::pair<uint32_t, uint32_t> variable_position(std::string_view text,
                                                         std::string_view name) {
    uint32_t line = 1, column = 1;
    for (size_t i = 0; i < text.size(); ++i) {
      if ((text[i] == '?' || text[i] == '$') && text.compare(i + 1, name.size(), name) == 0) {
        const size_t end = i + 1 + name.size();
        if (end == text.size() ||
            !(std::isalnum(static_cast<unsigned char>(text[end])) || text[end] == '_'))
          return {line, column};
      }
      if (text[i] == '\n') {
        ++line;
        column = 1;
      } else {
        ++column;
      }
    }
    return {0, 0};
  }

  // The values of `predicate` at `node`, which must be literals; `who` starts
  // the message otherwise.
  std::vector<TermId> literal_values(const std::string& who, TermId node, TermId predicate) {
    std::vector<TermId> out;
    for (const Value& m : values(node, predicate)) {
      if (!t_[m.object].is_literal())
        fail_at(m.where,
                who + ": " + show(predicate) + " must be a literal, got " + show(m.object));
      out.push_back(m.object);
    }
    return out;
  }

  std::shared_ptr<const SparqlConstraint> sparql_constraint(uint32_t self, const Shape& s,
                                                            const Value& v) {
    if (t_[v.object].is_literal())
      fail(self, v.where, "sh:sparql must be an IRI or blank node, got " + show(v.object));
    check_properties(v.object, sparql_properties_, "a SPARQL-based constraint",
                     v.object == s.node ? &shape_properties_ : nullptr);
    auto deactivated = values(v.object, deactivated_);
    at_most_one(self, deactivated, "sh:deactivated");
    if (!deactivated.empty() && bool_param(self, deactivated[0], "sh:deactivated").value_or(false))
      return nullptr;
    auto selects = values(v.object, select_);
    if (selects.size() != 1 || !t_[selects[0].object].is_literal())
      fail(self, selects.empty() ? v.where : selects[0].where,
           "SPARQL constraint " + show(v.object) + " needs exactly one sh:select string");
    const std::string_view prebound[] = {"this", "currentShape"};
    sparql::Query query =
        parse_sparql(self, s, v.object, selects[0], sparql::QueryForm::Select,
                     "sh:select of SPARQL constraint " + show(v.object), prebound);
    auto c = std::make_shared<SparqlConstraint>(
        SparqlConstraint{v.object, std::move(query), {}, false, TermId::any(), false, {}, {}, {}});
    c->binds_current_shape = c->query.mentions("currentShape");
    c->messages = literal_values("shape " + out_.describe(self), v.object, message_);
    referenced_.push_back(v.object);
    return c;
  }

  // ---- SPARQL-based constraint components (SHACL 6) ---------------------

  struct Parameter {
    TermId path;       // the parameter's predicate (an IRI)
    std::string name;  // its local name: the pre-bound variable
    bool optional = false;
    TermId declaration;
    SourceLoc where;           // the sh:parameter triple
    bool constrained = false;  // the declaration carries constraints of its own
  };

  struct CustomComponent {
    TermId node;  // the component's IRI
    SourceLoc where;
    std::vector<Parameter> parameters;
    // sh:validator (ASK), sh:nodeValidator, sh:propertyValidator (SELECT);
    // object any() when absent.
    Value ask{TermId::any(), {}}, node_select{TermId::any(), {}},
        property_select{TermId::any(), {}};
    std::vector<TermId> messages, labels;
  };

  [[noreturn]] void fail_at(SourceLoc where, const std::string& message,
                            DiagnosticCode code = "shacl-ill-formed") {
    std::string file = out_.files_ != nullptr && where.known() ? out_.files_->path(where.file) : "";
    throw Error(code, message, file, where.line, where.column);
  }

  SourceLoc first_location(TermId node) const {
    SourceLoc where;
    g_.scan(node, TermId::any(), TermId::any(), TermId::any(), [&](const rdf::Quad&, uint32_t i) {
      where = g_.location(i);
      return false;
    });
    return where;
  }

  // The local name of a parameter's IRI (SHACL 6.1: the longest NCName at its
  // end), which must also be a SPARQL variable name.
  static std::string local_name(std::string_view iri) {
    size_t start = iri.size();
    auto name_char = [](unsigned char c) {
      return std::isalnum(c) || c == '_' || c == '-' || c == '.' || c >= 0x80;
    };
    while (start > 0 && name_char(static_cast<unsigned char>(iri[start - 1]))) --start;
    while (start < iri.size() &&
           !(std::isalpha(static_cast<unsigned char>(iri[start])) || iri[start] == '_' ||
             static_cast<unsigned char>(iri[start]) >= 0x80))
      ++start;
    return std::string(iri.substr(start));
  }

  // Every sh:ConstraintComponent of the shapes graph, checked once; SHACL's
  // own components (the sh: namespace) are built in and skipped.
  void declare_components() {
    // SHACL instances of sh:ConstraintComponent include instances of its
    // subclasses: a component typed with one must not be left undeclared, or
    // its parameters would be ignored and the data would conform.
    std::vector<Value> declared;
    for (TermId cls : subclasses({constraint_component_}))
      g_.scan(TermId::any(), type_, cls, TermId::any(), [&](const rdf::Quad& q, uint32_t i) {
        for (const Value& d : declared)
          if (d.object == q.subject) return true;
        declared.push_back({q.subject, g_.location(i)});
        return true;
      });
    for (const Value& d : declared) {
      const rdf::Term& term = t_[d.object];
      if (term.is_iri() && term.value.substr(0, vocab::sh::ns.size()) == vocab::sh::ns) continue;
      const std::string who = "constraint component " + show(d.object);
      if (!term.is_iri()) fail_at(d.where, who + " must be an IRI (SHACL 6.2)");
      check_properties(d.object, component_properties_, "a constraint component");
      CustomComponent c;
      c.node = d.object;
      c.where = d.where;
      for (const Value& p : values(d.object, parameter_)) {
        if (t_[p.object].is_literal())
          fail_at(p.where, who + ": sh:parameter must be a node, got " + show(p.object));
        auto paths = values(p.object, path_);
        if (paths.size() != 1 || !t_[paths[0].object].is_iri())
          fail_at(p.where, who + ": parameter declaration " + show(p.object) +
                               " needs exactly one sh:path, an IRI");
        Parameter param;
        param.path = paths[0].object;
        param.declaration = p.object;
        param.where = p.where;
        param.name = local_name(t_[param.path].value);
        auto optional = values(p.object, optional_);
        if (optional.size() > 1)
          fail_at(optional[1].where,
                  who + ": more than one sh:optional for parameter " + show(param.path));
        if (!optional.empty()) {
          const rdf::Term& o = t_[optional[0].object];
          if (!o.is_literal() || t_[o.datatype].value != vocab::xsd::boolean ||
              (o.value != "true" && o.value != "false"))
            fail_at(optional[0].where,
                    who + ": sh:optional must be true or false, got " + show(optional[0].object));
          param.optional = o.value == "true";
        }
        const bool valid_name =
            !param.name.empty() && std::all_of(param.name.begin(), param.name.end(), [](char ch) {
              return std::isalnum(static_cast<unsigned char>(ch)) || ch == '_';
            });
        if (!valid_name)
          fail_at(p.where, who + ": parameter " + show(param.path) + " has the name \"" +
                               param.name +
                               "\" (its local name), which is not a SPARQL variable name");
        for (std::string_view reserved :
             {"this", "shapesGraph", "currentShape", "path", "PATH", "value"})
          if (param.name == reserved)
            fail_at(p.where, who + ": parameter " + show(param.path) + " may not be named \"" +
                                 param.name + "\" (a variable SHACL pre-binds itself)");
        for (const Parameter& other : c.parameters)
          if (other.name == param.name)
            fail_at(p.where, who + ": two parameters are named \"" + param.name + "\" (" +
                                 show(other.path) + " and " + show(param.path) + ")");
        // Constraints on the parameter's values (sh:datatype, sh:minLength,
        // ...): checked against each shape that uses the component.
        g_.scan(p.object, TermId::any(), TermId::any(), TermId::any(),
                [&](const rdf::Quad& q, uint32_t) {
                  param.constrained = param.constrained || params_.count(q.predicate.index) != 0;
                  return !param.constrained;
                });
        parameter_nodes_.insert(p.object.index);
        check_properties(p.object, shape_properties_, "a parameter declaration");
        c.parameters.push_back(std::move(param));
      }
      if (std::all_of(c.parameters.begin(), c.parameters.end(),
                      [](const Parameter& p) { return p.optional; }))
        fail_at(d.where, who + " needs at least one sh:parameter that is not sh:optional");
      for (auto [predicate, slot, form] :
           {std::tuple{validator_, &c.ask, sparql::QueryForm::Ask},
            {node_validator_, &c.node_select, sparql::QueryForm::Select},
            {property_validator_, &c.property_select, sparql::QueryForm::Select}}) {
        auto vs = values(d.object, predicate);
        if (vs.empty()) continue;
        const std::string param = show(predicate);
        if (vs.size() > 1)
          fail_at(vs[1].where, who + ": more than one value for " + param +
                                   " (mospec would have to pick one at random)");
        const Value& v = vs[0];
        if (t_[v.object].is_literal())
          fail_at(v.where, who + ": " + param + " must be a validator node, got " + show(v.object));
        check_properties(v.object, validator_properties_, "a SPARQL validator");
        const bool has_ask = !values(v.object, ask_).empty();
        const bool has_select = !values(v.object, select_).empty();
        if (!has_ask && !has_select)
          fail_at(v.where,
                  who + ": validator " + show(v.object) +
                      " has neither sh:ask nor sh:select; mospec implements SPARQL-based "
                      "validators only (SHACL-JS and other languages are not supported)",
                  "unsupported-shacl");
        if (form == sparql::QueryForm::Ask && !has_ask)
          fail_at(v.where, who +
                               ": the value of sh:validator must be an ASK-based validator "
                               "(sh:SPARQLAskValidator with sh:ask); use sh:nodeValidator or "
                               "sh:propertyValidator for a SELECT query");
        if (form == sparql::QueryForm::Select && !has_select)
          fail_at(v.where, who + ": the value of " + param +
                               " must be a SELECT-based validator (sh:SPARQLSelectValidator "
                               "with sh:select); use sh:validator for an ASK query");
        if (has_ask && has_select)
          fail_at(v.where,
                  who + ": validator " + show(v.object) + " has both sh:ask and sh:select");
        *slot = v;
      }
      if (c.ask.object.is_any() && c.node_select.object.is_any() &&
          c.property_select.object.is_any())
        fail_at(d.where,
                who + " has no validator (sh:validator, sh:nodeValidator or sh:propertyValidator)",
                "unsupported-shacl");
      c.messages = literal_values(who, d.object, message_);
      c.labels = literal_values(who, d.object, label_template_);
      const uint32_t index = static_cast<uint32_t>(components_.size());
      for (const Parameter& p : c.parameters) custom_params_[p.path.index].push_back(index);
      components_.push_back(std::move(c));
    }
  }

  // The constraints of custom component `ci` that shape `s` declares (one per
  // combination of parameter values), if it has values for every mandatory
  // parameter.
  void add_component_constraints(uint32_t self, Shape& s, uint32_t ci) {
    const CustomComponent& c = components_[ci];
    std::vector<std::vector<Value>> given;
    for (const Parameter& p : c.parameters) {
      given.push_back(values(s.node, p.path));
      if (!p.optional && given.back().empty()) return;
    }
    const Value* first = nullptr;  // the first mandatory parameter value: the constraint's place
    size_t combinations = 1;
    for (size_t i = 0; i < c.parameters.size(); ++i) {
      if (!given[i].empty()) combinations *= given[i].size();
      if (first == nullptr && !c.parameters[i].optional) first = &given[i][0];
      if (combinations > kMaxCombinations)
        fail(self, given[i][0].where,
             "the values of the parameters of constraint component " + show(c.node) +
                 " make more than " + std::to_string(kMaxCombinations) +
                 " combinations (one constraint each)");
    }
    const std::string who = "constraint component " + show(c.node);
    const Value& chosen = s.is_property && !c.property_select.object.is_any() ? c.property_select
                          : !s.is_property && !c.node_select.object.is_any()  ? c.node_select
                                                                              : c.ask;
    if (chosen.object.is_any())
      fail(self, first->where,
           "uses " + who + ", which has no validator for " +
               (s.is_property ? "property shapes (sh:propertyValidator or sh:validator)"
                              : "node shapes (sh:nodeValidator or sh:validator)") +
               "; SHACL would ignore this constraint, mospec refuses it",
           "unsupported-shacl");
    const bool ask = &chosen == &c.ask;
    const TermId validator = chosen.object;
    const Value literal = values(validator, ask ? ask_ : select_)[0];
    if (!t_[literal.object].is_literal())
      fail_at(literal.where, who + ": the sh:" + std::string(ask ? "ask" : "select") +
                                 " of validator " + show(validator) + " must be a string");
    std::vector<std::string_view> prebound{"this", "currentShape"};
    if (ask) prebound.push_back("value");
    for (const Parameter& p : c.parameters) prebound.push_back(p.name);
    sparql::Query query = parse_sparql(self, s, validator, literal,
                                       ask ? sparql::QueryForm::Ask : sparql::QueryForm::Select,
                                       std::string(ask ? "sh:ask" : "sh:select") +
                                           " of validator " + show(validator) + " of " + who,
                                       prebound);
    auto shared = std::make_shared<SparqlConstraint>(
        SparqlConstraint{validator, std::move(query), {}, false, c.node, ask, {}, {}, {}});
    shared->binds_current_shape = shared->query.mentions("currentShape");
    shared->messages = literal_values(who, validator, message_);
    if (shared->messages.empty()) shared->messages = c.messages;
    shared->labels = c.labels;
    for (const Parameter& p : c.parameters)
      if (p.constrained) shared->parameter_shapes.push_back(compile(p.declaration));
    // One constraint per combination of values (odometer over the parameters).
    std::vector<size_t> pick(c.parameters.size(), 0);
    for (size_t n = 0; n < combinations; ++n) {
      auto k = std::make_shared<SparqlConstraint>(*shared);
      for (size_t i = 0; i < c.parameters.size(); ++i)
        if (!given[i].empty())
          k->parameters.emplace_back(c.parameters[i].name, given[i][pick[i]].object);
      Constraint constraint;
      constraint.component = Component::SparqlComponent;
      constraint.where = first->where;
      constraint.sparql = std::move(k);
      s.constraints.push_back(std::move(constraint));
      for (size_t i = 0; i < pick.size(); ++i) {
        if (given[i].empty()) continue;
        if (++pick[i] < given[i].size()) break;
        pick[i] = 0;
      }
    }
  }

  // ---- what mospec does not implement -----------------------------------

  bool in_sh(TermId id) const {
    const rdf::Term& term = t_[id];
    return term.is_iri() && term.value.substr(0, vocab::sh::ns.size()) == vocab::sh::ns;
  }

  std::string sh_name(TermId id) const {
    return "sh:" + std::string(t_[id].value.substr(vocab::sh::ns.size()));
  }

  // Why a SHACL term is not implemented, for the ones with a known reason.
  static std::string_view unsupported_reason(std::string_view local) {
    static constexpr std::pair<std::string_view, std::string_view> kReasons[] = {
        {"rule", "rules (SHACL Advanced Features) are not implemented"},
        {"target", "custom targets (sh:target, SHACL Advanced Features) are not implemented"},
        {"js", "SHACL-JS constraints are not implemented"},
        {"jsFunctionName", "SHACL-JS is not implemented"},
        {"jsLibrary", "SHACL-JS is not implemented"},
        {"jsLibraryURL", "SHACL-JS is not implemented"},
        {"entailment",
         "entailment regimes are not implemented (mospec validates the graph as "
         "written)"},
        {"condition", "rule conditions (SHACL Advanced Features) are not implemented"},
        {"construct", "SPARQL CONSTRUCT rules (SHACL Advanced Features) are not implemented"},
        {"expression", "node expressions (SHACL Advanced Features) are not implemented"},
        {"filterShape", "node expressions (SHACL Advanced Features) are not implemented"},
        {"shapesGraph",
         "mospec takes shapes from the files the app names, not from "
         "sh:shapesGraph"},
        {"suggestedShapesGraph",
         "mospec takes shapes from the files the app names, not from "
         "sh:suggestedShapesGraph"},
        {"SPARQLTarget", "SPARQL-based targets (SHACL Advanced Features) are not implemented"},
        {"SPARQLTargetType",
         "SPARQL-based target types (SHACL Advanced Features) are not "
         "implemented"},
        {"JSTarget", "SHACL-JS is not implemented"},
        {"JSTargetType", "SHACL-JS is not implemented"},
        {"JSConstraint", "SHACL-JS is not implemented"},
        {"JSValidator", "SHACL-JS is not implemented"},
        {"JSFunction", "SHACL-JS is not implemented"},
        {"JSLibrary", "SHACL-JS is not implemented"},
        {"JSRule", "SHACL-JS is not implemented"},
        {"SPARQLRule", "rules (SHACL Advanced Features) are not implemented"},
        {"TripleRule", "rules (SHACL Advanced Features) are not implemented"},
        {"SPARQLFunction", "SHACL functions (SHACL Advanced Features) are not implemented"},
        {"Function", "SHACL functions (SHACL Advanced Features) are not implemented"},
    };
    for (auto [name, reason] : kReasons)
      if (name == local) return reason;
    return {};
  }

  static bool known_class(std::string_view local) {
    for (std::string_view name :
         {"Shape", "NodeShape", "PropertyShape", "SPARQLConstraint", "ConstraintComponent",
          "Parameter", "Validator", "SPARQLAskValidator", "SPARQLSelectValidator",
          "SPARQLExecutable", "SPARQLAskExecutable", "SPARQLSelectExecutable", "PrefixDeclaration",
          "ValidationReport", "ValidationResult", "AbstractResult", "Severity", "NodeKind",
          "PropertyGroup"})
      if (name == local) return true;
    return false;
  }

  // Terms of SHACL Advanced Features, SHACL-JS and the like, anywhere in the
  // shapes graph (as a predicate, or as the class of a node): mospec would
  // ignore them, so it refuses them.
  void refuse_unsupported_constructs() {
    g_.scan(TermId::any(), TermId::any(), TermId::any(), TermId::any(),
            [&](const rdf::Quad& q, uint32_t i) {
              const bool is_class = q.predicate == type_ && in_sh(q.object);
              const TermId term = is_class ? q.object : q.predicate;
              if (!in_sh(term)) return true;
              const std::string_view local = t_[term].value.substr(vocab::sh::ns.size());
              std::string_view reason = unsupported_reason(local);
              if (reason.empty() && is_class && !known_class(local))
                fail_at(g_.location(i),
                        show(q.subject) + ": " + sh_name(term) +
                            " is not a SHACL class that mospec knows (misspelt? a node of an "
                            "unknown type would not be treated as a shape)",
                        "unsupported-shacl");
              if (reason.empty()) return true;
              fail_at(g_.location(i),
                      show(q.subject) + ": " + sh_name(term) +
                          " is not supported: " + std::string(reason) +
                          "; remove it, or express the check with "
                          "sh:sparql",
                      "unsupported-shacl");
            });
  }

  // Refuses the SHACL-namespace properties of `node` that are not in
  // `allowed` (nor a parameter of a custom constraint component): a
  // misspelt parameter would otherwise be silently ignored.
  void check_properties(TermId node, const std::unordered_set<uint32_t>& allowed,
                        std::string_view what, const std::unordered_set<uint32_t>* also = nullptr) {
    g_.scan(node, TermId::any(), TermId::any(), TermId::any(), [&](const rdf::Quad& q, uint32_t i) {
      if (!in_sh(q.predicate) || allowed.count(q.predicate.index) != 0 ||
          (also != nullptr && also->count(q.predicate.index) != 0) ||
          custom_params_.count(q.predicate.index) != 0)
        return true;
      if (q.predicate == optional_ && parameter_nodes_.count(node.index) != 0) return true;
      fail_at(g_.location(i),
              show(node) + " (" + std::string(what) + "): " + sh_name(q.predicate) +
                  " is not a SHACL property that mospec implements here; check the spelling, or "
                  "remove it (see docs/validation.md for what is supported)",
              "unsupported-shacl");
    });
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

  // Nesting limits: shape references and path nodes are compiled recursively.
  static constexpr int kMaxShapeDepth = 256;
  static constexpr size_t kMaxPathDepth = 256;
  // Constraints one shape may declare through one custom component.
  static constexpr size_t kMaxCombinations = 64;

  const rdf::Dataset& g_;
  const rdf::TermTable& t_;
  Shapes out_;
  int depth_ = 0;  // shapes being compiled (nested compile() calls)
  std::unordered_map<uint32_t, uint32_t> index_;
  std::unordered_map<uint32_t, Component> params_;
  // SHACL-namespace properties allowed on shapes, sh:sparql constraints,
  // constraint components and validators (predicate ids).
  std::unordered_set<uint32_t> shape_properties_, sparql_properties_, component_properties_,
      validator_properties_;
  std::vector<CustomComponent> components_;
  // Parameter predicate -> the custom components that declare it.
  std::unordered_map<uint32_t, std::vector<uint32_t>> custom_params_;
  std::unordered_set<uint32_t> parameter_nodes_;  // parameter declarations
  std::vector<TermId> referenced_;
  TermId type_, first_, rest_, nil_, subclass_, sparql_, rdfs_class_, node_shape_, property_shape_;
  TermId violation_, warning_, info_;
  TermId path_, target_node_, target_class_, target_subjects_, target_objects_, deactivated_,
      severity_, message_;
  TermId alternative_, inverse_, zero_or_more_, one_or_more_, zero_or_one_, flags_;
  TermId qvs_, qmin_, qmax_, qdisjoint_, ignored_, property_;
  TermId select_, prefixes_, declare_, prefix_, namespace_, owl_imports_;
  TermId constraint_component_, parameter_, optional_, validator_, node_validator_,
      property_validator_, ask_, label_template_;
  TermId nk_blank_, nk_iri_, nk_literal_, nk_blank_iri_, nk_blank_literal_, nk_iri_literal_;
};

Shapes Shapes::compile(const rdf::Dataset& graph, const SourceFiles* files) {
  return ShapesCompiler(graph, files).run();
}

}  // namespace mospec::shacl
