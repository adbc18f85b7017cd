// The robot interface: sensor names, fault injection and the actuation limits,
// without a simulator.
#include <gtest/gtest.h>

#include <cmath>

#include "robot/faults.hpp"
#include "robot/limits.hpp"
#include "robot/sensors.hpp"
#include "support/diagnostics.hpp"

namespace mospec::robot {
namespace {

TEST(Sensors, EveryNameRoundTrips) {
  for (int k = 0; k < kSensorCount; ++k) {
    const SensorId id{static_cast<std::uint16_t>(k)};
    const std::string name = sensor_name(id);
    auto found = find_sensor(name);
    ASSERT_TRUE(found.has_value()) << name;
    EXPECT_EQ(found->index, k) << name;
  }
  EXPECT_EQ(sensor_name(sensor("right_arm.q[0]")), "right_arm.q[0]");
  EXPECT_EQ(sensor_name(sensor("left_arm.tau[6]")), "left_arm.tau[6]");
  EXPECT_EQ(sensor_name(sensor("wheel_qd[7]")), "wheel_qd[7]");
}

TEST(Sensors, ValuesAreTheStructFields) {
  MeasuredState s;
  sensor_value(s, sensor("left_arm.qd[3]")) = 1.5;
  sensor_value(s, sensor("pivot_q[2]")) = 2.5;
  sensor_value(s, sensor("wheel_qd[5]")) = 3.5;
  EXPECT_EQ(s.arm[kLeftArm].qd[3], 1.5);
  EXPECT_EQ(s.pivot_q[2], 2.5);
  EXPECT_EQ(s.wheel_qd[5], 3.5);
}

TEST(Sensors, BadNamesAreRejectedWithTheForms) {
  for (const char* bad : {"", "right_arm", "right_arm.q[7]", "right_arm.q[-1]", "left_arm.x[0]",
                          "pivot_q[4]", "pivot_q[1", "wheel_qd[08x]", "middle_arm.q[0]"}) {
    EXPECT_FALSE(find_sensor(bad).has_value()) << bad;
  }
  try {
    sensor("pivot_q[4]");
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(),
                 "mospec: error: no sensor named 'pivot_q[4]'; sensors are "
                 "right_arm.{q,qd,tau}[0..6], left_arm.{q,qd,tau}[0..6], pivot_q[0..3], "
                 "wheel_qd[0..7]");
  }
}

MeasuredState sample(std::uint64_t tick, double value) {
  MeasuredState s;
  s.clock.tick = tick;
  s.arm[kRightArm].q.fill(value);
  s.pivot_q.fill(value);
  return s;
}

TEST(Faults, NanForASpanOfTicks) {
  FaultInjector f;
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
  FaultInjector f;
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
  l.arm_effort = {ArmVector{39, 39, 39, 39, 9, 9, 9}, ArmVector{39, 39, 39, 39, 9, 9, 9}};
  l.wheel_torque.fill(10.0);
  l.platform_force = 100.0;
  l.platform_moment = 20.0;
  return l;
}

// A stand-in for the robot's drive geometry: f_x is the sum of the hub
// torques, f_y zero, m_z the sum of wheel i's torque times i.
PlatformWrench toy_wrench(const WheelVector& tau) noexcept {
  PlatformWrench F{0, 0, 0};
  for (size_t w = 0; w < tau.size(); ++w) {
    F[0] += tau[w];
    F[2] += static_cast<double>(w) * tau[w];
  }
  return F;
}

TEST(Limits, JointAndHubTorquesSaturatePerActuatorAndAreCounted) {
  CommandLimiter limiter(test_limits());
  Command c;
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
  EXPECT_EQ(r[kArmJoints + 6].ticks, 1u);
  EXPECT_EQ(r[kArmJoints + 6].max_requested, 12.0);
  EXPECT_EQ(r[kArmJoints + 5].ticks, 0u);
  EXPECT_EQ(r[kArmTorqueLimits + 1].ticks, 1u);
  EXPECT_EQ(r[kPlatformMomentLimit].ticks, 0u);
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
  Command c;
  // Every hub within its limit, together 8 x 10 = 80 N > 50 N.
  c.wheel_tau.fill(10.0);
  limiter.clamp(c, 3, toy_wrench);
  // The moment (0+1+...+7) x 10 = 280 N·m > 20 N·m is the tighter bound.
  const double scale = 20.0 / 280.0;
  for (double t : c.wheel_tau) EXPECT_DOUBLE_EQ(t, 10.0 * scale);
  const auto r = limiter.records();
  EXPECT_EQ(r[kPlatformForceLimit].ticks, 1u);
  EXPECT_EQ(r[kPlatformForceLimit].max_requested, 80.0);
  EXPECT_EQ(r[kPlatformMomentLimit].ticks, 1u);
  EXPECT_EQ(r[kPlatformMomentLimit].first_tick, 3u);
  for (int w = 0; w < kWheels; ++w) EXPECT_EQ(r[kArmTorqueLimits + w].ticks, 0u) << w;
  EXPECT_EQ(limited_quantity_name(kPlatformForceLimit), "platform.force");
  EXPECT_EQ(limited_quantity_unit(kPlatformForceLimit), std::string("N"));
  // A huge requested force (4e10 N through the hubs) is reported as requested.
  c.wheel_tau = {};
  c.wheel_tau[0] = 4e10;
  limiter.clamp(c, 4, toy_wrench);
  EXPECT_EQ(limiter.records()[kPlatformForceLimit].max_requested, 4e10);
  EXPECT_LE(std::abs(toy_wrench(c.wheel_tau)[0]), 50.0 + 1e-9);
}

TEST(Limits, WithinTheLimitsNothingChanges) {
  CommandLimiter limiter(test_limits());
  Command c;
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

}  // namespace
}  // namespace mospec::robot
