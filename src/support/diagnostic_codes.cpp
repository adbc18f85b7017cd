#include "support/diagnostic_codes.hpp"

#include <ostream>
#include <stdexcept>

namespace mospec {

namespace detail {
void diagnostic_code_not_in_catalogue() {}
}  // namespace detail

const CodeEntry* DiagnosticCode::find(std::string_view code) {
  const uint16_t i = index_of(code);
  return i == kNone ? nullptr : &kDiagnosticCodes[i];
}

DiagnosticCode DiagnosticCode::checked(std::string_view code) {
  DiagnosticCode c;
  if (code.empty()) return c;  // no code, as a default-made Diagnostic has
  c.index_ = index_of(code);
  if (c.empty()) {
    throw std::logic_error("the diagnostic code '" + std::string(code) +
                           "' is not in the catalogue (src/support/diagnostic_codes.hpp)");
  }
  return c;
}

DiagnosticCode::DiagnosticCode(const std::string& code) : DiagnosticCode(checked(code)) {}

std::ostream& operator<<(std::ostream& out, const DiagnosticCode& code) {
  return out << code.name();
}

}  // namespace mospec
