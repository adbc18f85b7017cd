// The built controllers (run by build_test.sh after `mospec build`): they load,
// expose the program's log columns, and tick for tick give bit-identical log
// values and commands to the IR interpreter on the same program and the same
// measurements.
#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "codegen/build.hpp"
#include "ir/interpreter.hpp"
#include "load_controller.hpp"
#include "programs.hpp"

namespace mospec::codegen {
namespace {

bool same_bits(const void* a, const void* b, std::size_t n) {
  return std::memcmp(a, b, n) == 0;
}

void expect_like_the_interpreter(const char* env, ir::Program (*make)(SourceFiles&), int ticks) {
  const std::string path = testing::library_from_env(env);
  if (path.empty()) GTEST_SKIP() << env << " is not set (run by build_test.sh)";
  const std::unique_ptr<robot::Controller> generated = load_controller(path);
  robot::Controller& gen = *generated;
  SourceFiles files;
  ir::Interpreter interp(make(files));
  const ir::Program& program = interp.program();

  EXPECT_STREQ(gen.app(), interp.app());
  const auto columns = gen.log_columns();
  ASSERT_EQ(columns.size(), program.log.size());
  for (std::size_t i = 0; i < columns.size(); ++i) {
    EXPECT_STREQ(columns[i].name, program.log[i].name.c_str());
    EXPECT_STREQ(columns[i].unit, program.log[i].unit.c_str());
    EXPECT_STREQ(columns[i].name, interp.log_columns()[i].name);
  }

  std::vector<double> a(columns.size()), b(columns.size());
  std::vector<double> first_gen, last_gen;
  for (int k = 0; k < ticks; ++k) {
    const robot::MeasuredState state = testing::measurement(static_cast<std::uint64_t>(k));
    robot::Command ca, cb;
    ca.arm_tau[0][0] = 99.0;  // stale contents must be overwritten
    cb.arm_tau[0][0] = -99.0;
    interp.tick(state, ca);
    gen.tick(state, cb);
    interp.log_values(a);
    gen.log_values(b);
    for (std::size_t i = 0; i < a.size(); ++i) {
      ASSERT_TRUE(same_bits(&a[i], &b[i], sizeof(double)))
          << "tick " << k << ", column " << columns[i].name << ": interpreter " << a[i]
          << ", generated " << b[i];
    }
    ASSERT_EQ(ca.tick, cb.tick);
    ASSERT_TRUE(same_bits(ca.arm_tau.data(), cb.arm_tau.data(), sizeof ca.arm_tau)) << "tick " << k;
    ASSERT_TRUE(same_bits(ca.wheel_tau.data(), cb.wheel_tau.data(), sizeof ca.wheel_tau))
        << "tick " << k;
    if (k == 0) first_gen = b;
    last_gen = b;
  }
  EXPECT_NE(first_gen, last_gen) << "the test signals should change the logged values";
}

TEST(GeneratedController, SmallProgramMatchesTheInterpreterBitForBit) {
  expect_like_the_interpreter("MOSPEC_SMALL_CONTROLLER", &testing::small_program, 2000);
}

TEST(GeneratedController, ArmProgramMatchesTheInterpreterBitForBit) {
  expect_like_the_interpreter("MOSPEC_ARM_CONTROLLER", &testing::arm_program, 2000);
}

// The columns a reader of the log sees, by name and unit.
TEST(GeneratedController, LogColumnsAreTheProgramsNamedColumns) {
  const std::string path = testing::library_from_env("MOSPEC_SMALL_CONTROLLER");
  if (path.empty()) GTEST_SKIP() << "MOSPEC_SMALL_CONTROLLER is not set (run by build_test.sh)";
  const std::unique_ptr<robot::Controller> generated = load_controller(path);
  const auto columns = generated->log_columns();
  ASSERT_EQ(columns.size(), 21u);
  EXPECT_STREQ(columns[0].name, "time");
  EXPECT_STREQ(columns[0].unit, "SEC");
  EXPECT_STREQ(columns[17].name, "push_ok");
  EXPECT_STREQ(columns[17].unit, "");
  EXPECT_STREQ(columns[18].name, "F_P.f_x");
  EXPECT_STREQ(columns[18].unit, "N");
  // Flags and events log as exactly 0 or 1.
  std::vector<double> v(columns.size());
  for (std::uint64_t k = 0; k < 100; ++k) {
    robot::Command c;
    generated->tick(testing::measurement(k), c);
    generated->log_values(v);
    for (std::size_t i = 12; i < 18; ++i) EXPECT_TRUE(v[i] == 0.0 || v[i] == 1.0) << columns[i].name;
  }
}

}  // namespace
}  // namespace mospec::codegen

namespace mospec::codegen {
namespace {

TEST(LoadController, NamesTheLibraryAndTheReason) {
  try {
    load_controller("/nonexistent/libmospec_controller.so");
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), "load");
    EXPECT_NE(std::string(e.what()).find("cannot load controller '/nonexistent/libmospec_controller.so'"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace mospec::codegen
