// Drivers: fixed command laws for running the simulated robot headless (`mospec
// sim`) and for the physics tests, not generated from a model. Each fills part
// of a Command from the robot interface (MeasuredState in, Command out) with the
// runtime's solvers; compute() is noexcept and allocation-free. (In src/sim,
// "controller" means only the robot::Controller that sim::run drives.)
#pragma once

#include <span>
#include <vector>

#include "robot/interface.hpp"
#include "runtime/chain.hpp"
#include "runtime/kelo.hpp"
#include "runtime/model.hpp"

namespace mospec::sim {

// Gravity compensation of every arm with the runtime's RNE, tau = g(q), plus
// an optional end-effector force: tau += J^T f with f the force each
// end-effector is to exert on its environment, in the platform frame P.
// Gravity is taken as -9.81 m/s² along z_P (the platform is assumed level;
// no ground truth is used). Non-finite readings give a zero command for that
// arm (a torque computed from NaN is not sent).
class GravityCompensation {
 public:
  // arms[k], X_PB[k]: arm k's chain and its base in the platform frame.
  // Throws mospec::Error when the counts differ.
  GravityCompensation(std::span<const runtime::Chain> arms, std::span<const runtime::Pose> X_PB);
  // Every arm is `arm`.
  GravityCompensation(const runtime::Chain& arm, std::span<const runtime::Pose> X_PB)
      : GravityCompensation(std::vector<runtime::Chain>(X_PB.size(), arm), X_PB) {}

  // Sets command.arm_tau (and command.tick); leaves the wheel torques alone.
  void compute(const robot::MeasuredState& state, robot::Command& command) noexcept;

  // Per arm: the end-effector force to exert [N] (zero at construction).
  std::vector<runtime::Vec3> f_E_P;

 private:
  std::vector<runtime::Pose> X_PB_;
  std::vector<runtime::AchdModel> models_;
  std::vector<runtime::AchdData> data_;
};

// A commanded platform wrench distributed to the drives by the runtime's KELO
// solver (kelo_force_step: Eq. 2-3 with the alignment reference), from the
// measured pivot angles. Sets command.wheel_tau.
class PlatformWrenchDriver {
 public:
  explicit PlatformWrenchDriver(const runtime::KeloConfig& config);

  void compute(const robot::MeasuredState& state, robot::Command& command) noexcept;

  runtime::Vec3 F_p = runtime::Vec3::Zero();  // [f_x, f_y, m_z] seen by P [N, N, N·m]

 private:
  runtime::KeloModel model_;
  runtime::KeloData data_;
  runtime::KeloPivotVector q_;
};

}  // namespace mospec::sim
