// libFuzzer target for the SHACL shapes compiler and validator: the input is one
// Turtle document that is both the shapes graph and the data graph (shape files
// are downloaded and shared, so they are as untrusted as models).
//
// Invariants beyond "no crash, no sanitizer report, no hang": every rejection
// is a mospec::Error (a syntax error of the Turtle, an ill-formed or
// unsupported shapes graph, a recursion, a regex or query limit) carrying a
// code; nothing else escapes.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "rdf/turtle.hpp"
#include "shacl/shapes.hpp"
#include "shacl/validate.hpp"
#include "support/diagnostics.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    mospec::rdf::Dataset graph;
    mospec::rdf::read_turtle(text, "http://example.org/shapes.ttl", graph, 1, "fuzz.ttl");
    const mospec::shacl::Shapes shapes = mospec::shacl::Shapes::compile(graph);
    (void)mospec::shacl::validate(shapes, graph);
  } catch (const mospec::Error& e) {
    if (e.code().empty()) std::abort();
  }
  return 0;
}
