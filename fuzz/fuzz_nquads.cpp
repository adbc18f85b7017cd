// libFuzzer target for the N-Quads reader and writer.
//
// Invariants checked beyond "no crash, no sanitizer report": anything the
// reader accepts is written in a form the reader accepts again, and that
// second reading is isomorphic to the first (escaping and canonical forms are
// lossless). Rejections must be mospec::Error; any other exception escapes and
// is reported by libFuzzer.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <string_view>

#include "rdf/isomorphism.hpp"
#include "rdf/nquads.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  mospec::rdf::Dataset first;
  try {
    mospec::rdf::read_nquads(text, first, 1, "fuzz.nq");
  } catch (const mospec::Error& e) {
    if (e.code() != "syntax") std::abort();
    return 0;
  }
  const std::string written = mospec::rdf::to_nquads(first);
  mospec::rdf::Dataset second;
  mospec::rdf::read_nquads(written, second);  // throwing here is a writer bug
  if (!mospec::rdf::isomorphic(first, second)) std::abort();
  // Writing is deterministic.
  if (mospec::rdf::to_nquads(first) != written) std::abort();
  return 0;
}
