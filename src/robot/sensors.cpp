#include "robot/sensors.hpp"

#include <charconv>

#include "support/diagnostics.hpp"

namespace mospec::robot {
namespace {

using Field = SensorId::Field;
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

SensorId id(Field field, int arm, int index) {
  return SensorId{field, static_cast<std::uint16_t>(arm), static_cast<std::uint16_t>(index)};
}

}  // namespace

std::vector<SensorId> all_sensors(const RobotShape& shape) {
  std::vector<SensorId> out;
  for (size_t a = 0; a < shape.arms.size(); ++a) {
    for (int f = 0; f < 3; ++f) {
      for (int j = 0; j < shape.arms[a].joints; ++j) {
        out.push_back(id(static_cast<Field>(f), static_cast<int>(a), j));
      }
    }
  }
  for (int i = 0; i < shape.drives; ++i) out.push_back(id(Field::PivotQ, 0, i));
  for (int i = 0; i < 2 * shape.drives; ++i) out.push_back(id(Field::WheelQd, 0, i));
  return out;
}

std::string sensor_name(const RobotShape& shape, SensorId s) {
  switch (s.field) {
    case Field::PivotQ:
      return "pivot_q[" + std::to_string(s.index) + "]";
    case Field::WheelQd:
      return "wheel_qd[" + std::to_string(s.index) + "]";
    default:
      break;
  }
  const std::string arm =
      s.arm < shape.arms.size() ? shape.arms[s.arm].name : "arm" + std::to_string(s.arm);
  return arm + "_arm." + std::string(kArmFields[static_cast<int>(s.field)]) + "[" +
         std::to_string(s.index) + "]";
}

std::optional<SensorId> find_sensor(const RobotShape& shape, std::string_view name) {
  for (size_t arm = 0; arm < shape.arms.size(); ++arm) {
    const std::string prefix = shape.arms[arm].name + "_arm.";
    if (name.size() > prefix.size() && name.substr(0, prefix.size()) == prefix) {
      const std::string_view rest = name.substr(prefix.size());
      for (int field = 0; field < 3; ++field) {
        if (auto j = parse_indexed(rest, kArmFields[field], shape.arms[arm].joints)) {
          return id(static_cast<Field>(field), static_cast<int>(arm), *j);
        }
      }
      return {};
    }
  }
  if (auto i = parse_indexed(name, "pivot_q", shape.drives)) return id(Field::PivotQ, 0, *i);
  if (auto i = parse_indexed(name, "wheel_qd", 2 * shape.drives)) {
    return id(Field::WheelQd, 0, *i);
  }
  return {};
}

SensorId sensor(const RobotShape& shape, std::string_view name) {
  if (auto s = find_sensor(shape, name)) return *s;
  std::string forms;
  for (const ArmShape& a : shape.arms) {
    forms += a.name + "_arm.{q,qd,tau}[0.." + std::to_string(a.joints - 1) + "], ";
  }
  if (shape.drives > 0) {
    forms += "pivot_q[0.." + std::to_string(shape.drives - 1) + "], wheel_qd[0.." +
             std::to_string(2 * shape.drives - 1) + "]";
  } else if (!forms.empty()) {
    forms.resize(forms.size() - 2);
  }
  throw Error("unknown-sensor", "no sensor named '" + std::string(name) + "'; sensors are " +
                                    (forms.empty() ? std::string("none") : forms));
}

double& sensor_value(MeasuredState& state, SensorId s) noexcept {
  switch (s.field) {
    case Field::ArmQ:
      return state.arm[s.arm].q[s.index];
    case Field::ArmQd:
      return state.arm[s.arm].qd[s.index];
    case Field::ArmTau:
      return state.arm[s.arm].tau[s.index];
    case Field::PivotQ:
      return state.pivot_q[s.index];
    case Field::WheelQd:
      break;
  }
  return state.wheel_qd[s.index];
}

}  // namespace mospec::robot
