// The diagnostic-case runner (diagnostic_cases.hpp) checked against itself:
// a wrong expectation of any kind fails a case, and every code lowering can
// report has at least one case under tests/ir/diagnostics/ (the catalogue's
// lowering codes, src/support/diagnostic_codes.hpp).
#include "diagnostic_cases.hpp"

#include <gtest/gtest.h>

#include "ir/controllers.hpp"
#include "support/io.hpp"

namespace fs = std::filesystem;
using mospec::test::check_case;

namespace {

const fs::path kSource = MOSPEC_SOURCE_DIR;
const fs::path kCases = kSource / "tests/ir/diagnostics";
// The case the self-tests mutate: ComposePose without `in2`, one diagnostic
// on the line `"@id": "compose"` (line 26 of its model.json).
const fs::path kCase = kCases / "missing-property-operator";
const std::string kGood =
    "validation: refused\n"
    "model.json:{{\"@id\": \"compose\"}}: error[missing-property]: names no `in2`\n";

std::string run(const std::string& expected) {
  const auto r = check_case(kSource, kCase, expected);
  return (r.ok ? "ok\n" : "FAILED\n") + r.report;
}

TEST(DiagnosticCases, TheSelfTestCaseMatchesAsWritten) {
  EXPECT_EQ(run(kGood).substr(0, 3), "ok\n") << run(kGood);
  EXPECT_EQ(run("validation: refused\n"
                "model.json:26: error[missing-property]: names no `in2`\n")
                .substr(0, 3),
            "ok\n");
}

TEST(DiagnosticCases, AWrongLineFails) {
  const std::string r =
      run("validation: refused\n"
          "model.json:{{\"@id\": \"pose-c-a\"}}: error[missing-property]: names no `in2`\n");
  EXPECT_NE(r.find("FAILED"), std::string::npos) << r;
  EXPECT_NE(r.find("MISSING     model.json:23: error[missing-property]"), std::string::npos) << r;
  EXPECT_NE(r.find("UNEXPECTED  model.json:26: error[missing-property]: the ComposePose"),
            std::string::npos)
      << r;
}

TEST(DiagnosticCases, AWrongFileFails) {
  const std::string r =
      run("validation: refused\napp.json:26: error[missing-property]: names no `in2`\n");
  EXPECT_NE(r.find("MISSING     app.json:26"), std::string::npos) << r;
}

TEST(DiagnosticCases, AWrongCodeFails) {
  const std::string r =
      run("validation: refused\nmodel.json:26: error[type-mismatch]: names no `in2`\n");
  EXPECT_NE(r.find("MISSING     model.json:26: error[type-mismatch]"), std::string::npos) << r;
  EXPECT_NE(r.find("UNEXPECTED  model.json:26: error[missing-property]"), std::string::npos) << r;
}

TEST(DiagnosticCases, AWrongMessageFails) {
  const std::string r =
      run("validation: refused\nmodel.json:26: error[missing-property]: names no `in3`\n");
  EXPECT_NE(r.find("MISSING"), std::string::npos) << r;
  EXPECT_NE(r.find("UNEXPECTED"), std::string::npos) << r;
}

TEST(DiagnosticCases, ACaretAnchorsTheMessageAtItsBeginning) {
  EXPECT_EQ(run("validation: refused\nmodel.json:26: error[missing-property]: ^the ComposePose\n")
                .substr(0, 3),
            "ok\n");
  const std::string r =
      run("validation: refused\nmodel.json:26: error[missing-property]: ^names no `in2`\n");
  EXPECT_NE(r.find("MISSING     model.json:26: error[missing-property]: ...^names no `in2`..."),
            std::string::npos)
      << r;
}

TEST(DiagnosticCases, ALooseExpectationDoesNotTakeAStricterOnesDiagnostic) {
  // Two diagnostics on one line; the first expectation fits both, the second
  // only one of them: the matching must still pair them up.
  const fs::path c = kCases / "missing-property-solver";
  const auto r =
      check_case(kSource, c,
                 "validation: refused\n"
                 "model.json:{{\"@id\": \"solver\"}}: error[missing-property]: names no\n"
                 "model.json:{{\"@id\": \"solver\"}}: error[missing-property]: names no gravity\n");
  EXPECT_TRUE(r.ok) << r.report;
}

TEST(DiagnosticCases, AnUnlocatedExpectationDoesNotMatchALocatedDiagnostic) {
  const std::string r = run("validation: refused\n-: error[missing-property]: names no `in2`\n");
  EXPECT_NE(r.find("MISSING     -: error[missing-property]"), std::string::npos) << r;
}

TEST(DiagnosticCases, AMissingDiagnosticFails) {
  const std::string r = run(kGood + "model.json:26: error[missing-property]: names no `in2`\n");
  EXPECT_NE(r.find("FAILED (2 expected, 1 reported)"), std::string::npos) << r;
  EXPECT_NE(r.find("MISSING"), std::string::npos) << r;
  EXPECT_EQ(r.find("UNEXPECTED"), std::string::npos) << r;
}

TEST(DiagnosticCases, AnUnexpectedDiagnosticFails) {
  // The same model, its expectation about another line: the real one is extra.
  const std::string r =
      run("validation: refused\nmodel.json:25: error[missing-property]: names no `in2`\n");
  EXPECT_NE(r.find("UNEXPECTED  model.json:26"), std::string::npos) << r;
}

TEST(DiagnosticCases, TheValidationVerdictIsChecked) {
  const std::string r =
      run("validation: clean\nmodel.json:26: error[missing-property]: names no `in2`\n");
  EXPECT_NE(r.find("validation: expected clean, got refused"), std::string::npos) << r;
  EXPECT_NE(r.find("a pose composition has exactly one second input pose"), std::string::npos) << r;
}

TEST(DiagnosticCases, IllFormedExpectationsFail) {
  const struct {
    std::string text, message;
  } cases[] = {
      {"model.json:26: error[missing-property]: names no `in2`\n", "states no `validation"},
      {"validation: maybe\n", "is `clean` or `refused`"},
      {"validation: clean\nvalidation: clean\n", "stated twice"},
      {"validation: refused\n", "expects no diagnostic"},
      {"validation: refused\nmodel.json:{{no such text}}: error[x]: y\n",
       "no line of model.json contains {{no such text}}"},
      {"validation: refused\nmodel.json:{{\"@id\": \"frame-}}: error[x]: y\n",
       "3 lines of model.json contain"},
      {"validation: refused\nmodel.json: error[x]: y\n", "a line number or {{TEXT}}"},
      {"validation: refused\nmodel.json:26: remark[x]: y\n",
       "expected `error[CODE]: MESSAGE`, `warning[CODE]: MESSAGE` or `note[CODE]: MESSAGE`"},
      {"validation: refused\nmodel.json:26: error[x]:\n", "a code and a message substring"},
      {"validation: refused\nmodel.json:{{compose: error[x]: y\n", "ends with `}}:`"},
  };
  for (const auto& c : cases) {
    const std::string r = run(c.text);
    EXPECT_NE(r.find("FAILED\n"), std::string::npos) << c.text << r;
    EXPECT_NE(r.find("the expectations are ill-formed"), std::string::npos) << c.text << r;
    EXPECT_NE(r.find(c.message), std::string::npos) << c.text << r;
  }
}

// Every lowering code of the catalogue has a case (docs/testing.md: an
// expected message beside the offending input); the catalogue's own test
// (tests/support/diagnostic_codes_test.cpp) checks the other stages' codes, and
// that every code a case expects is in the catalogue.
TEST(DiagnosticCases, EveryLoweringCodeHasACase) {
  std::map<std::string, std::vector<std::string>> covered;
  for (const fs::path& c : mospec::test::list_cases(kCases)) {
    const auto e =
        mospec::test::parse_expectations(mospec::read_file((c / "expected.txt").string()), c);
    for (const auto& d : e.diagnostics) covered[d.code].push_back(c.filename().string());
  }
  size_t codes = 0;
  for (const mospec::CodeEntry& entry : mospec::kDiagnosticCodes) {
    // What every case's lowering throws (the runner checks it), not a finding.
    if (entry.stage != "lowering" || entry.code == "lowering-failed") continue;
    ++codes;
    EXPECT_TRUE(covered.count(std::string(entry.code)))
        << "lowering reports [" << entry.code << "], but no case under "
        << "tests/ir/diagnostics/ expects it; add one (docs/testing.md)";
  }
  EXPECT_GE(codes, 60u) << "the catalogue lists too few lowering codes";
  // The controller registry's refusals are lowering's codes too.
  for (const mospec::ir::ControllerKind& k : mospec::ir::controller_kinds()) {
    for (const mospec::ir::RefusedProperty& r : k.refused) {
      const mospec::CodeEntry* entry = mospec::DiagnosticCode::find(r.code);
      ASSERT_NE(entry, nullptr) << r.code << " is not in the catalogue";
      EXPECT_EQ(entry->stage, "lowering") << r.code;
    }
  }
}

}  // namespace
