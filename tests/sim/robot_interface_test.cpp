// The robot interface: sensor names and fault injection, without a simulator.
#include <gtest/gtest.h>

#include <cmath>

#include "robot/faults.hpp"
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

}  // namespace
}  // namespace mospec::robot
