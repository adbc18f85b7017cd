#include "runtime/steps.hpp"

#include <cmath>

#include "runtime/rne.hpp"

namespace mospec::runtime::steps {

ArmWorkspace::ArmWorkspace(const AchdModel& model, int constraints)
    : q(JointVector::Zero(model.nq)),
      qd(JointVector::Zero(model.nq)),
      tau_ff(JointVector::Zero(model.nq)),
      tau_measured(JointVector::Zero(model.nq)),
      tau_bias(JointVector::Zero(model.nq)),
      alpha_To_B(ConstraintMatrix::Zero(6, constraints)),
      beta(ConstraintVector::Zero(constraints)),
      alpha_engaged(ConstraintMatrix::Zero(6, constraints)),
      beta_engaged(ConstraintVector::Zero(constraints)),
      tau_command(JointVector::Zero(model.nq)) {
  F_ext.fill(Vec6::Zero());
  engaged.fill(true);
}

void arm_kinematics(const AchdModel& model, AchdData& data, ArmWorkspace& ws,
                    std::span<const double> q_measured,
                    std::span<const double> qd_measured) noexcept {
  ws.input_fault = false;
  for (int i = 0; i < model.nq; ++i) {
    const auto k = static_cast<std::size_t>(i);
    const bool present = k < q_measured.size() && k < qd_measured.size();
    const double qi = present ? q_measured[k] : std::nan("");
    const double qdi = present ? qd_measured[k] : std::nan("");
    // Keep each entry's last finite value (q and qd start at zero).
    if (std::isfinite(qi)) ws.q[i] = qi;
    if (std::isfinite(qdi)) ws.qd[i] = qdi;
    ws.input_fault = ws.input_fault || !std::isfinite(qi) || !std::isfinite(qdi);
  }
  ws.any_valid = ws.any_valid || !ws.input_fault;
  // The outward velocity sweep of ACHD/RNE, without the dynamics.
  Vec6 V_P = Vec6::Zero();
  Pose X_BP;
  for (int i = 0; i < model.nq; ++i) {
    const auto k = static_cast<std::size_t>(i);
    const SegmentModel& s = model.segments[k];
    data.X_PS[k] = runtime::segment_pose(s, ws.q[i]);
    data.X_BS[k] = X_BP * data.X_PS[k];
    data.V[k] = motion_to_child(data.X_PS[k], V_P) + motion_subspace(s) * ws.qd[i];
    V_P = data.V[k];
    X_BP = data.X_BS[k];
  }
  data.X_BT = X_BP * model.X_NT;
}

Vec6 estimated_wrench(const AchdModel& physical_model, AchdData& data, ArmWorkspace& ws,
                      std::span<const double> tau_measured, int segment) noexcept {
  const int n = physical_model.nq;
  for (int i = 0; i < n; ++i) joint_torque(ws, tau_measured, i);
  // h(q, qd): rne with qdd = 0 (also refreshes data.X_BS from ws.q).
  impl::rne_into(physical_model, data, ws.q, ws.qd, nullptr, {}, ws.tau_bias);
  const auto k = static_cast<std::size_t>(segment);
  const Vec3& p_BSo = data.X_BS[k].p;
  Jacobian J = Jacobian::Zero(6, n);
  for (int i = 0; i <= segment && i < n; ++i) {
    const auto j = static_cast<std::size_t>(i);
    const Vec3 axis_B = data.X_BS[j].R * physical_model.segments[j].axis;
    if (physical_model.segments[j].type == JointType::Revolute) {
      J.col(i) << axis_B, axis_B.cross(p_BSo - data.X_BS[j].p);
    } else {
      J.col(i) << Vec3::Zero(), axis_B;
    }
  }
  Mat6 A;
  A.noalias() = J * J.transpose();
  A.diagonal().array() += kWrenchEstimateDamping2;
  Vec6 b;
  b.noalias() = J * (ws.tau_bias - ws.tau_measured);
  return A.ldlt().solve(b);
}

void arm_solve(const AchdModel& task_model, const AchdModel& physical_model, AchdData& data,
               ArmWorkspace& ws, std::span<double> tau_out) noexcept {
  const AchdModel& model = task_model;
  const auto n = static_cast<std::size_t>(model.nq);
  if (ws.input_fault) {
    arm_hold(physical_model, data, ws, kFaultHoldTimeConstant, tau_out);
    return;
  }
  // Pack the engaged columns (all of them, unless a one-sided constraint is
  // satisfied): fixed-capacity storage, nothing allocated.
  Eigen::Index engaged = 0;
  for (Eigen::Index k = 0; k < ws.beta.size(); ++k) {
    if (!ws.engaged[static_cast<std::size_t>(k)]) continue;
    ws.alpha_engaged.col(engaged) = ws.alpha_To_B.col(k);
    ws.beta_engaged[engaged] = ws.beta[k];
    ++engaged;
  }
  const auto beta = ws.beta_engaged.head(engaged);
  bool finite = ws.tau_ff.allFinite() && beta.allFinite();
  for (std::size_t i = 0; i < n; ++i) finite = finite && ws.F_ext[i].allFinite();
  if (finite) {
    ws.status = achd(model, data, ws.q, ws.qd, ws.tau_ff, SegmentWrenches(ws.F_ext.data(), n),
                     ws.alpha_engaged.leftCols(engaged), beta);
  } else {
    ws.status = Status::SizeMismatch;  // reported as a fault: nothing solved
  }
  const bool solved = ws.status == Status::Ok || ws.status == Status::ConstraintsDegraded;
  if (solved) {
    const JointIn qdd(data.qdd);
    impl::rne_into(physical_model, data, ws.q, ws.qd, &qdd, {}, ws.tau_command);
  }
  if (!solved || !ws.tau_command.allFinite()) ws.tau_command.setZero();
  for (std::size_t i = 0; i < tau_out.size(); ++i) {
    tau_out[i] = i < n ? ws.tau_command[static_cast<Eigen::Index>(i)] : 0.0;
  }
}

void arm_hold(const AchdModel& physical_model, AchdData& data, ArmWorkspace& ws,
              double time_constant, std::span<double> tau_out) noexcept {
  const auto n = static_cast<std::size_t>(physical_model.nq);
  ws.status = Status::Ok;
  if (!ws.any_valid) {
    ws.tau_command.setZero();
  } else {
    data.qdd = -ws.qd / time_constant;
    const JointIn qdd(data.qdd);
    impl::rne_into(physical_model, data, ws.q, ws.qd, &qdd, {}, ws.tau_command);
    if (!ws.tau_command.allFinite()) ws.tau_command.setZero();
  }
  for (std::size_t i = 0; i < tau_out.size(); ++i) {
    tau_out[i] = i < n ? ws.tau_command[static_cast<Eigen::Index>(i)] : 0.0;
  }
}

void base_force_distribution(const KeloModel& model, KeloData& data,
                             std::span<const double> pivot_q, const Vec6& F_Po_P,
                             std::span<double> wheel_tau) noexcept {
  KeloPivotVector q = KeloPivotVector::Zero(model.drives);
  bool finite = F_Po_P.allFinite() && pivot_q.size() >= static_cast<std::size_t>(model.drives);
  for (int i = 0; i < model.drives && finite; ++i) {
    q[i] = pivot_q[static_cast<std::size_t>(i)];
    finite = std::isfinite(q[i]);
  }
  if (!finite) {
    for (double& t : wheel_tau) t = 0.0;
    return;
  }
  const KeloDriveVector& tau = kelo_force_step(model, data, q, planar_wrench(F_Po_P));
  for (std::size_t w = 0; w < wheel_tau.size(); ++w) {
    wheel_tau[w] =
        static_cast<Eigen::Index>(w) < tau.size() ? tau[static_cast<Eigen::Index>(w)] : 0.0;
  }
}

namespace {

// Pivots and wheel rates as Eigen vectors; false when any is not finite.
bool base_measurements(std::span<const double> pivot_q, std::span<const double> wheel_qd,
                       KeloPivotVector& q, KeloDriveVector& rates) noexcept {
  if (pivot_q.size() < static_cast<std::size_t>(q.size()) ||
      wheel_qd.size() < static_cast<std::size_t>(rates.size()))
    return false;
  bool finite = true;
  for (Eigen::Index i = 0; i < q.size(); ++i) {
    q[i] = pivot_q[static_cast<std::size_t>(i)];
    finite = finite && std::isfinite(q[i]);
  }
  for (Eigen::Index w = 0; w < rates.size(); ++w) {
    rates[w] = wheel_qd[static_cast<std::size_t>(w)];
    finite = finite && std::isfinite(rates[w]);
  }
  return finite;
}

}  // namespace

void base_velocity(const KeloModel& model, KeloData& data, std::span<const double> pivot_q,
                   std::span<const double> wheel_qd, Vec6& twist) noexcept {
  KeloPivotVector q = KeloPivotVector::Zero(model.drives);
  KeloDriveVector rates = KeloDriveVector::Zero(2 * model.drives);
  if (!base_measurements(pivot_q, wheel_qd, q, rates)) {
    twist.setZero();
    return;
  }
  kelo_set_pivots(model, data, q);
  twist = spatial_twist(kelo_platform_twist(model, data, rates));
}

void base_hold(const KeloModel& model, KeloData& data, std::span<const double> pivot_q,
               std::span<const double> wheel_qd, std::span<double> wheel_tau) noexcept {
  KeloPivotVector q = KeloPivotVector::Zero(model.drives);
  KeloDriveVector rates = KeloDriveVector::Zero(2 * model.drives);
  if (!base_measurements(pivot_q, wheel_qd, q, rates)) {
    for (double& t : wheel_tau) t = 0.0;
    return;
  }
  kelo_set_pivots(model, data, q);
  const Vec3 xd = kelo_platform_twist(model, data, rates);
  const Vec3 F_p(-kBaseHoldLinearDamping * xd[0], -kBaseHoldLinearDamping * xd[1],
                 -kBaseHoldAngularDamping * xd[2]);
  const KeloDriveVector& tau = kelo_force_step(model, data, q, F_p);
  for (std::size_t w = 0; w < wheel_tau.size(); ++w) {
    wheel_tau[w] =
        static_cast<Eigen::Index>(w) < tau.size() ? tau[static_cast<Eigen::Index>(w)] : 0.0;
  }
}

}  // namespace mospec::runtime::steps
