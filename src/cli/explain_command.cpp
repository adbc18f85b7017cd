// `mospec explain [CODE]`: a diagnostic code's entry in the catalogue
// (src/support/diagnostic_codes.hpp, docs/diagnostics.md); every entry without
// a code. MOSPEC_DIAGNOSTIC_CODES=1 shows the codes of what mospec reports.
#include <iostream>
#include <memory>
#include <string>

#include "cli/commands.hpp"
#include "support/diagnostics.hpp"
#include "support/paths.hpp"
#include "support/spelling.hpp"

namespace mospec::cli {
namespace {

void print(const CodeEntry& e) {
  std::cout << e.code << ": " << to_string(e.severity) << (e.internal ? ", internal" : "") << " ("
            << e.stage << "): " << e.meaning << '\n';
}

}  // namespace

Action add_explain_command(CLI::App& app) {
  auto code = std::make_shared<std::string>();
  CLI::App* cmd = app.add_subcommand(
      "explain",
      "What a diagnostic code means (docs/diagnostics.md); every code without one. "
      "MOSPEC_DIAGNOSTIC_CODES=1 writes each diagnostic's code after its severity.");
  cmd->add_option("code", *code, "A diagnostic code, e.g. loop-sign")->type_name("CODE");
  return [code]() {
    if (code->empty()) {
      for (const CodeEntry& e : kDiagnosticCodes) print(e);
      return kExitOk;
    }
    if (const CodeEntry* e = DiagnosticCode::find(*code)) {
      print(*e);
      return kExitOk;
    }
    Nearest nearest(*code);
    for (const CodeEntry& e : kDiagnosticCodes) nearest.offer(e.code);
    std::string message = "no diagnostic code '" + escaped_bytes(*code) + "'";
    if (!nearest.best().empty()) message += "; did you mean '" + std::string(nearest.best()) + "'?";
    message += " (mospec explain lists them all)";
    throw Error("usage", message);
  };
}

}  // namespace mospec::cli
