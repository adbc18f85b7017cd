// Drivers: fixed command laws for running the simulated robot headless (`mospec
// sim`) and for the physics tests, not generated from a model. Each fills part
// of a Command from the robot interface (MeasuredState in, Command out) with the
// runtime's solvers; compute() is noexcept and allocation-free. (In src/sim,
// "controller" means only the robot::Controller that sim::run drives.)
#pragma once

#include <array>

#include "robot/interface.hpp"
#include "runtime/chain.hpp"
#include "runtime/kelo.hpp"
#include "runtime/model.hpp"

namespace mospec::sim {

// Gravity compensation of both arms with the runtime's RNE, tau = g(q), plus
// an optional end-effector force: tau += J^T f with f the force each
// end-effector is to exert on its environment, in the platform frame P.
// Gravity is taken as -9.81 m/s² along z_P (the platform is assumed level;
// no ground truth is used). Non-finite readings give a zero command for that
// arm (a torque computed from NaN is not sent).
class GravityCompensation {
 public:
  // X_PB: each arm's base in the platform frame. Throws mospec::Error when the
  // chain does not have robot::kArmJoints joints.
  GravityCompensation(const runtime::Chain& arm,
                      const std::array<runtime::Pose, robot::kArms>& X_PB);

  // Sets command.arm_tau (and command.tick); leaves the wheel torques alone.
  void compute(const robot::MeasuredState& state, robot::Command& command) noexcept;

  // End-effector force to exert [N] (Eigen leaves {} uninitialised: zero it).
  std::array<runtime::Vec3, robot::kArms> f_E_P{runtime::Vec3::Zero(), runtime::Vec3::Zero()};

 private:
  std::array<runtime::Pose, robot::kArms> X_PB_;
  std::array<runtime::AchdModel, robot::kArms> models_;
  std::array<runtime::AchdData, robot::kArms> data_;
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
};

}  // namespace mospec::sim
