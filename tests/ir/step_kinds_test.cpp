// The step kinds (ir.hpp: step_kinds()): each StepKind is declared once, in
// order, with a unique name and the hooks every kind needs, its roles say what
// the code that reads them expects, and the generated controller's template
// has the section codegen selects for it. Outside the registry nothing
// dispatches on a kind (the ctest step_kind_dispatch).
#include <gtest/gtest.h>

#include <charconv>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "ir/ir.hpp"
#include "source_tree.hpp"

namespace mospec::ir {
namespace {

TEST(StepKinds, EachDeclaredOnceInOrderWithAUniqueName) {
  const auto kinds = step_kinds();
  ASSERT_EQ(kinds.size(), kStepKindCount);
  std::set<std::string_view> names;
  for (size_t k = 0; k < kinds.size(); ++k) {
    EXPECT_EQ(static_cast<size_t>(kinds[k].kind), k) << kinds[k].name << " is out of order";
    EXPECT_EQ(info(kinds[k].kind).name, kinds[k].name);
    EXPECT_EQ(to_string(kinds[k].kind), kinds[k].name);
    EXPECT_TRUE(names.insert(kinds[k].name).second) << kinds[k].name << " is declared twice";
    EXPECT_FALSE(kinds[k].lowered_from.empty()) << kinds[k].name << " says nothing it lowers from";
    EXPECT_FALSE(kinds[k].summary.empty()) << kinds[k].name << " has no summary";
  }
  EXPECT_EQ(to_string(static_cast<StepKind>(kStepKindCount)), "?");
}

// Every kind is verified, interpreted and emitted through its entry: a kind
// without one of these hooks could not run (the interpreter and codegen call
// them unconditionally).
TEST(StepKinds, EachHasTheHooksEveryKindNeeds) {
  for (const StepKindInfo& k : step_kinds()) {
    EXPECT_NE(k.signature, nullptr) << k.name << " has no signature";
    EXPECT_NE(k.interpret, nullptr) << k.name << " has no interpret hook";
    EXPECT_NE(k.emit, nullptr) << k.name << " has no emit hook";
  }
}

// What the roles promise the code that reads them: the verdict and the report
// read a motion's running flag and ended event, a constraint's satisfied
// flag, a monitor's and a controller's one output; the log names them.
TEST(StepKinds, RolesKeepTheirPromises) {
  for (const StepKindInfo& k : step_kinds()) {
    switch (k.role) {
      case StepRole::Motion:
        EXPECT_EQ(k.state, StateKind::Motion) << k.name;
        EXPECT_NE(k.log, nullptr) << k.name << ": a motion's running flag is logged";
        break;
      case StepRole::Constraint:
        EXPECT_EQ(k.member, StepMember::Evaluator) << k.name;
        EXPECT_NE(k.log, nullptr) << k.name << ": a constraint's satisfaction is logged";
        break;
      case StepRole::Monitor:
        EXPECT_EQ(k.member, StepMember::MonitorTolerance) << k.name;
        EXPECT_NE(k.log, nullptr) << k.name << ": a monitor's flag or event is logged";
        break;
      case StepRole::Controller:
        EXPECT_EQ(k.member, StepMember::Controller) << k.name;
        EXPECT_NE(k.gate, nullptr) << k.name << ": a controller may be gated by its motion";
        break;
      case StepRole::Clock:
      case StepRole::Measurement:
      case StepRole::Computation:
      case StepRole::Solver:
        EXPECT_EQ(k.member, StepMember::None) << k.name;
        break;
    }
  }
  EXPECT_EQ(info(StepKind::ArmSolve).role, StepRole::Solver);
  EXPECT_EQ(info(StepKind::BaseForceDistribution).role, StepRole::Solver);
  EXPECT_EQ(info(StepKind::ReadClock).role, StepRole::Clock);
}

TEST(StepKinds, TheControllerTemplateHasASectionForEachKind) {
  const std::string tpl = mospec::test::slurp(std::filesystem::path(MOSPEC_SOURCE_DIR) /
                                              "src/codegen/templates/controller.cpp.mustache");
  ASSERT_FALSE(tpl.empty());
  for (const StepKindInfo& k : step_kinds()) {
    const std::string section = template_section(k.kind);
    EXPECT_NE(tpl.find("{{#" + section + "}}"), std::string::npos)
        << "controller.cpp.mustache has no {{#" << section << "}} section for step kind " << k.name;
  }
}

TEST(StepKinds, StateSlotsAreThoseOfStatefulKinds) {
  // Controllers keep their state per controller kind (controllers.hpp).
  EXPECT_EQ(info(StepKind::Controller).state, std::nullopt);
  EXPECT_EQ(info(StepKind::LevelMonitor).state, StateKind::Monitor);
  EXPECT_EQ(info(StepKind::EdgeMonitor).state, StateKind::Monitor);
  EXPECT_EQ(info(StepKind::GuardedMotion).state, StateKind::Motion);
  EXPECT_EQ(info(StepKind::Operator).state, std::nullopt);
}

// The default tolerances of a motion's goals (issue #33 item 1) are
// documented: docs/simulation.md's table under "Default tolerances" has one
// row per entry of default_tolerances(), with its unit and value, and no other.
TEST(DefaultTolerances, TheDocumentedTableIsTheCodes) {
  const std::string doc =
      mospec::test::slurp(std::filesystem::path(MOSPEC_SOURCE_DIR) / "docs" / "simulation.md");
  const size_t start = doc.find("*Default tolerances.*");
  ASSERT_NE(start, std::string::npos);
  const size_t end = doc.find("\n\n", doc.find("| `", start));
  const std::string table = doc.substr(start, end - start);
  size_t rows = 0;
  for (size_t at = table.find("\n| `"); at != std::string::npos; at = table.find("\n| `", at + 1))
    ++rows;
  EXPECT_EQ(rows, default_tolerances().size()) << table;
  for (const DefaultTolerance& d : default_tolerances()) {
    char number[32];
    const auto [p, ec] = std::to_chars(number, number + sizeof number, d.tolerance);
    ASSERT_EQ(ec, std::errc());
    const std::string row = "| `" + std::string(d.unit) + "` | " + std::string(number, p) + " ";
    EXPECT_NE(table.find(row), std::string::npos) << "no row '" << row << "' in\n" << table;
    EXPECT_EQ(default_tolerance(d.unit), d.tolerance);
  }
  EXPECT_EQ(default_tolerance("KiloGM"), std::nullopt);
}

}  // namespace
}  // namespace mospec::ir
