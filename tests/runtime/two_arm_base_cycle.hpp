// One tick of the whole SC1-shaped controller: both arms' ACHD solvers and the
// base cycle (base_cycle.hpp), composed the way generated code will chain them:
//   per arm: ACHD (nc = 5 tip constraints: the three angular axes and the
//   linear x, y axes held at zero acceleration; the distance controller's force
//   applied at the tip as an external wrench; gravity) -> the tip pose X_BT in
//   the arm's root (= shoulder) frame -> the base cycle's 3D-1D maps,
//   constraints, monitors, controllers and KELO distribution.
// The arms' state is advanced with the solved accelerations (semi-implicit
// Euler), standing in for the robot; a joint posture task is the feed-forward
// torque. Used by the allocation test and
// BM_TwoArmBaseTick.
#pragma once

#include <array>
#include <span>

#include "base_cycle.hpp"
#include "runtime/achd.hpp"

namespace mospec::runtime::testing {

class TwoArmBaseCycle {
 public:
  explicit TwoArmBaseCycle(const Chain& arm) : model_(arm), right_(model_), left_(model_) {
    const int n = model_.nq;
    // A bent-elbow posture away from singularities (any nq).
    JointVector q0 = JointVector::Zero(n);
    for (int i = 0; i < n; ++i) q0[i] = (i % 2 == 1) ? 0.6 : 0.1 * (i + 1);
    for (Side* side : {&right_, &left_}) {
      side->q0 = q0;
      side->q = q0;
      side->qd = JointVector::Zero(n);
      side->tau_ff = JointVector::Zero(n);
      side->F_ext.fill(Vec6::Zero());
    }
    left_.q0[0] = left_.q[0] = -q0[0];
    alpha_ = ConstraintMatrix::Zero(6, 5);
    for (int c = 0; c < 5; ++c) alpha_(c, c) = 1.0;  // ω̇x, ω̇y, ω̇z, a_x, a_y (angular first)
    beta_ = ConstraintVector::Zero(5);
  }

  // One tick at time t [s] after dt [s]; returns the hub torques. Counts arm
  // solves that came back degraded (singular constraints) in degraded().
  const KeloDriveVector& tick(double t, double dt) noexcept {
    step_arm(right_, base_.right_force(), dt);
    step_arm(left_, base_.left_force(), dt);
    base_.set_contact_poses(right_.data.X_BT, left_.data.X_BT);
    return base_.tick(t, dt);
  }

  const BaseCycle& base() const { return base_; }
  const AchdData& right_arm() const { return right_.data; }
  const AchdData& left_arm() const { return left_.data; }
  int degraded() const { return degraded_; }

 private:
  struct Side {
    explicit Side(const AchdModel& m) : data(m) {}
    AchdData data;
    JointVector q0, q, qd, tau_ff;
    std::array<Vec6, kMaxJoints> F_ext;
  };

  void step_arm(Side& s, double force_N, double dt) noexcept {
    const int n = model_.nq;
    // The commanded contact force acts on the last segment along the root's x
    // axis (about the segment origin, in B): a stand-in for Eq. (1)'s wrench.
    s.F_ext[static_cast<size_t>(n - 1)] = (Vec6() << 0, 0, 0, 0.05 * force_N, 0, 0).finished();
    // A joint-space posture task as the feed-forward torque (what a lower
    // priority level would add); it keeps the free directions from drifting.
    s.tau_ff = kPostureStiffness * (s.q0 - s.q) - kPostureDamping * s.qd;
    const Status status =
        achd(model_, s.data, s.q, s.qd, s.tau_ff,
             std::span<const Vec6>(s.F_ext.data(), static_cast<size_t>(n)), alpha_, beta_);
    degraded_ += status != Status::Ok;
    s.qd += dt * s.data.qdd;
    s.q += dt * s.qd;
  }

  static constexpr double kPostureStiffness = 20.0;  // N·m/rad
  static constexpr double kPostureDamping = 2.0;     // N·m·s/rad
  AchdModel model_;
  Side right_, left_;
  ConstraintMatrix alpha_;
  ConstraintVector beta_;
  BaseCycle base_;
  int degraded_ = 0;
};

}  // namespace mospec::runtime::testing
