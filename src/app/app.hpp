// The application model: the paper's unit of composition.
//
// An app file is a JSON-LD document whose node lists `import` (model IRIs),
// `constraints` (shape-file IRIs, for verification) and `iri-map` (IRI prefix ->
// local path). Loading an app resolves its iri-map, loads every imported model
// once, in the order listed, and keeps per-quad provenance so later stages can
// point at the file and line where an entity is written.
#pragma once

#include <chrono>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "jsonld/loader.hpp"
#include "rdf/dataset.hpp"
#include "support/diagnostics.hpp"
#include "vocab/metamodels.hpp"

namespace mospec::app {

inline constexpr std::string_view kAppNs = vocab::app::ns;

struct LoadOptions {
  // Extra IRI-prefix -> directory mappings (the CLI's --map IRI=DIR), applied
  // before any app file's iri-map.
  std::vector<std::pair<std::string, std::string>> maps;
  // Directory that the iri-map's relative paths resolve against. Unset: the
  // current directory (what the authors' tool does).
  std::optional<std::string> root;
  // Resolve the metamodel base (vocab::kMetamodels) to mospec's own metamodels
  // (builtin_metamodels_dir()), and the secorolab base (vocab::kSecorolab) to
  // its secorolab/ folder, wherever no --map or iri-map entry covers them.
  bool builtin_metamodels = true;
  // Threads that read, parse and expand an app's imports at once (the quads
  // are made on the calling thread, in order, so the model is the same for
  // any number). 0: two where the machine has two cores, else one. The
  // mospec commands use one (a single load in a fresh process; docs/ir.md,
  // "Loading on two threads").
  unsigned threads = 0;
  // With more than one thread: how long the calling thread waits for a
  // document another thread is preparing before it prepares the document
  // itself as well (a thread whose core was taken away must not hold the
  // load up; about four times what expanding one of the shipped models takes).
  std::chrono::microseconds helper_patience{200};
};

// One loaded JSON-LD document.
struct ModelFile {
  std::string iri;   // the IRI it was loaded as
  std::string path;  // local path it was read from
  uint32_t file_id = 0;
  bool is_app = false;
  SourceLoc imported_at;  // where the app's import list names it (unknown for CLI inputs)
};

// An entity the app leaves out of the model it imports (mospec/app#drop).
struct Drop {
  std::string iri;
  SourceLoc at;  // the app's statement
};

struct AppInfo {
  std::string file;                      // the app file's path
  std::vector<std::string> imports;      // model IRIs, duplicates removed, in order
  std::vector<std::string> constraints;  // shape-file IRIs
  std::vector<std::pair<std::string, std::string>> iri_map;  // prefix -> resolved dir
  std::vector<Drop> drops;
};

class LoadedModel {
 public:
  jsonld::MappedDocumentLoader& loader() { return loader_; }
  const SourceFiles& files() const { return loader_.files(); }
  // Every quad of every file. Quads in a file's default graph are placed in a
  // graph named by that file's IRI, so each file keeps its own graph; quads
  // that a file puts in a named graph of its own stay there.
  const rdf::Dataset& dataset() const { return dataset_; }
  rdf::Dataset& dataset() { return dataset_; }
  // The union of all graphs as triples: what validation and lowering read.
  rdf::Dataset flattened() const { return dataset_.flattened_union(); }
  const std::vector<ModelFile>& model_files() const { return files_; }
  const std::vector<AppInfo>& apps() const { return apps_; }
  const DiagnosticSink& diagnostics() const { return diagnostics_; }
  DiagnosticSink& diagnostics() { return diagnostics_; }

  // Where an entity's "@id" is first written (the first quad with it as subject).
  std::optional<SourceLoc> where(rdf::TermId subject) const;
  std::string describe(SourceLoc loc) const;  // "file:line:col"

 private:
  friend LoadedModel load(const std::vector<std::string>&, const LoadOptions&);
  jsonld::MappedDocumentLoader loader_;
  rdf::Dataset dataset_;
  std::vector<ModelFile> files_;
  std::vector<AppInfo> apps_;
  DiagnosticSink diagnostics_;
};

inline constexpr std::string_view kMetamodelsIri = vocab::kMetamodels;
inline constexpr std::string_view kSecorolabIri = vocab::kSecorolab;

// Where mospec's own metamodels are: $MOSPEC_METAMODELS_DIR if set, else the
// metamodels/ folder of the source tree mospec was built from.
std::string builtin_metamodels_dir();

// Loads each input (an app file or a plain JSON-LD model file). Warnings (dropped
// keys, undefined types) are collected in diagnostics(); errors throw mospec::Error.
// What an app drops (mospec/app#drop) is gone from the model: every statement
// about the entity and every reference to it, each drop noted in diagnostics().
LoadedModel load(const std::vector<std::string>& inputs, const LoadOptions& options = {});

}  // namespace mospec::app
