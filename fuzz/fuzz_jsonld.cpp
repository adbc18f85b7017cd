// libFuzzer target: arbitrary bytes through the JSON parser, expansion and RDF
// deserialisation. Every failure must surface as mospec::Error; any other
// exception, a crash or a sanitizer report is a bug.
#include <cstddef>
#include <cstdint>
#include <new>
#include <string_view>
#include <utility>

#include "json/json.hpp"
#include "jsonld/expand.hpp"
#include "jsonld/loader.hpp"
#include "jsonld/to_rdf.hpp"
#include "rdf/dataset.hpp"
#include "support/arena.hpp"
#include "support/diagnostics.hpp"

namespace {

// Maps no IRI prefix, and also refuses what an unmapped loader would still
// read (file: IRIs, plain paths), so a fuzzed "@context": "file:///dev/zero"
// cannot reach the file system; unmapped IRIs take the real error path.
class NoFilesLoader : public mospec::jsonld::MappedDocumentLoader {
 public:
  mospec::jsonld::RemoteDocument load(std::string_view iri, mospec::SourceLoc referenced_from,
                                      bool for_context) override {
    if (!resolve(iri).empty()) {
      throw mospec::Error(for_context ? mospec::DiagnosticCode("loading remote context failed")
                                      : mospec::DiagnosticCode("loading document failed"),
                          "the fuzz target reads no files");
    }
    return MappedDocumentLoader::load(iri, referenced_from, for_context);
  }
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  std::string_view text(reinterpret_cast<const char*>(data), size);
  NoFilesLoader loader;
  mospec::jsonld::Options options;
  options.base = "https://example.org/fuzz/doc.jsonld";
  options.loader = &loader;
  mospec::DiagnosticSink diagnostics;
  options.diagnostics = &diagnostics;
  // As app::load does it: the document parsed into an arena and expanded
  // into one, both trees dropped with the arena and never destroyed. That is
  // sound only if every block of them is in the arena: checked here, and a
  // block on the heap would also be reported as a leak.
  mospec::Arena arena;
  auto in_arena = [&arena](mospec::json::Value v) -> const mospec::json::Value& {
    auto* slot = arena.allocate(sizeof(mospec::json::Value), alignof(mospec::json::Value));
    const auto* kept = new (slot) mospec::json::Value(std::move(v));
    if (!mospec::json::lives_in(*kept, &arena)) __builtin_trap();
    return *kept;
  };
  try {
    const mospec::json::Value& document = in_arena(mospec::json::parse(text, 0, "<fuzz>", &arena));
    const mospec::json::Value& expanded =
        in_arena(mospec::jsonld::expand(document, options, &arena));
    mospec::rdf::Dataset dataset;
    mospec::jsonld::to_rdf(expanded, dataset, options);
  } catch (const mospec::Error&) {
    // Expected for invalid input.
  }
  return 0;
}
