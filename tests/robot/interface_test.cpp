// The robot interface: sensor names, fault injection and the actuation limits,
// without a simulator.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <span>

#include "robot/faults.hpp"
#include "robot/limits.hpp"
#include "robot/sensors.hpp"
#include "support/diagnostics.hpp"

namespace mospec::robot {
namespace {

// mospec's default robot: two 7-joint arms, four drives.
const RobotShape kPair{{{"right", 7}, {"left", 7}}, 4};
constexpr size_t kDrives = 4, kWheels = 8;

TEST(Sensors, EveryNameRoundTrips) {
  const std::vector<SensorId> all = all_sensors(kPair);
  EXPECT_EQ(all.size(), 2u * 3 * 7 + kDrives + kWheels);
  for (const SensorId id : all) {
    const std::string name = sensor_name(kPair, id);
    auto found = find_sensor(kPair, name);
    ASSERT_TRUE(found.has_value()) << name;
    EXPECT_EQ(*found, id) << name;
  }
  EXPECT_EQ(sensor_name(kPair, sensor(kPair, "right_arm.q[0]")), "right_arm.q[0]");
  EXPECT_EQ(sensor_name(kPair, sensor(kPair, "left_arm.tau[6]")), "left_arm.tau[6]");
  EXPECT_EQ(sensor_name(kPair, sensor(kPair, "wheel_qd[7]")), "wheel_qd[7]");
}

TEST(Sensors, AnyArmsAndJointCounts) {
  const RobotShape shape{{{"ur", 6}, {"gantry", 3}, {"left", 7}}, 4};
  EXPECT_EQ(all_sensors(shape).size(), 3u * (6 + 3 + 7) + kDrives + kWheels);
  EXPECT_TRUE(find_sensor(shape, "ur_arm.tau[5]").has_value());
  EXPECT_FALSE(find_sensor(shape, "ur_arm.tau[6]").has_value());
  EXPECT_TRUE(find_sensor(shape, "gantry_arm.qd[2]").has_value());
  EXPECT_FALSE(find_sensor(shape, "right_arm.q[0]").has_value());
  MeasuredState s = make_state(shape);
  ASSERT_EQ(s.arm.size(), 3u);
  EXPECT_EQ(s.arm[1].q.size(), 3u);
  sensor_value(s, sensor(shape, "gantry_arm.qd[2]")) = 4.5;
  EXPECT_EQ(s.arm[1].qd[2], 4.5);
  const Command c = make_command(shape);
  ASSERT_EQ(c.arm_tau.size(), 3u);
  EXPECT_EQ(c.arm_tau[0].size(), 6u);
  try {
    sensor(shape, "right_arm.q[0]");
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), "unknown-sensor");
    EXPECT_STREQ(e.what(),
                 "mospec: error: no sensor named 'right_arm.q[0]'; sensors are "
                 "ur_arm.{q,qd,tau}[0..5], gantry_arm.{q,qd,tau}[0..2], left_arm.{q,qd,tau}[0..6], "
                 "pivot_q[0..3], wheel_qd[0..7]");
  }
}

TEST(Sensors, ValuesAreTheStructFields) {
  MeasuredState s = make_state(kPair);
  sensor_value(s, sensor(kPair, "left_arm.qd[3]")) = 1.5;
  sensor_value(s, sensor(kPair, "pivot_q[2]")) = 2.5;
  sensor_value(s, sensor(kPair, "wheel_qd[5]")) = 3.5;
  EXPECT_EQ(s.arm[kLeftArm].qd[3], 1.5);
  EXPECT_EQ(s.pivot_q[2], 2.5);
  EXPECT_EQ(s.wheel_qd[5], 3.5);
}

TEST(Sensors, BadNamesAreRejectedWithTheForms) {
  for (const char* bad : {"", "right_arm", "right_arm.q[7]", "right_arm.q[-1]", "left_arm.x[0]",
                          "pivot_q[4]", "pivot_q[1", "wheel_qd[08x]", "middle_arm.q[0]"}) {
    EXPECT_FALSE(find_sensor(kPair, bad).has_value()) << bad;
  }
  try {
    sensor(kPair, "pivot_q[4]");
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(),
                 "mospec: error: no sensor named 'pivot_q[4]'; sensors are "
                 "right_arm.{q,qd,tau}[0..6], left_arm.{q,qd,tau}[0..6], pivot_q[0..3], "
                 "wheel_qd[0..7]");
  }
}

MeasuredState sample(std::uint64_t tick, double value) {
  MeasuredState s = make_state(kPair);
  s.clock.tick = tick;
  std::fill(s.arm[kRightArm].q.begin(), s.arm[kRightArm].q.end(), value);
  std::fill(s.pivot_q.begin(), s.pivot_q.end(), value);
  return s;
}

TEST(Faults, NanForASpanOfTicks) {
  FaultInjector f(kPair);
  f.inject_nan("right_arm.q[2]", 3, 2);
  for (std::uint64_t t = 0; t < 7; ++t) {
    MeasuredState s = sample(t, 1.0 + static_cast<double>(t));
    f.corrupt(s);
    EXPECT_EQ(std::isnan(s.arm[kRightArm].q[2]), t == 3 || t == 4) << t;
    EXPECT_EQ(s.arm[kRightArm].q[1], 1.0 + static_cast<double>(t));  // others untouched
  }
}

TEST(Faults, StaleHoldsTheLastGoodValue) {
  FaultInjector f;
  f.inject_stale("pivot_q[1]", 2);  // until cleared
  for (std::uint64_t t = 0; t < 6; ++t) {
    MeasuredState s = sample(t, static_cast<double>(t));
    f.corrupt(s);
    EXPECT_EQ(s.pivot_q[1], t < 2 ? static_cast<double>(t) : 1.0) << t;
    EXPECT_EQ(s.pivot_q[0], static_cast<double>(t));
  }
  f.clear();
  MeasuredState s = sample(6, 6.0);
  f.corrupt(s);
  EXPECT_EQ(s.pivot_q[1], 6.0);
}

TEST(Faults, StaleInjectedLateFreezesItsFirstSample) {
  FaultInjector f;
  f.inject_stale("pivot_q[0]", 0, 3);
  for (std::uint64_t t = 10; t < 14; ++t) {
    MeasuredState s = sample(t, static_cast<double>(t));
    f.corrupt(s);
    EXPECT_EQ(s.pivot_q[0], static_cast<double>(t));  // span 0..2 is over
  }
  FaultInjector g;
  g.inject_stale("pivot_q[0]", 10, 2);
  for (std::uint64_t t = 10; t < 13; ++t) {
    MeasuredState s = sample(t, static_cast<double>(t));
    g.corrupt(s);
    EXPECT_EQ(s.pivot_q[0], t < 12 ? 10.0 : 12.0) << t;
  }
}

TEST(Faults, DroppedCommands) {
  FaultInjector f;
  f.drop_commands(5, 2);
  for (std::uint64_t t = 0; t < 9; ++t) EXPECT_EQ(f.drops(t), t == 5 || t == 6) << t;
}

TEST(Faults, CapacityAndNamesAreChecked) {
  FaultInjector f(kPair);
  EXPECT_THROW(f.inject_nan("nope", 0), Error);
  for (int i = 0; i < FaultInjector::kCapacity; ++i) f.drop_commands(0);
  try {
    f.drop_commands(0);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), "too-many-faults");
  }
}

CommandLimits test_limits() {
  CommandLimits l;
  l.arm_names = {"right", "left"};
  l.arm_effort = {JointValues{39, 39, 39, 39, 9, 9, 9}, JointValues{39, 39, 39, 39, 9, 9, 9}};
  l.wheel_torque.assign(kWheels, 10.0);
  l.platform_force = 100.0;
  l.platform_moment = 20.0;
  return l;
}

// A stand-in for the robot's drive geometry: f_x is the sum of the hub
// torques, f_y zero, m_z the sum of wheel i's torque times i.
PlatformWrench toy_wrench(std::span<const double> tau) noexcept {
  PlatformWrench F{0, 0, 0};
  for (size_t w = 0; w < tau.size(); ++w) {
    F[0] += tau[w];
    F[2] += static_cast<double>(w) * tau[w];
  }
  return F;
}

TEST(Limits, JointAndHubTorquesSaturatePerActuatorAndAreCounted) {
  CommandLimiter limiter(test_limits());
  Command c = make_command(kPair);
  c.arm_tau[kRightArm][0] = 1e300;
  c.arm_tau[kLeftArm][6] = -12.0;
  c.arm_tau[kLeftArm][5] = 9.0;  // at the limit: not clamped
  c.wheel_tau[1] = -15.0;        // platform: 15 N, 15 N·m, within the limits
  limiter.clamp(c, 7, toy_wrench);
  EXPECT_EQ(c.arm_tau[kRightArm][0], 39.0);
  EXPECT_EQ(c.arm_tau[kLeftArm][6], -9.0);
  EXPECT_EQ(c.arm_tau[kLeftArm][5], 9.0);
  EXPECT_EQ(c.wheel_tau[1], -10.0);
  c.arm_tau[kRightArm][0] = 50.0;
  limiter.clamp(c, 8, toy_wrench);
  const auto r = limiter.records();
  EXPECT_EQ(r[0].ticks, 2u);
  EXPECT_EQ(r[0].first_tick, 7u);
  EXPECT_EQ(r[0].max_requested, 1e300);
  EXPECT_EQ(r[0].limit, 39.0);
  EXPECT_EQ(r[7 + 6].ticks, 1u);
  EXPECT_EQ(r[7 + 6].max_requested, 12.0);
  EXPECT_EQ(r[7 + 5].ticks, 0u);
  EXPECT_EQ(r[14 + 1].ticks, 1u);
  EXPECT_EQ(r[14 + 1].quantity, "wheel_tau[1]");
  EXPECT_EQ(r[static_cast<size_t>(limiter.platform_moment_index())].ticks, 0u);
  EXPECT_TRUE(limiter.any());
  EXPECT_EQ(describe_clamps(r),
            "right_arm.tau[0]: clamped in 2 ticks from tick 7, requested up to 1e+300 N·m, "
            "limit 39 N·m\n"
            "left_arm.tau[6]: clamped in 1 tick from tick 7, requested up to 12 N·m, limit 9 N·m\n"
            "wheel_tau[1]: clamped in 1 tick from tick 7, requested up to 15 N·m, limit 10 N·m\n");
  limiter.reset();
  EXPECT_FALSE(limiter.any());
  EXPECT_EQ(describe_clamps(limiter.records()), "");
}

TEST(Limits, ThePlatformWrenchIsScaledAlongItsDirection) {
  CommandLimits l = test_limits();
  l.platform_force = 50.0;
  CommandLimiter limiter(l);
  Command c = make_command(kPair);
  // Every hub within its limit, together 8 x 10 = 80 N > 50 N.
  std::fill(c.wheel_tau.begin(), c.wheel_tau.end(), 10.0);
  limiter.clamp(c, 3, toy_wrench);
  // The moment (0+1+...+7) x 10 = 280 N·m > 20 N·m is the tighter bound.
  const double scale = 20.0 / 280.0;
  for (double t : c.wheel_tau) EXPECT_DOUBLE_EQ(t, 10.0 * scale);
  const auto r = limiter.records();
  const auto force = static_cast<size_t>(limiter.platform_force_index());
  const auto moment = static_cast<size_t>(limiter.platform_moment_index());
  EXPECT_EQ(r[force].ticks, 1u);
  EXPECT_EQ(r[force].max_requested, 80.0);
  EXPECT_EQ(r[moment].ticks, 1u);
  EXPECT_EQ(r[moment].first_tick, 3u);
  for (size_t w = 0; w < kWheels; ++w) EXPECT_EQ(r[14 + w].ticks, 0u) << w;
  EXPECT_EQ(r[force].quantity, "platform.force");
  EXPECT_EQ(r[force].unit, std::string("N"));
  // A huge requested force (4e10 N through the hubs) is reported as requested.
  std::fill(c.wheel_tau.begin(), c.wheel_tau.end(), 0.0);
  c.wheel_tau[0] = 4e10;
  limiter.clamp(c, 4, toy_wrench);
  EXPECT_EQ(limiter.records()[force].max_requested, 4e10);
  EXPECT_LE(std::abs(toy_wrench(c.wheel_tau)[0]), 50.0 + 1e-9);
}

TEST(Limits, WithinTheLimitsNothingChanges) {
  CommandLimiter limiter(test_limits());
  Command c = make_command(kPair);
  c.arm_tau[kRightArm] = {38.9, -39, 1, 2, 8.9, -9, 0};
  c.wheel_tau = {1, -1, 2, -2, 0.5, 0.5, 0, 0};
  const Command before = c;
  limiter.clamp(c, 0, toy_wrench);
  EXPECT_EQ(c.arm_tau, before.arm_tau);
  EXPECT_EQ(c.wheel_tau, before.wheel_tau);
  EXPECT_FALSE(limiter.any());
}

TEST(Limits, LimitsMustBeFinitePositive) {
  CommandLimits l = test_limits();
  l.wheel_torque[5] = 0.0;
  try {
    CommandLimiter limiter(l);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), "invalid-limits");
    EXPECT_NE(std::string(e.what()).find("wheel_tau[5]"), std::string::npos) << e.what();
  }
  l = test_limits();
  l.platform_moment = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(CommandLimiter{l}, Error);
}

TEST(Limits, APrismaticJointIsLimitedInNewtons) {
  CommandLimits l = test_limits();
  l.arm_names = {"gantry"};
  l.arm_effort = {JointValues{200, 5}};
  l.arm_prismatic = {{true, false}};
  CommandLimiter limiter(l);
  Command c = make_command(RobotShape{{{"gantry", 2}}});
  c.arm_tau[0] = {-300, 6};
  limiter.clamp(c, 1, toy_wrench);
  EXPECT_EQ(c.arm_tau[0], (JointValues{-200, 5}));
  EXPECT_EQ(describe_clamps(limiter.records()),
            "gantry_arm.tau[0]: clamped in 1 tick from tick 1, requested up to 300 N, limit 200 N\n"
            "gantry_arm.tau[1]: clamped in 1 tick from tick 1, requested up to 6 N·m, limit 5 "
            "N·m\n");
}

}  // namespace
}  // namespace mospec::robot
