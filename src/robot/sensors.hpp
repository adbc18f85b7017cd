// Names for the individual readings of a MeasuredState, so that faults,
// logs and messages can address "left_arm.qd[3]" or "pivot_q[2]".
//
// Names follow the struct fields, 0-based:
//   right_arm.q[i], right_arm.qd[i], right_arm.tau[i]   i = 0..6
//   left_arm.q[i],  left_arm.qd[i],  left_arm.tau[i]
//   pivot_q[i]                                          i = 0..3
//   wheel_qd[i]                                         i = 0..7
// Ground truth is not a sensor and has no name.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "robot/interface.hpp"

namespace mospec::robot {

// A reading's index in the order listed above.
struct SensorId {
  std::uint16_t index = 0;
  friend bool operator==(SensorId, SensorId) = default;
};

inline constexpr int kSensorCount = kArms * 3 * kArmJoints + kDrives + kWheels;

// The reading's name, e.g. "left_arm.tau[6]".
std::string sensor_name(SensorId id);

// The id of `name`, or nothing when no reading has that name.
std::optional<SensorId> find_sensor(std::string_view name);

// Like find_sensor, but throws mospec::Error("unknown-sensor") whose message
// names `name` and gives the accepted forms.
SensorId sensor(std::string_view name);

// The reading itself (a reference into `state`).
double& sensor_value(MeasuredState& state, SensorId id) noexcept;

}  // namespace mospec::robot
