// libFuzzer target for the Turtle reader (serd underneath, plus mospec's
// base-IRI resolution, blank-node renaming and locations).
//
// Invariants checked beyond "no crash, no sanitizer report": rejections are
// mospec::Error with code "syntax" and a location; anything the reader accepts
// is written as N-Quads that the N-Quads reader accepts again, isomorphic to
// what was read; every quad read has a location inside the input.
//
// Ill-formed UTF-8 is rejected by the reader itself (Turtle documents are
// UTF-8), so everything it accepts must round-trip.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>

#include "rdf/isomorphism.hpp"
#include "rdf/nquads.hpp"
#include "rdf/turtle.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  mospec::rdf::Dataset first;
  try {
    mospec::rdf::read_turtle(text, "http://example.org/base/doc.ttl", first, 1, "fuzz.ttl");
  } catch (const mospec::Error& e) {
    if (e.code() != "syntax") std::abort();
    if (e.diagnostic().file != "fuzz.ttl") std::abort();
    return 0;
  }
  uint32_t lines = 1;
  for (char c : text) lines += c == '\n' ? 1 : 0;
  for (size_t i = 0; i < first.size(); ++i) {
    mospec::SourceLoc loc = first.location(i);
    if (loc.file != 1 || loc.line > lines) std::abort();
  }
  const std::string written = mospec::rdf::to_nquads(first);
  mospec::rdf::Dataset second;
  mospec::rdf::read_nquads(written, second);  // throwing here: reader and writer disagree
  if (!mospec::rdf::isomorphic(first, second)) std::abort();
  return 0;
}
