#include "sim/drivers.hpp"

#include <cmath>
#include <string>

#include "runtime/kinematics.hpp"
#include "runtime/rne.hpp"
#include "support/diagnostics.hpp"

namespace mospec::sim {
namespace {

constexpr double kGravity = 9.81;

runtime::AchdModel gravity_model(const runtime::Chain& arm, const runtime::Pose& X_PB) {
  return runtime::AchdModel(arm, X_PB.R.transpose() * runtime::Vec3(0, 0, -kGravity));
}

}  // namespace

GravityCompensation::GravityCompensation(const runtime::Chain& arm,
                                         const std::array<runtime::Pose, robot::kArms>& X_PB)
    : X_PB_(X_PB),
      models_{gravity_model(arm, X_PB[0]), gravity_model(arm, X_PB[1])},
      data_{runtime::AchdData(models_[0]), runtime::AchdData(models_[1])} {
  if (arm.size() != robot::kArmJoints) {
    throw Error("invalid-world", "gravity compensation: the arm chain has " +
                                     std::to_string(arm.size()) + " joints; the robot has " +
                                     std::to_string(robot::kArmJoints));
  }
}

void GravityCompensation::compute(const robot::MeasuredState& state,
                                  robot::Command& command) noexcept {
  command.tick = state.clock.tick;
  for (int k = 0; k < robot::kArms; ++k) {
    const auto ak = static_cast<size_t>(k);
    const runtime::AchdModel& model = models_[ak];
    runtime::AchdData& data = data_[ak];
    Eigen::Matrix<double, robot::kArmJoints, 1> q, zero = decltype(q)::Zero();
    bool finite = true;
    for (int i = 0; i < robot::kArmJoints; ++i) {
      q[i] = state.arm[ak].q[static_cast<size_t>(i)];
      finite = finite && std::isfinite(q[i]);
    }
    robot::ArmVector& tau = command.arm_tau[ak];
    if (!finite) {
      tau.fill(0.0);
      continue;
    }
    runtime::rne(model, data, q, zero, zero, {});
    for (int i = 0; i < robot::kArmJoints; ++i) tau[static_cast<size_t>(i)] = data.tau[i];
    if (!f_E_P[ak].isZero()) {
      runtime::tip_jacobian(model, data, q);
      const runtime::Vec3 f_B = X_PB_[ak].R.transpose() * f_E_P[ak];
      const Eigen::Matrix<double, robot::kArmJoints, 1> t =
          data.J_To_B.bottomRows<3>().transpose() * f_B;
      for (int i = 0; i < robot::kArmJoints; ++i) tau[static_cast<size_t>(i)] += t[i];
    }
  }
}

PlatformWrenchDriver::PlatformWrenchDriver(const runtime::KeloConfig& config)
    : model_(config), data_(model_) {}

void PlatformWrenchDriver::compute(const robot::MeasuredState& state,
                                   robot::Command& command) noexcept {
  command.tick = state.clock.tick;
  const Eigen::Vector4d q(state.pivot_q[0], state.pivot_q[1], state.pivot_q[2], state.pivot_q[3]);
  if (!q.allFinite() || !F_p.allFinite()) {
    command.wheel_tau.fill(0.0);
    return;
  }
  const runtime::KeloDriveVector& tau = runtime::kelo_force_step(model_, data_, q, F_p);
  for (int w = 0; w < robot::kWheels; ++w) command.wheel_tau[static_cast<size_t>(w)] = tau[w];
}

}  // namespace mospec::sim
