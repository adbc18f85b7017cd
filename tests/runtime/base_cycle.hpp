// One tick of the base part of the paper's alignment task (SC1), composed from
// the runtime's blocks the way generated code will chain them:
//   operators (ComposePose, PoseToLinearDistance, PoseToDirection,
//   PlanarAngleFromDirections, InvertAngle) -> constraint evaluators (tube on
//   each shoulder-contact distance, equality on the angle) -> monitors (level
//   with hysteresis, edge) -> PID with decaying integral -> Eq. (1) wrench ->
//   TransformWrenchToProximal -> AddWrench -> planar projection -> KELO
//   alignment reference, distribution, hub torques and platform twist.
// The arm poses are synthetic (moving with t) unless measured ones are given
// with set_contact_poses (two_arm_base_cycle.hpp feeds the ACHD arms' tips).
// Used by the allocation tests and the benchmarks.
#pragma once

#include <cmath>

#include "kelo_base.hpp"
#include "runtime/controllers.hpp"
#include "runtime/evaluators.hpp"
#include "runtime/kelo.hpp"
#include "runtime/monitors.hpp"
#include "runtime/operators.hpp"

namespace mospec::runtime::testing {

struct ArmSide {
  Pose X_PS;  // shoulder in the platform
  Pose X_SE;  // contact (end-effector) in the shoulder
  PidState distance_pid;
  PidState angle_pid;
  MonitorState in_tube_level;
  MonitorState in_tube_edge;
  MonitorState height_ok;
  Vec6 F_Po_P = Vec6::Zero();  // this arm's contribution, about Po, seen by P
};

class BaseCycle {
 public:
  BaseCycle()
      : tube_({.kind = ConstraintKind::Bilateral, .lower = 0.55, .upper = 0.6, .tolerance = 1e-3},
              "cstr-dist"),
        angle_({.kind = ConstraintKind::Equality, .reference = 0.0, .tolerance = 0.01}, "cstr-ang"),
        height_({.kind = ConstraintKind::LessThan, .threshold = 0.4}, "cstr-height"),
        in_tube_level_({.sense = Sense::Below, .enter = 1e-3, .leave = 5e-3}, "mon-dist-level"),
        in_tube_edge_({.sense = Sense::Below, .enter = 1e-3, .leave = 5e-3}, Edges::Both,
                      "mon-dist-edge"),
        distance_pid_({.kp = 450.0,
                       .ki = 65.5,
                       .kd = 80.0,
                       .decay_rate = 0.99,
                       .output_min = -150.0,
                       .output_max = 150.0},
                      "ctrl-dist"),
        angle_pid_({.kp = 200.0,
                    .ki = 2.9,
                    .kd = 80.5,
                    .output_min = -50.0,
                    .output_max = 50.0,
                    .anti_windup = AntiWindup::BackCalculation,
                    .tracking_rate = 10.0},
                   "ctrl-ang"),
        add_({"platform-origin", "platform"}, {"platform-origin", "platform"}),
        kelo_(::mospec::testing::paper_base()),
        kelo_data_(kelo_) {
    right_.X_PS = {Mat3::Identity(), Vec3(0.2, -0.15, 0.6)};
    left_.X_PS = {Mat3::Identity(), Vec3(0.2, 0.15, 0.6)};
  }

  // One tick at time t [s] after dt [s]; returns the hub torques.
  const KeloDriveVector& tick(double t, double dt) noexcept {
    events_ = 0;
    step_arm(right_, t, dt, 1.0);
    step_arm(left_, t, dt, -1.0);
    const Vec6 F_Po_P = add_(right_.F_Po_P, left_.F_Po_P);
    const Vec3 F_p = planar_wrench(F_Po_P);
    const Vec4 q(0.1 * std::sin(t), -0.2, 0.3 * std::cos(t), 1.0);
    kelo_force_step(kelo_, kelo_data_, q, F_p);
    KeloDriveVector wheel_rates = KeloDriveVector::Constant(8, 2.0);
    wheel_rates[0] += 0.1 * std::sin(3 * t);
    kelo_platform_twist(kelo_, kelo_data_, wheel_rates);
    return kelo_data_.tau_wheel;
  }

  // Measured contact poses X_SE (end-effector in its shoulder frame) for the
  // next tick, replacing the synthetic motion from then on.
  void set_contact_poses(const Pose& X_SE_right, const Pose& X_SE_left) noexcept {
    right_.X_SE = X_SE_right;
    left_.X_SE = X_SE_left;
    measured_ = true;
  }
  // The force each distance controller commands along its shoulder-contact
  // direction [N] (what the arms must realise at their tips).
  double right_force() const { return right_.distance_pid.output; }
  double left_force() const { return left_.distance_pid.output; }

  const KeloData& kelo_data() const { return kelo_data_; }
  int events() const { return events_; }

 private:
  void step_arm(ArmSide& arm, double t, double dt, double side) noexcept {
    if (!measured_) {
      // The contact point moves in the shoulder frame (synthetic arm motion).
      arm.X_SE.p = Vec3(0.5 + 0.1 * std::sin(t + side), side * 0.05 * std::cos(t), -0.3);
      arm.X_SE.R = Eigen::AngleAxisd(0.2 * std::sin(t), Vec3::UnitZ()).toRotationMatrix();
    }
    const Pose X_PE = compose_pose(arm.X_PS, arm.X_SE);

    // 3D -> 1D.
    const double distance = pose_to_linear_distance(arm.X_SE);
    Vec3 d_SE_S;
    pose_to_direction(arm.X_SE, d_SE_S);
    const Vec3 d_SE_P = rotate_direction_to_proximal(arm.X_PS, d_SE_S);
    double angle = 0.0;
    planar_angle_from_directions(Vec3::UnitX(), d_SE_P, Vec3::UnitZ(), angle);
    angle = invert_angle(angle);
    const double height = view(X_PE, {Part::Linear, Axis::Z});

    // Constraints, monitors.
    const Evaluation dist_eval = tube_.evaluate(distance);
    const Evaluation ang_eval = angle_.evaluate(angle);
    LevelMonitor::update(arm.height_ok, height_.evaluate(height).satisfied);
    in_tube_level_.update(arm.in_tube_level, std::abs(dist_eval.error));
    events_ += in_tube_edge_.update(arm.in_tube_edge, std::abs(dist_eval.error)) != Event::None;

    // Controllers.
    distance_pid_.step(arm.distance_pid, dist_eval.error, dt);
    angle_pid_.step(arm.angle_pid, ang_eval.error, dt);

    // 1D -> 3D: the force along the shoulder-contact direction at the shoulder
    // (Eq. 1 with the shoulder as both measurement and application point), then
    // moved to the platform origin; the angle controller's output as a moment
    // about z (a view written back).
    Vec6 F_So_S =
        wrench_from_position_direction_and_magnitude(Vec3::Zero(), d_SE_S, arm.distance_pid.output);
    F_So_S[View{Part::Angular, Axis::Z}.index()] += arm.angle_pid.output;
    arm.F_Po_P = transform_wrench_to_proximal(arm.X_PS, F_So_S);
  }

  ConstraintEvaluator tube_;
  ConstraintEvaluator angle_;
  ConstraintEvaluator height_;
  LevelMonitor in_tube_level_;
  EdgeMonitor in_tube_edge_;
  Pid distance_pid_;
  Pid angle_pid_;
  AddWrench add_;
  KeloModel kelo_;
  KeloData kelo_data_;
  ArmSide right_, left_;
  int events_ = 0;
  bool measured_ = false;
};

}  // namespace mospec::runtime::testing
