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
};

// "http://www.w3.org/ns/shacl#ClassConstraintComponent" etc.
std::string_view component_iri(Component);
// "sh:ClassConstraintComponent" etc.
std::string_view component_name(Component);

enum NodeKindMask : uint8_t { kBlankNode = 1, kIri = 2, kLiteral = 4 };

enum class Level : uint8_t { Info, Warning, Violation, Other };

// A SHACL-SPARQL constraint (a value of sh:sparql), parsed once.
struct SparqlConstraint {
  rdf::TermId node;                   // the sh:sparql value (sh:sourceConstraint)
  sparql::Query query;                // sh:select with sh:prefixes applied, $PATH substituted
  std::vector<rdf::TermId> messages;  // sh:message of the constraint (may hold {?var})
  bool binds_current_shape = false;   // the query mentions $currentShape
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
  // shape and the file:line:col of the offending triple.
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

// "file:line:col" of a location (empty when unknown).
std::string describe_location(const SourceFiles* files, SourceLoc loc);

// SPARQL surface syntax of a path ("<p>/^<q>*"), for messages and reports.
std::string path_to_sparql(const rdf::TermTable& terms, const sparql::Path& path);

}  // namespace mospec::shacl
