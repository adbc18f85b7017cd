// Diagnostic tests that read like the model (clang -verify, MLIR
// -verify-diagnostics): each case under tests/ir/diagnostics/<case>/ is a small
// app model (app.json and the files it imports) plus `expected.txt`, which
// states every diagnostic lowering must report and where:
//
//   # a comment
//   validation: clean
//   model.json:{{"@id": "compose",}}: error[missing-property]: names no `in2`
//   model.json:17: error[type-mismatch]: must be a pose
//   model.json:30: warning[controller-reaches-no-solver]: reaches no solver
//   -: error[some-code]: a diagnostic with no file:line
//
// `error[...]` is an error lowering throws (ir::LowerError), `warning[...]` a
// warning and `note[...]` a note it reports through LowerOptions::warnings.
//
// `validation:` says what `mospec ir` would do before lowering: `clean` (the
// app's shapes accept the model, so the CLI reaches this diagnostic) or
// `refused` (SHACL already refuses it; the case tests lowering directly).
// A location is a file relative to the case directory and either a line
// number or {{TEXT}}: the one line of that file containing TEXT. The message
// is a substring of the diagnostic's message (^TEXT: its beginning). The comparison is exact: every
// expected diagnostic must be reported (at that file and line, with that code)
// and nothing else may be. See docs/testing.md.
#pragma once

#include <filesystem>
#include <set>
#include <string>
#include <vector>

#include "support/diagnostics.hpp"

namespace mospec::test {

struct ExpectedDiagnostic {
  std::filesystem::path file;  // empty: not located
  uint32_t line = 0;
  std::string code;
  Severity severity = Severity::Error;  // error[CODE], warning[CODE] or note[CODE]
  std::string text;                     // a substring of the message
  std::string spelled;                  // the line as written in expected.txt
  int source_line = 0;                  // its line number in expected.txt
};

struct Expectations {
  enum class Validation { Unstated, Clean, Refused } validation = Validation::Unstated;
  std::vector<ExpectedDiagnostic> diagnostics;
  std::vector<std::string> errors;  // problems in expected.txt itself
};

// Parses an expected.txt (its text), resolving files and {{TEXT}} locators
// against `case_dir`.
Expectations parse_expectations(const std::string& text, const std::filesystem::path& case_dir);

struct CaseResult {
  bool ok = false;
  std::string report;  // what matched, what is missing, what was unexpected
};

// Loads case_dir/app.json (iri-map paths resolve against `source_dir`),
// validates it with the app's shapes, lowers it with ir::lower and compares
// the diagnostics with `expected_text` (the case's expected.txt when empty).
CaseResult check_case(const std::filesystem::path& source_dir,
                      const std::filesystem::path& case_dir, std::string expected_text = {});

// The case directories under `cases_dir` (those holding an expected.txt), sorted.
std::vector<std::filesystem::path> list_cases(const std::filesystem::path& cases_dir);

}  // namespace mospec::test
