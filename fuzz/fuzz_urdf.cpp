// libFuzzer target for `mospec import-urdf`: URDF text -> chain -> JSON-LD text.
// URDFs are downloaded and shared like models, so the text is untrusted.
//
// Invariants beyond "no crash, no sanitizer report, no leak, no hang": every
// refusal is a mospec::Error with code "invalid-urdf" that names the file
// (located at LINE:COL whenever the offending element is known); nothing else
// escapes; TinyXML never refuses what the XML scan passed. A chain that is accepted is written
// without refusal, and what is written holds no non-finite number and no control character.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "description/chain_jsonld.hpp"
#include "description/urdf_import.hpp"
#include "support/diagnostics.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  mospec::runtime::Chain chain("");
  try {
    // The URDF's root link to its only leaf, as import-urdf does by default.
    chain = mospec::description::chain_from_urdf(text, "", "", "fuzz.urdf");
  } catch (const mospec::Error& e) {
    if (e.code() != "invalid-urdf" || e.diagnostic().file != "fuzz.urdf") std::abort();
    // scan_xml is stricter than TinyXML: a document it passes that TinyXML
    // cannot parse means the two read it differently (and TinyXML may then
    // see nesting the scan's limits never counted).
    const std::string& m = e.diagnostic().message;
    if (m.starts_with("urdfdom cannot read the URDF: Error") ||
        m.starts_with("urdfdom cannot read the URDF: Failed to read")) {
      std::abort();
    }
    return 0;
  }
  const std::string written = mospec::description::chain_to_jsonld(chain);
  // Outside its strings the document holds only numbers, punctuation and line
  // breaks: a letter other than an exponent's 'e' is an "inf" or a "nan".
  // Inside them no control character may stand raw.
  bool in_string = false;
  for (std::size_t i = 0; i < written.size(); ++i) {
    const char c = written[i];
    const bool control = static_cast<unsigned char>(c) < 0x20;
    if (in_string) {
      if (control) std::abort();
      if (c == '\\') {
        ++i;
      } else if (c == '"') {
        in_string = false;
      }
    } else if (c == '"') {
      in_string = true;
    } else if ((control && c != '\n') ||
               (((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z')) && c != 'e')) {
      std::abort();
    }
  }
  return 0;
}
