// SHACL validation reports: the results, their deterministic order, and the
// Turtle / text / RDF renderings.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "rdf/dataset.hpp"
#include "shacl/shapes.hpp"
#include "sparql/path.hpp"
#include "support/diagnostics.hpp"

namespace mospec::shacl {

// One sh:ValidationResult. Term ids refer to Report::terms.
struct Result {
  rdf::TermId focus;                       // sh:focusNode
  rdf::TermId value = rdf::TermId::any();  // sh:value (any(): none)
  rdf::TermId shape;                       // sh:sourceShape
  Component component = Component::Class;  // sh:sourceConstraintComponent
  // The component's IRI when component is SparqlComponent (else any()).
  rdf::TermId component_node = rdf::TermId::any();
  rdf::TermId source_constraint = rdf::TermId::any();  // sh:sourceConstraint (SHACL-SPARQL)
  sparql::PathPtr path;                                // sh:resultPath (null: none)
  Level level = Level::Violation;                      // sh:resultSeverity
  rdf::TermId severity = rdf::TermId::any();           // the severity IRI when level is Other
  std::vector<rdf::TermId> messages;                   // sh:resultMessage, from sh:message
  std::string default_message;  // generated text for results without sh:message
  SourceLoc focus_loc;          // where the focus node is written (data files)
  SourceLoc shape_loc;          // where the shape is written (shapes files)
  // Where the value node is written, when it is a node of the data other than
  // the focus (unknown otherwise).
  SourceLoc value_loc;
  // SHACL-SPARQL: other data nodes the result's row names (e.g. the upper
  // threshold a lower one exceeds), each where it is written.
  struct Related {
    std::string name;  // the query's variable
    rdf::TermId node;
    SourceLoc where;
  };
  std::vector<Related> related;
  // For the text report only (the report graph is what SHACL says):
  // a hint appended to the message ("did you mean <X>?"), and the index of
  // the result this one most likely follows from (-1: none), which the text
  // report prints as a note under that cause rather than as a second error.
  std::string hint;
  int follows = -1;
};

class Report {
 public:
  rdf::TermTable terms;
  std::vector<Result> results;

  bool conforms() const { return results.empty(); }
  size_t count(Level level) const;
  // Deterministic order: focus node location (unlocated last), focus node,
  // shape, component, path, value.
  void sort();
};

// As the text report writes it, in the project's diagnostic shape
// (file:line:col: error: ...): "error", "warning", "info", "other".
std::string_view diagnostic_level(Level);

// The IRI of a result's sh:sourceConstraintComponent.
std::string result_component_iri(const Report& report, const Result& result);

// The report graph in Turtle: sh:ValidationReport with nested results,
// standard prefixes, byte-for-byte deterministic for a sorted report.
std::string to_turtle(const Report& report);

// Two lines per result, in the project's diagnostic shape: the finding at the
// focus node, then a note at the shape that fired,
//   file:line:col: error|warning|info: <focus>: <message> [<component>, path <P>, value <V>]
//   shapes.ttl:line:col: note: the shape that fired: <S>|[]
// and a note where the value node is written, and where each other data node
// a SPARQL constraint's row names is (?upper: "note: upper <U> is here"); then "shacl: N
// violations, M warnings, K infos" (plus other severities when present). A result that
// follows from another (Result::follows) is a note naming its cause. `data_files` names
// Result::focus_loc, `shape_files` Result::shape_loc.
std::string to_text(const Report& report, const SourceFiles* data_files,
                    const SourceFiles* shape_files = nullptr);

// The report graph as JSON-LD: one node object with a small context ("sh",
// "xsd"), results nested in report order, blank-node focus nodes as "_:"
// identifiers. Deterministic for a sorted report.
std::string to_jsonld(const Report& report);

// The report graph as a dataset (for comparisons, e.g. the W3C test suite).
rdf::Dataset to_dataset(const Report& report);

}  // namespace mospec::shacl
