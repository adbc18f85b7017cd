// sim::run refuses, before the first tick, a controller made for another robot
// and run options that name arms the world does not have.
#include "sim/run.hpp"

#include <gtest/gtest.h>

#include <array>

#include "sim_test_util.hpp"

namespace mospec::sim {
namespace {

// A controller that does nothing, for arms of the given joint counts.
class IdleController final : public robot::Controller {
 public:
  explicit IdleController(std::array<int, 2> joints) : joints_(joints) {}
  const char* app() const noexcept override { return "idle"; }
  void tick(const robot::MeasuredState&, robot::Command&) noexcept override {}
  std::span<const int> arm_joints() const noexcept override { return joints_; }
  std::span<const robot::LogColumnInfo> log_columns() const noexcept override { return {}; }
  void log_values(std::span<double>) const noexcept override {}

 private:
  std::array<int, 2> joints_;
};

TEST(Run, AControllerForAnotherRobotIsRefused) {
  NEED_GEN3();
  World world(testing::test_world(), arm_chain);
  IdleController three_joints({3, 0});
  RunOptions options;
  options.duration = 0.01;
  try {
    run(world, three_joints, options);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), "robot-mismatch");
    EXPECT_NE(std::string(e.what()).find("with 3 joints, but that arm has 7; the controller was "
                                         "made for another robot"),
              std::string::npos)
        << e.what();
  }
}

TEST(Run, OptionsForMoreArmsThanTheWorldHasAreRefused) {
  NEED_GEN3();
  World world(testing::test_world(), arm_chain);
  IdleController right_arm({7, 0});
  RunOptions options;
  options.duration = 0.01;
  options.pushing = {{}, {}, {}};  // three arms; the world has two
  try {
    run(world, right_arm, options);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), "invalid-run-options");
    EXPECT_STREQ(e.what(), "mospec: error: the run options name more arms than the world has");
  }
}

}  // namespace
}  // namespace mospec::sim
