// A built controller's tick allocates nothing: 10 000 ticks (and log reads,
// and the robot interface's clamp) of each dlopened generated library under
// the counting allocator. Run by
// build_test.sh; its own executable because it replaces the global allocator.
#include <gtest/gtest.h>

#include <vector>

#include "codegen/build.hpp"
#include "load_controller.hpp"
#include "programs.hpp"
#include "robot/limits.hpp"
// Defines the replacement allocator: this translation unit only, and last.
#include "alloc_counter.hpp"  // NOLINT(llvm-include-order)

namespace mospec::codegen {
namespace {

void expect_no_allocation(const char* env) {
#ifdef MOSPEC_NO_ALLOC_COUNTING
  GTEST_SKIP() << "allocation counting is off under AddressSanitizer";
#endif
  const std::string path = testing::library_from_env(env);
  if (path.empty()) GTEST_SKIP() << env << " is not set (run by build_test.sh)";
  const std::unique_ptr<robot::Controller> generated = load_controller(path);
  robot::Controller& c = *generated;
  std::vector<double> values(c.log_columns().size());
  std::vector<robot::MeasuredState> states;
  for (std::uint64_t k = 0; k < 1000; ++k) states.push_back(testing::measurement(k));
  robot::Command command = robot::make_command(robot::gen3_pair_shape());
  // The robot interface's clamp after each tick (Gen3 and KELO hub limits;
  // the platform wrench here a plain sum of the hub torques).
  robot::CommandLimits limits;
  limits.arm_names = {"right", "left"};
  limits.arm_effort.assign(2, {39, 39, 39, 39, 9, 9, 9});
  limits.wheel_torque.assign(8, 10.0);
  limits.platform_force = 1000.0;
  limits.platform_moment = 300.0;
  robot::CommandLimiter limiter(limits);
  const auto wrench = [](std::span<const double> tau) noexcept {
    robot::PlatformWrench F{0, 0, 0};
    for (double t : tau) F[0] += t;
    return F;
  };
  double sum = 0.0;
  const long n = alloc_counter::during([&] {
    for (int k = 0; k < 10000; ++k) {
      c.tick(states[static_cast<std::size_t>(k % 1000)], command);
      c.log_values(values);
      if (k % 100 < 10) command.arm_tau[0][0] = 1e300;  // beyond the limit
      limiter.clamp(command, static_cast<std::uint64_t>(k), wrench);
      sum += values.empty() ? 0.0 : values[0];
    }
  });
  EXPECT_EQ(n, 0) << "allocations in 10 000 ticks";
  EXPECT_TRUE(limiter.any()) << "the clamp was exercised";
  EXPECT_TRUE(sum == sum);
}

TEST(GeneratedControllerAllocation, SmallProgramTicksWithoutAllocating) {
  expect_no_allocation("MOSPEC_SMALL_CONTROLLER");
}

TEST(GeneratedControllerAllocation, EveryOperatorKindTicksWithoutAllocating) {
  expect_no_allocation("MOSPEC_OPERATORS_CONTROLLER");
}

TEST(GeneratedControllerAllocation, ArmProgramTicksWithoutAllocating) {
  expect_no_allocation("MOSPEC_ARM_CONTROLLER");
}

TEST(GeneratedControllerAllocation, ScenarioTicksWithoutAllocating) {
  expect_no_allocation("MOSPEC_SCENARIO_CONTROLLER");
}

}  // namespace
}  // namespace mospec::codegen
