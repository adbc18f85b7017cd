// The compiled shapes model: every shape of a SHACL shapes graph, parsed once
// into plain structs (term ids, counts, compiled regexes and paths) so that
// validation never looks at the shapes graph's triples or at IRI strings.
//
// Term ids in the model are ids of the shapes graph's TermTable; the validator
// translates them to the data graph once per validation run.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "rdf/dataset.hpp"
#include "sparql/path.hpp"
#include "sparql/query.hpp"
#include "sparql/regex.hpp"
#include "support/diagnostics.hpp"

namespace mospec::shacl {

// The constraint components of SHACL Core (plus SHACL-SPARQL's sh:sparql).
enum class Component : uint8_t {
  Class,
  Datatype,
  NodeKind,
  MinCount,
  MaxCount,
  MinExclusive,
  MinInclusive,
  MaxExclusive,
  MaxInclusive,
  MinLength,
  MaxLength,
  Pattern,
  LanguageIn,
  UniqueLang,
  Equals,
  Disjoint,
  LessThan,
  LessThanOrEquals,
  Not,
  And,
  Or,
  Xone,
  Node,
  Property,
  QualifiedMinCount,
  QualifiedMaxCount,
  Closed,
  HasValue,
  In,
  Sparql,
  // A SPARQL-based constraint component declared in the shapes graph (SHACL
  // 6); its IRI is SparqlConstraint::component.
  SparqlComponent,
};

// "http://www.w3.org/ns/shacl#ClassConstraintComponent" etc. (empty for
// SparqlComponent, whose IRI is the constraint's).
std::string_view component_iri(Component);
// "sh:ClassConstraintComponent" etc. (empty for SparqlComponent).
std::string_view component_name(Component);

enum NodeKindMask : uint8_t { kBlankNode = 1, kIri = 2, kLiteral = 4 };

enum class Level : uint8_t { Info, Warning, Violation, Other };

// A SHACL-SPARQL constraint, parsed once: a value of sh:sparql, or one use of
// a SPARQL-based constraint component (SHACL 6) by a shape, with the values
// of the component's parameters.
struct SparqlConstraint {
  // The node that holds the query: the sh:sparql value (reported as
  // sh:sourceConstraint), or the validator of a component (not reported).
  rdf::TermId node = rdf::TermId::any();
  // sh:select (or the validator's sh:ask) with sh:prefixes applied, $PATH
  // substituted in property shapes' SELECT queries.
  sparql::Query query;
  // sh:message of the constraint, else of the validator, else of the
  // component (may hold {?var} / {$param}).
  std::vector<rdf::TermId> messages;
  bool binds_current_shape = false;  // the query mentions $currentShape

  // SPARQL-based constraint components only.
  rdf::TermId component = rdf::TermId::any();  // its IRI (sh:sourceConstraintComponent)
  bool ask = false;  // an sh:SPARQLAskValidator: one ASK per value node ($value pre-bound)
  // Pre-bound parameters: (parameter name, value in the shapes graph), in the
  // order the component declares them; optional parameters without a value
  // are left out.
  std::vector<std::pair<std::string, rdf::TermId>> parameters;
  std::vector<rdf::TermId> labels;  // the component's sh:labelTemplate (default message)
  // Each parameter declaration that carries constraints of its own (SHACL 6.1:
  // "Shapes that do not conform ... are ill-formed"): the index of the
  // declaration compiled as a property shape (for the check after compiling).
  std::vector<uint32_t> parameter_shapes;
};

struct Constraint {
  Component component = Component::Class;
  SourceLoc where;  // the parameter's triple in the shapes files
  // Class, Datatype, HasValue, Equals/Disjoint/LessThan(OrEquals) predicate,
  // Min/Max In/Exclusive bound literal.
  rdf::TermId term;
  int64_t number = 0;               // Min/MaxCount, Min/MaxLength, qualified counts
  uint8_t node_kinds = 0;           // NodeKind: NodeKindMask bits
  std::vector<rdf::TermId> terms;   // In members, LanguageIn ranges (literals)
  std::vector<std::string> ranges;  // LanguageIn ranges as text
  std::vector<uint32_t> shapes;     // Not/Node/Property/QualifiedX: one; And/Or/Xone: members
  std::vector<uint32_t> siblings;   // QualifiedX with sh:qualifiedValueShapesDisjoint true
  std::shared_ptr<const sparql::Regex> regex;  // Pattern (sh:flags applied)
  std::shared_ptr<const SparqlConstraint> sparql;
};

struct Shape {
  rdf::TermId node;  // the shape's IRI or blank node in the shapes graph
  SourceLoc where;   // first triple about the shape
  bool is_property = false;
  bool deactivated = false;
  sparql::PathPtr path;                       // property shapes
  rdf::TermId path_node;                      // the sh:path value (for reports)
  Level level = Level::Violation;             // sh:severity (default sh:Violation)
  rdf::TermId severity = rdf::TermId::any();  // the sh:severity IRI when level is Other
  std::vector<rdf::TermId> messages;          // sh:message literals
  std::vector<Constraint> constraints;
  // Targets.
  std::vector<rdf::TermId> target_nodes, target_classes, target_subjects_of, target_objects_of;
  bool has_targets() const {
    return !target_nodes.empty() || !target_classes.empty() || !target_subjects_of.empty() ||
           !target_objects_of.empty();
  }
  // Closed: the predicates allowed on value nodes (sh:path predicates of the
  // sh:property shapes plus sh:ignoredProperties), sorted.
  std::vector<rdf::TermId> closed_allowed;
};

class Shapes {
 public:
  // Compiles every shape of `graph` (which must outlive the Shapes). `files`
  // names the file ids of the graph's source locations in error messages.
  // Ill-formed shapes throw mospec::Error (code "shacl-ill-formed") naming the
  // shape and the file:line:col of the offending triple. So do, with code
  // "unsupported-shacl", constructs mospec does not implement (SHACL-AF, SHACL-JS,
  // unknown sh: properties and classes; docs/validation.md), and with code
  // "shacl-too-deep" shapes or paths nesting deeper than 256 levels.
  static Shapes compile(const rdf::Dataset& graph, const SourceFiles* files = nullptr);

  const rdf::Dataset& graph() const { return *graph_; }
  const std::vector<Shape>& shapes() const { return shapes_; }
  const Shape& operator[](uint32_t i) const { return shapes_[i]; }
  // Every term the model refers to (constraint parameters, targets, path
  // predicates), so a validator translates just these.
  const std::vector<rdf::TermId>& referenced_terms() const { return referenced_; }
  // "<iri>" or "_:b at file:line" for messages.
  std::string describe(uint32_t shape) const;
  const SourceFiles* files() const { return files_; }

 private:
  friend class ShapesCompiler;
  const rdf::Dataset* graph_ = nullptr;
  const SourceFiles* files_ = nullptr;
  std::vector<Shape> shapes_;
  std::vector<rdf::TermId> referenced_;
};

namespace detail {
// Checks every shape that uses a SPARQL-based constraint component against
// the constraints its parameter declarations carry (SHACL 6.1: such a shape is
// ill-formed otherwise); throws "shacl-ill-formed". Defined in validate.cpp,
// called by Shapes::compile.
void check_component_parameters(const Shapes& shapes);
}  // namespace detail

// "file:line:col" of a location (empty when unknown).
std::string describe_location(const SourceFiles* files, SourceLoc loc);

// SPARQL surface syntax of a path ("<p>/^<q>*"), for messages and reports.
std::string path_to_sparql(const rdf::TermTable& terms, const sparql::Path& path);

}  // namespace mospec::shacl
