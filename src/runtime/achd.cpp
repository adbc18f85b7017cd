#include "runtime/achd.hpp"

#include <string>

#include "support/diagnostics.hpp"

namespace mospec::runtime {

namespace {

// Equations a)-g) below follow Vereshchagin (1989) as tagged in KDL, rewritten
// in Featherstone's articulated-body notation. Every quantity of segment i is
// in S_i at So_i; X_i is the motion transform from the parent into S_i.

// Outward sweep: poses, twists, velocity-product accelerations, rigid-body
// bias forces (including the external wrenches).
void outward_sweep(const AchdModel& model, AchdData& d, const JointIn& q, const JointIn& qd,
                   SegmentWrenches F_ext) noexcept {
  Vec6 V_P = Vec6::Zero();
  Pose X_BP;
  for (int i = 0; i < model.nq; ++i) {
    const auto k = static_cast<std::size_t>(i);
    const SegmentModel& s = model.segments[k];
    const Pose X_PS = segment_pose(s, q[i]);
    d.X_PS[k] = X_PS;
    d.X_BS[k] = X_BP * X_PS;
    const Vec6 vJ = motion_subspace(s) * qd[i];
    d.V[k] = motion_to_child(X_PS, V_P) + vJ;
    d.c[k] = cross_motion(d.V[k], vJ);
    d.IA[k] = s.I_So_S;
    const Vec6 IV = s.I_So_S * d.V[k];
    d.pA[k] = cross_force(d.V[k], IV);
    if (!F_ext.empty()) {
      const Mat3& R_BS = d.X_BS[k].R;
      d.pA[k].head<3>().noalias() -= R_BS.transpose() * F_ext[k].head<3>();
      d.pA[k].tail<3>().noalias() -= R_BS.transpose() * F_ext[k].tail<3>();
    }
    V_P = d.V[k];
    X_BP = d.X_BS[k];
  }
  d.X_BT = X_BP * model.X_NT;
}

// alpha (at To, in B) -> the last segment's frame N, at No.
void constraints_to_tip_segment(const AchdModel& model, AchdData& d,
                                const ConstraintsIn& alpha_To_B) noexcept {
  const int nc = static_cast<int>(alpha_To_B.cols());
  const Mat3& R_BN = d.X_BS[static_cast<std::size_t>(model.nq - 1)].R;
  const Vec3& p_NoTo_N = model.X_NT.p;
  d.alpha_No_N.resize(6, nc);
  for (int c = 0; c < nc; ++c) {
    const Vec3 f_N = R_BN.transpose() * alpha_To_B.col(c).tail<3>();
    d.alpha_No_N.col(c).tail<3>() = f_N;
    d.alpha_No_N.col(c).head<3>() =
        R_BN.transpose() * alpha_To_B.col(c).head<3>() + p_NoTo_N.cross(f_N);
  }
}

// Inward sweep: articulated inertias and bias forces, and how the unit
// constraint forces propagate to the root (E), the acceleration energy they
// generate (M) and the bias acceleration energy (G).
void inward_sweep(const AchdModel& model, AchdData& d, const JointIn& tau_ff, int nc) noexcept {
  const int n = model.nq;
  d.E[static_cast<std::size_t>(n - 1)] = d.alpha_No_N;
  d.M.setZero(nc, nc);
  d.G.setZero(nc);
  for (int i = n - 1; i >= 0; --i) {
    const auto k = static_cast<std::size_t>(i);
    const SegmentModel& s = model.segments[k];
    const Vec6 S = motion_subspace(s);
    Mat6& IA = d.IA[k];
    d.U[k].noalias() = IA * S;
    d.D[k] = S.dot(d.U[k]) + s.armature;
    const Vec6 IAc = IA * d.c[k];
    d.u[k] = tau_ff[i] - S.dot(d.pA[k] + IAc);
    d.EZ[k].noalias() = d.E[k].transpose() * S;
    const double inv_D = 1.0 / d.D[k];
    // d) acceleration energy of the unit constraint forces.
    d.M.noalias() -= (inv_D * d.EZ[k]) * d.EZ[k].transpose();
    // e) bias acceleration energy.
    d.G.noalias() += d.E[k].transpose() * (d.c[k] + (d.u[k] * inv_D) * S);
    // a) b) c) what the parent sees through joint i, still in S_i ...
    Mat6 Ia = IA;
    Ia.noalias() -= (inv_D * d.U[k]) * d.U[k].transpose();
    const Vec6 pa = d.pA[k] + IAc + (d.u[k] * inv_D) * d.U[k];
    ConstraintMatrix& Ea = d.E[k];  // E_i is not needed after this step
    d.EZ[k] *= inv_D;               // ... so neither is EZ unscaled; pass 3 rescales
    Ea.noalias() -= d.U[k] * d.EZ[k].transpose();
    // ... and moved into the parent frame.
    const Mat6 X = motion_transform_to_child(d.X_PS[k]);
    if (i > 0) {
      d.IA[k - 1].noalias() += X.transpose() * Ia * X;
      d.pA[k - 1] += force_to_parent(d.X_PS[k], pa);
      d.E[k - 1].noalias() = X.transpose() * Ea;
    } else {
      d.E_base.noalias() = X.transpose() * Ea;
    }
  }
}

}  // namespace

Status achd(const AchdModel& model, AchdData& d, const JointIn& q, const JointIn& qd,
            const JointIn& tau_ff, SegmentWrenches F_ext, const ConstraintsIn& alpha_To_B,
            const ConstraintValuesIn& beta) noexcept {
  const int n = model.nq;
  const int nc = static_cast<int>(alpha_To_B.cols());
  if (d.nq != n || q.size() != n || qd.size() != n || tau_ff.size() != n ||
      (!F_ext.empty() && static_cast<int>(F_ext.size()) != n) || nc > kMaxConstraints ||
      beta.size() != nc) {
    return Status::SizeMismatch;
  }

  outward_sweep(model, d, q, qd, F_ext);
  constraints_to_tip_segment(model, d, alpha_To_B);
  inward_sweep(model, d, tau_ff, nc);

  // f) the constraint force magnitudes:  M_0 nu = beta' - E_0^T a_0 - G_0,
  // where a_0 = [0; -g_B] is the root acceleration standing in for gravity and
  // beta' = beta + alpha^T a_0 re-adds that fictitious acceleration to the
  // caller's physical beta (a root acceleration with no angular part is the same
  // spatial vector at To).
  Vec6 a_0;
  a_0 << Vec3::Zero(), -model.g_B;
  Status status = Status::Ok;
  d.nu.resize(nc);
  if (nc > 0) {
    d.rhs = beta;
    d.rhs.noalias() += alpha_To_B.transpose() * a_0;
    d.rhs.noalias() -= d.E_base.transpose() * a_0;
    d.rhs -= d.G;
    // M_0 is negative definite unless the configuration is singular for the
    // constraints; LDLT (with pivoting) is exact and cheap for nc <= 6.
    d.ldlt_M.compute(d.M);
    const auto& D = d.ldlt_M.vectorD();
    const double largest = D.cwiseAbs().maxCoeff();
    if (d.ldlt_M.info() == Eigen::Success && D.cwiseAbs().minCoeff() > 1e-12 * largest) {
      d.nu = d.ldlt_M.solve(d.rhs);
    } else {
      // Singular: a truncated eigen-decomposition pseudo-inverse keeps the
      // constraints that remain feasible (KDL truncates an SVD the same way,
      // with an absolute 1e-14 threshold).
      status = Status::ConstraintsDegraded;
      d.eig_M.compute(d.M);
      const auto& w = d.eig_M.eigenvalues();
      const auto& Q = d.eig_M.eigenvectors();
      const double tol = 1e-12 * std::max(w.cwiseAbs().maxCoeff(), 1e-300);
      d.G.noalias() = Q.transpose() * d.rhs;  // G is free now: reuse as scratch
      for (int k = 0; k < nc; ++k) d.G[k] = std::abs(w[k]) > tol ? d.G[k] / w[k] : 0.0;
      d.nu.noalias() = Q * d.G;
    }
  }

  // g) outward: joint and segment accelerations, and the realising torque.
  const Vec3 f_c = nc > 0 ? Vec3(alpha_To_B.bottomRows<3>() * d.nu) : Vec3::Zero();
  const Vec3 n_c = nc > 0 ? Vec3(alpha_To_B.topRows<3>() * d.nu) : Vec3::Zero();
  d.qdd.resize(n);
  d.tau.resize(n);
  Vec6 a_P = a_0;
  for (int i = 0; i < n; ++i) {
    const auto k = static_cast<std::size_t>(i);
    const SegmentModel& s = model.segments[k];
    const Vec6 S = motion_subspace(s);
    const Vec6 a_from_parent = motion_to_child(d.X_PS[k], a_P);
    // u already holds -S^T IA c, so c is not in the projected acceleration;
    // EZ was scaled by 1/D in the inward sweep.
    double qdd = (d.u[k] - d.U[k].dot(a_from_parent)) / d.D[k];
    if (nc > 0) qdd -= d.EZ[k].dot(d.nu);
    d.qdd[i] = qdd;
    d.a[k] = a_from_parent + d.c[k] + S * qdd;
    a_P = d.a[k];
    // tau = tau_ff - J^T (alpha nu): the constraint wrench's moment about the
    // joint, projected on its axis.
    const Vec3 axis_B = d.X_BS[k].R * s.axis;
    double Jt_F;
    if (s.type == JointType::Revolute) {
      Jt_F = axis_B.dot(n_c + (d.X_BT.p - d.X_BS[k].p).cross(f_c));
    } else {
      Jt_F = axis_B.dot(f_c);
    }
    d.tau[i] = tau_ff[i] - Jt_F;
  }
  return status;
}

void check_achd_arguments(const AchdModel& model, const JointIn& q, const JointIn& qd,
                          const JointIn& tau_ff, SegmentWrenches F_ext,
                          const ConstraintsIn& alpha_To_B, const ConstraintValuesIn& beta) {
  const auto expect = [](const char* name, Eigen::Index got, Eigen::Index want, const char* hint) {
    if (got != want) {
      throw Error("size-mismatch", std::string("achd: ") + name + " has " + std::to_string(got) +
                                       " entries, expected " + std::to_string(want) + " (" + hint +
                                       ")");
    }
  };
  const auto finite = [](const char* name, bool ok) {
    if (!ok) throw Error("non-finite", std::string("achd: ") + name + " has non-finite entries");
  };
  expect("q", q.size(), model.nq, "model.nq");
  expect("qd", qd.size(), model.nq, "model.nq");
  expect("tau_ff", tau_ff.size(), model.nq, "model.nq");
  if (!F_ext.empty()) {
    expect("F_ext", static_cast<Eigen::Index>(F_ext.size()), model.nq,
           "one wrench per segment, or none");
  }
  if (alpha_To_B.cols() > kMaxConstraints) {
    throw Error("size-mismatch", "achd: alpha has " + std::to_string(alpha_To_B.cols()) +
                                     " columns, at most " + std::to_string(kMaxConstraints) +
                                     " constraints are supported");
  }
  expect("beta", beta.size(), alpha_To_B.cols(), "one per alpha column");
  finite("q", q.allFinite());
  finite("qd", qd.allFinite());
  finite("tau_ff", tau_ff.allFinite());
  for (const Vec6& F : F_ext) finite("F_ext", F.allFinite());
  finite("alpha", alpha_To_B.allFinite());
  finite("beta", beta.allFinite());
}

}  // namespace mospec::runtime
