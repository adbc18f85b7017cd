// Options and the term-drop policy shared by the JSON-LD algorithms.
#pragma once

#include <memory>
#include <optional>
#include <string>

#include "json/json.hpp"
#include "support/diagnostics.hpp"

namespace mospec::jsonld {

class DocumentLoader;
class ContextCache;

enum class ProcessingMode : uint8_t { JsonLd10, JsonLd11 };
enum class RdfDirection : uint8_t { None, I18nDatatype, CompoundLiteral };

struct Options {
  std::string base;  // document base IRI
  std::optional<json::Value> expand_context;
  ProcessingMode processing_mode = ProcessingMode::JsonLd11;
  bool ordered = false;
  bool produce_generalized_rdf = false;
  RdfDirection rdf_direction = RdfDirection::None;
  // toRdf: the graph that receives the default graph's quads (an IRI, used as
  // is). Empty: the dataset's default graph.
  std::string default_graph;
  DocumentLoader* loader = nullptr;  // required for remote contexts
  // Where silent drops are reported (keys that expand to no IRI, @type values
  // that are not defined terms and become document-relative IRIs). nullptr: not
  // reported. The file name in diagnostics comes from the loader's SourceFiles.
  DiagnosticSink* diagnostics = nullptr;
  // Memo of processed contexts (see ContextCache in context.hpp). Share one per
  // loader across the documents of a run so that remote and scoped contexts are
  // processed once; nullptr: every process_context call starts from scratch.
  std::shared_ptr<ContextCache> context_cache;
  // Expansion: with `property_prefix_seen` set, *property_prefix_seen becomes
  // true when a property of the result expands to an IRI starting with
  // `property_prefix` (so the app loader learns whether a document uses the
  // app vocabulary without walking the expanded document again).
  std::string property_prefix;
  bool* property_prefix_seen = nullptr;
};

}  // namespace mospec::jsonld
