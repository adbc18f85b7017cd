// Names for the individual readings of a MeasuredState, so that faults,
// logs and messages can address "left_arm.qd[3]" or "pivot_q[2]".
//
// Names follow the struct fields, 0-based, with each arm named by its
// RobotShape name:
//   <arm>_arm.q[i], <arm>_arm.qd[i], <arm>_arm.tau[i]   i = 0 .. joints-1
//   pivot_q[i]                                          i = 0 .. drives-1
//   wheel_qd[i]                                         i = 0 .. 2 drives-1
// e.g. right_arm.q[0] .. right_arm.tau[6] on mospec's default robot. Ground
// truth is not a sensor and has no name.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "robot/interface.hpp"

namespace mospec::robot {

// A reading: which field and, for an arm's, which arm and joint.
struct SensorId {
  enum class Field : std::uint8_t { ArmQ, ArmQd, ArmTau, PivotQ, WheelQd };
  Field field = Field::ArmQ;
  std::uint16_t arm = 0;    // ArmQ, ArmQd, ArmTau: the arm's index in the shape
  std::uint16_t index = 0;  // the joint, pivot or wheel
  friend bool operator==(SensorId, SensorId) = default;
};

// Every reading of a robot of `shape`, in the order listed above.
std::vector<SensorId> all_sensors(const RobotShape& shape);

// The reading's name, e.g. "left_arm.tau[6]".
std::string sensor_name(const RobotShape& shape, SensorId id);

// The id of `name`, or nothing when the robot has no reading of that name.
std::optional<SensorId> find_sensor(const RobotShape& shape, std::string_view name);

// Like find_sensor, but throws mospec::Error("unknown-sensor") whose message
// names `name` and gives the robot's accepted forms.
SensorId sensor(const RobotShape& shape, std::string_view name);

// The reading itself (a reference into `state`, which is made for the shape
// the id was found in).
double& sensor_value(MeasuredState& state, SensorId id) noexcept;

}  // namespace mospec::robot
