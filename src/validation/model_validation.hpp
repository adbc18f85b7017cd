// Validating a loaded app model: the shape files it names (or that the caller
// adds) are read into one shapes graph, compiled, and the model's dataset is
// validated against them. This is what `mospec validate` runs, kept in a
// library so tests and benchmarks run the very same pipeline in-process.
//
// Shape files share the model's SourceFiles table, so every location (data,
// shapes, errors) prints as file:line:col.
#pragma once

#include <memory>
#include <span>
#include <string>
#include <vector>

#include "app/app.hpp"
#include "rdf/dataset.hpp"
#include "shacl/report.hpp"
#include "shacl/shapes.hpp"
#include "shacl/validate.hpp"
#include "support/diagnostics.hpp"

namespace mospec::validation {

// One shape file to read.
struct ShapeFile {
  std::string path;    // local path
  std::string iri;     // base IRI for relative references inside it
  SourceLoc named_at;  // where an app file names it (unknown for --shapes)
  // Added by validate_model because the model uses its vocabulary (not listed
  // by the app): mospec's own shapes come with mospec's metamodels.
  bool automatic = false;
};

// The syntax of a shape file, from its extension (.ttl/.turtle, .trig,
// .nt/.nq, .json/.jsonld); other extensions are sniffed: a first
// non-blank '{' or '[' means JSON-LD, anything else Turtle.
enum class ShapeSyntax : uint8_t { Turtle, TriG, NQuads, JsonLd };
ShapeSyntax shape_syntax(const std::string& path, std::string_view content);

// Reads one shape file into `into`, registering it in loader.files() so its
// quads are located. A missing, unreadable or ill-formed file throws
// mospec::Error (located at the syntax error, or at `named_at` when the file
// cannot be read). JSON-LD shape files go through `loader` (contexts resolve
// through its IRI mappings) and report dropped keys to `diagnostics`.
void read_shape_file(const ShapeFile& file, jsonld::MappedDocumentLoader& loader,
                     rdf::Dataset& into, DiagnosticSink* diagnostics = nullptr);

// The shape files of a loaded model: every app's `constraints` IRIs resolved
// through its iri-map (in order, duplicates once), then `extra` local paths
// (the CLI's --shapes). An IRI that no mapping covers throws mospec::Error
// located at the app file's constraints entry.
std::vector<ShapeFile> shape_files(app::LoadedModel& model, const std::vector<std::string>& extra,
                                   bool use_app_constraints = true);

struct ModelValidationOptions {
  std::vector<std::string> extra_shapes;  // local paths (--shapes)
  bool use_app_constraints = true;        // read the apps' `constraints` lists
  // When the model's vocabulary resolves to mospec's metamodels (the
  // directory holding mospec/shape-files.txt), also apply every shape file it
  // lists whose targets select a node of the model — whatever the apps list.
  // An app resolving the vocabulary elsewhere keeps exactly its own list.
  bool vocabulary_shapes = true;
  bool strict = false;  // compute strict_findings
  // The SPARQL time and step budget of the whole validation (every SPARQL
  // constraint and sh:path, for every shape and focus node).
  sparql::Limits sparql_limits;
};

struct ModelValidation {
  std::vector<ShapeFile> files;                // the shape files read, in order
  std::unique_ptr<rdf::Dataset> shapes_graph;  // owned: `shapes` points into it
  std::unique_ptr<shacl::Shapes> shapes;
  shacl::Report report;
  // Under `strict`: shapes whose targets select no node ("shape-unused"),
  // rdf:type values that nothing defines ("undefined-type"), classes of
  // mospec's metamodels that no shape covers ("unshaped-term"), as warnings.
  std::vector<Diagnostic> strict_findings;
  // Loader-style warnings raised while reading JSON-LD shape files.
  DiagnosticSink shape_diagnostics;
};

// mospec's shape files for a model (ModelValidationOptions::vocabulary_shapes):
// those listed by <metamodels>/mospec/shape-files.txt, as the model's loader
// resolves it, whose targets (sh:targetClass, implicit class targets,
// sh:targetSubjectsOf/ObjectsOf, sh:targetNode) select a node of the model and
// whose node shapes `into` (the shapes read so far) does not hold. Each is
// read into `into`. A file whose path is one of `read_before` (the files read
// into `into` so far) is skipped without being read. Empty when the
// vocabulary does not resolve to mospec's metamodels.
std::vector<ShapeFile> vocabulary_shape_files(app::LoadedModel& model, rdf::Dataset& into,
                                              DiagnosticSink* diagnostics = nullptr,
                                              std::span<const ShapeFile> read_before = {});

// One cause, one error: a reference to an entity no loaded file defines is
// reported once, by mos:DefinedReferences (with the nearest defined IRI as a
// hint); the other results about the same value, and those about a node the
// cause's focus names, are marked as following from it (Result::follows),
// which the text report prints as notes. The report graph is unchanged.
void note_follow_on_results(shacl::Report& report, const rdf::Dataset& data);

// The whole pipeline on a loaded model: read shape files, compile (ill-formed
// shapes throw mospec::Error "shacl-ill-formed", located), validate every graph
// of the model's dataset as one graph. No shape files at all throws
// mospec::Error "usage".
ModelValidation validate_model(app::LoadedModel& model, const ModelValidationOptions& options);

// Strict checks (also run by validate_model under `strict`).
//  * shape-unused: a shape with targets (sh:targetClass etc., or implicit
//    class targets) that selects no focus node in the data.
//  * undefined-type: an IRI used as an rdf:type object in the data that is
//    "defined" by nothing loaded. Defined means: some term of a JSON-LD
//    context used by the model's files (their @context entries, the remote
//    contexts those load, and the scoped contexts inside their term
//    definitions) maps to exactly that IRI; or the shapes graph mentions it
//    as a subject or as the object of sh:targetClass or sh:class.
//  * unshaped-term: when the vocabulary resolves to mospec's metamodels (as
//    for vocabulary_shape_files), a class in their namespace that types a
//    node of the model and that no shape covers: no active shape's
//    sh:targetClass or implicit class target is the class or, through
//    rdfs:subClassOf in the data or shapes graph, a superclass of it; and
//    <metamodels>/mospec/unshaped-terms.txt does not list it. Reported once
//    per class, at the first node's rdf:type statement. Likewise a predicate
//    of theirs (the application/ terms aside) that the model uses and that
//    no shape's sh:path names, once per predicate at its first statement.
// Shapes of `files` marked automatic are not reported as shape-unused.
std::vector<Diagnostic> strict_checks(app::LoadedModel& model, const shacl::Shapes& shapes,
                                      const std::vector<ShapeFile>& files = {});

// The class IRIs listed by an unshaped-terms file (metamodels/mospec/
// unshaped-terms.txt): one IRI (<...> or bare absolute) or CURIE per line,
// CURIE prefixes declared by earlier '@prefix NAME: <IRI> .' lines; '#'
// starts a comment (the reason). A malformed line throws mospec::Error
// "unshaped-terms" located at it.
std::vector<std::string> read_unshaped_terms(const std::string& path);

// Every IRI that a term of the model files' JSON-LD contexts maps to.
std::vector<std::string> context_term_iris(app::LoadedModel& model);

}  // namespace mospec::validation
