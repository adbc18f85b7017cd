#include "robot/sensors.hpp"

#include <charconv>

#include "support/diagnostics.hpp"

namespace mospec::robot {
namespace {

constexpr int kPerArm = 3 * kArmJoints;
constexpr int kPivotBase = kArms * kPerArm;
constexpr int kWheelBase = kPivotBase + kDrives;

constexpr std::string_view kArmNames[kArms] = {"right_arm", "left_arm"};
constexpr std::string_view kArmFields[3] = {"q", "qd", "tau"};

// "field[i]" -> i when the field matches and 0 <= i < n.
std::optional<int> parse_indexed(std::string_view text, std::string_view field, int n) {
  if (text.size() < field.size() + 3 || text.substr(0, field.size()) != field) return {};
  text.remove_prefix(field.size());
  if (text.front() != '[' || text.back() != ']') return {};
  text = text.substr(1, text.size() - 2);
  int i = -1;
  auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), i);
  if (ec != std::errc() || end != text.data() + text.size() || i < 0 || i >= n) return {};
  return i;
}

}  // namespace

std::string sensor_name(SensorId id) {
  const int k = id.index;
  if (k < kPivotBase) {
    const int arm = k / kPerArm, field = (k % kPerArm) / kArmJoints, joint = k % kArmJoints;
    return std::string(kArmNames[arm]) + "." + std::string(kArmFields[field]) + "[" +
           std::to_string(joint) + "]";
  }
  if (k < kWheelBase) return "pivot_q[" + std::to_string(k - kPivotBase) + "]";
  return "wheel_qd[" + std::to_string(k - kWheelBase) + "]";
}

std::optional<SensorId> find_sensor(std::string_view name) {
  auto id = [](int k) { return SensorId{static_cast<std::uint16_t>(k)}; };
  for (int arm = 0; arm < kArms; ++arm) {
    const std::string_view prefix = kArmNames[arm];
    if (name.size() > prefix.size() + 1 && name.substr(0, prefix.size()) == prefix &&
        name[prefix.size()] == '.') {
      const std::string_view rest = name.substr(prefix.size() + 1);
      for (int field = 0; field < 3; ++field) {
        if (auto j = parse_indexed(rest, kArmFields[field], kArmJoints)) {
          return id(arm * kPerArm + field * kArmJoints + *j);
        }
      }
      return {};
    }
  }
  if (auto i = parse_indexed(name, "pivot_q", kDrives)) return id(kPivotBase + *i);
  if (auto i = parse_indexed(name, "wheel_qd", kWheels)) return id(kWheelBase + *i);
  return {};
}

SensorId sensor(std::string_view name) {
  if (auto id = find_sensor(name)) return *id;
  throw Error("unknown-sensor", "no sensor named '" + std::string(name) +
                                    "'; sensors are right_arm.{q,qd,tau}[0..6], "
                                    "left_arm.{q,qd,tau}[0..6], pivot_q[0..3], wheel_qd[0..7]");
}

double& sensor_value(MeasuredState& state, SensorId id) noexcept {
  const int k = id.index;
  if (k < kPivotBase) {
    ArmMeasurement& arm = state.arm[static_cast<std::size_t>(k / kPerArm)];
    const auto joint = static_cast<std::size_t>(k % kArmJoints);
    switch ((k % kPerArm) / kArmJoints) {
      case 0:
        return arm.q[joint];
      case 1:
        return arm.qd[joint];
      default:
        return arm.tau[joint];
    }
  }
  if (k < kWheelBase) return state.pivot_q[static_cast<std::size_t>(k - kPivotBase)];
  return state.wheel_qd[static_cast<std::size_t>(k - kWheelBase)];
}

}  // namespace mospec::robot
