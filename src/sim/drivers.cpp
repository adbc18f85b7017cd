#include "sim/drivers.hpp"

#include <algorithm>
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

GravityCompensation::GravityCompensation(std::span<const runtime::Chain> arms,
                                         std::span<const runtime::Pose> X_PB) {
  if (arms.size() != X_PB.size()) {
    throw Error("invalid-world", "gravity compensation: " + std::to_string(arms.size()) +
                                     " chains for " + std::to_string(X_PB.size()) + " mounts");
  }
  X_PB_.assign(X_PB.begin(), X_PB.end());
  f_E_P.assign(arms.size(), runtime::Vec3::Zero());
  models_.reserve(arms.size());
  for (size_t k = 0; k < arms.size(); ++k) models_.push_back(gravity_model(arms[k], X_PB[k]));
  for (const runtime::AchdModel& m : models_) data_.emplace_back(m);
}

void GravityCompensation::compute(const robot::MeasuredState& state,
                                  robot::Command& command) noexcept {
  command.tick = state.clock.tick;
  for (size_t ak = 0; ak < models_.size(); ++ak) {
    const runtime::AchdModel& model = models_[ak];
    runtime::AchdData& data = data_[ak];
    const int n = model.nq;
    runtime::JointVector q(n), zero = runtime::JointVector::Zero(n);
    bool finite = true;
    for (int i = 0; i < n; ++i) {
      q[i] = state.arm[ak].q[static_cast<size_t>(i)];
      finite = finite && std::isfinite(q[i]);
    }
    robot::JointValues& tau = command.arm_tau[ak];
    if (!finite) {
      std::fill(tau.begin(), tau.end(), 0.0);
      continue;
    }
    runtime::rne(model, data, q, zero, zero, {});
    for (int i = 0; i < n; ++i) tau[static_cast<size_t>(i)] = data.tau[i];
    if (!f_E_P[ak].isZero()) {
      runtime::tip_jacobian(model, data, q);
      const runtime::Vec3 f_B = X_PB_[ak].R.transpose() * f_E_P[ak];
      const runtime::JointVector t = data.J_To_B.bottomRows<3>().transpose() * f_B;
      for (int i = 0; i < n; ++i) tau[static_cast<size_t>(i)] += t[i];
    }
  }
}

PlatformWrenchDriver::PlatformWrenchDriver(const runtime::KeloConfig& config)
    : model_(config), data_(model_), q_(runtime::KeloPivotVector::Zero(model_.drives)) {}

void PlatformWrenchDriver::compute(const robot::MeasuredState& state,
                                   robot::Command& command) noexcept {
  command.tick = state.clock.tick;
  for (int i = 0; i < model_.drives; ++i) q_[i] = state.pivot_q[static_cast<size_t>(i)];
  if (!q_.allFinite() || !F_p.allFinite()) {
    std::fill(command.wheel_tau.begin(), command.wheel_tau.end(), 0.0);
    return;
  }
  const runtime::KeloDriveVector& tau = runtime::kelo_force_step(model_, data_, q_, F_p);
  for (int w = 0; w < 2 * model_.drives; ++w) command.wheel_tau[static_cast<size_t>(w)] = tau[w];
}

}  // namespace mospec::sim
