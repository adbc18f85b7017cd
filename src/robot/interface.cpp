#include "robot/interface.hpp"

#include <algorithm>

#include "robot/controller.hpp"

namespace mospec::robot {

MeasuredState make_state(const RobotShape& shape) {
  MeasuredState s;
  s.arm.resize(shape.arms.size());
  for (std::size_t k = 0; k < shape.arms.size(); ++k) {
    const auto n = static_cast<std::size_t>(shape.arms[k].joints);
    s.arm[k].q.assign(n, 0.0);
    s.arm[k].qd.assign(n, 0.0);
    s.arm[k].tau.assign(n, 0.0);
  }
  s.pivot_q.assign(static_cast<std::size_t>(shape.drives), 0.0);
  s.wheel_qd.assign(static_cast<std::size_t>(2 * shape.drives), 0.0);
  return s;
}

Command make_command(const RobotShape& shape) {
  Command c;
  c.arm_tau.resize(shape.arms.size());
  for (std::size_t k = 0; k < shape.arms.size(); ++k) {
    c.arm_tau[k].assign(static_cast<std::size_t>(shape.arms[k].joints), 0.0);
  }
  c.wheel_tau.assign(static_cast<std::size_t>(2 * shape.drives), 0.0);
  return c;
}

void zero(Command& command) noexcept {
  command.tick = 0;
  for (JointValues& arm : command.arm_tau) std::fill(arm.begin(), arm.end(), 0.0);
  std::fill(command.wheel_tau.begin(), command.wheel_tau.end(), 0.0);
}

std::string check_fits(const Controller& controller, const RobotShape& shape) {
  const std::span<const int> joints = controller.arm_joints();
  for (size_t k = 0; k < joints.size(); ++k) {
    if (joints[k] == 0) continue;
    if (k >= shape.arms.size()) {
      return "the controller drives arm " + std::to_string(k) + " (" + std::to_string(joints[k]) +
             " joints), but the robot has " + std::to_string(shape.arms.size()) + " arm(s)";
    }
    if (shape.arms[k].joints != joints[k]) {
      return "the controller drives arm " + std::to_string(k) + " ('" + shape.arms[k].name +
             "') with " + std::to_string(joints[k]) + " joints, but that arm has " +
             std::to_string(shape.arms[k].joints);
    }
  }
  return {};
}

RobotShape gen3_pair_shape() {
  return RobotShape{{{"right", 7}, {"left", 7}}};
}

}  // namespace mospec::robot
