#include "runtime/achd.hpp"

#include <algorithm>
#include <cmath>
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

// The constraint part runs with compile-time sizes: nc is dispatched once to
// solve<NC>() so every 6 x nc and nc x nc operation is fixed-size (unrolled,
// vectorised) while the storage in AchdData keeps its one capacity.
template <int NC>
struct Fixed {
  using E = Eigen::Matrix<double, 6, NC>;
  using Vec = Eigen::Matrix<double, NC, 1>;
  using Sq = Eigen::Matrix<double, NC, NC>;
  static Eigen::Map<E> e(ConstraintMatrix& m) {
    m.resize(6, NC);
    return Eigen::Map<E>(m.data());
  }
  static Eigen::Map<Vec> vec(ConstraintVector& v) {
    v.resize(NC);
    return Eigen::Map<Vec>(v.data());
  }
  static Eigen::Map<Sq> sq(ConstraintSquare& m) {
    m.resize(NC, NC);
    return Eigen::Map<Sq>(m.data());
  }
};

// alpha (at To, in B) -> the last segment's frame N, at No.
template <int NC>
void constraints_to_tip_segment(const AchdModel& model, AchdData& d,
                                const ConstraintsIn& alpha_To_B) noexcept {
  const Mat3& R_BN = d.X_BS[static_cast<std::size_t>(model.nq - 1)].R;
  auto alpha_N = Fixed<NC>::e(d.alpha_No_N);
  alpha_N.template bottomRows<3>().noalias() =
      R_BN.transpose() * alpha_To_B.template bottomRows<3>();
  alpha_N.template topRows<3>().noalias() = R_BN.transpose() * alpha_To_B.template topRows<3>();
  alpha_N.template topRows<3>().noalias() += skew(model.X_NT.p) * alpha_N.template bottomRows<3>();
}

// Inward sweep: articulated inertias and bias forces, and how the unit
// constraint forces propagate to the root (E), the acceleration energy they
// generate (M) and the bias acceleration energy (G).
template <int NC>
void inward_sweep(const AchdModel& model, AchdData& d, const JointIn& tau_ff) noexcept {
  using F = Fixed<NC>;
  const int n = model.nq;
  auto M = F::sq(d.M);
  auto G = F::vec(d.G);
  M.setZero();
  G.setZero();
  F::e(d.E[static_cast<std::size_t>(n - 1)]) = F::e(d.alpha_No_N);
  for (int i = n - 1; i >= 0; --i) {
    const auto k = static_cast<std::size_t>(i);
    const SegmentModel& s = model.segments[k];
    const bool revolute = s.type == JointType::Revolute;
    Mat6& IA = d.IA[k];
    Vec6& U = d.U[k];
    // IA S picks three columns of IA (S is [a; 0] or [0; a]).
    U.noalias() = revolute ? IA.leftCols<3>() * s.axis : IA.rightCols<3>() * s.axis;
    const auto S_dot = [&](const Vec6& x) {
      return revolute ? s.axis.dot(x.head<3>()) : s.axis.dot(x.tail<3>());
    };
    d.D[k] = S_dot(U) + s.armature;
    const Vec6 IAc = IA * d.c[k];
    d.u[k] = tau_ff[i] - S_dot(d.pA[k] + IAc);
    const double inv_D = 1.0 / d.D[k];
    // a) b) what the parent sees through joint i, still in S_i (IA_i is not
    // needed after this) ...
    const Vec6 pa = d.pA[k] + IAc + (d.u[k] * inv_D) * U;
    IA.noalias() -= (inv_D * U) * U.transpose();
    const Pose& X_PS = d.X_PS[k];
    if (i > 0) {
      add_inertia_to_parent(X_PS, IA, d.IA[k - 1]);
      d.pA[k - 1] += force_to_parent(X_PS, pa);
    }
    if constexpr (NC > 0) {
      auto E = F::e(d.E[k]);
      auto EZ = F::vec(d.EZ[k]);
      EZ.noalias() = revolute ? E.template topRows<3>().transpose() * s.axis
                              : E.template bottomRows<3>().transpose() * s.axis;
      // d) acceleration energy of the unit constraint forces.
      M.noalias() -= (inv_D * EZ) * EZ.transpose();
      // e) bias acceleration energy.
      Vec6 cSu = d.c[k];
      (revolute ? cSu.head<3>() : cSu.tail<3>()) += (d.u[k] * inv_D) * s.axis;
      G.noalias() += E.transpose() * cSu;
      // c) the constraint forces the parent sees (E_i and unscaled EZ_i are
      // not needed after this: pass 3 uses EZ / D) ...
      EZ *= inv_D;
      E.noalias() -= U * EZ.transpose();
      // ... moved into the parent frame: f_P = R f, n_P = R n + p x f_P.
      auto E_P = F::e(i > 0 ? d.E[k - 1] : d.E_base);
      E_P.template bottomRows<3>().noalias() = X_PS.R * E.template bottomRows<3>();
      E_P.template topRows<3>().noalias() = X_PS.R * E.template topRows<3>();
      E_P.template topRows<3>().noalias() += skew(X_PS.p) * E_P.template bottomRows<3>();
    }
  }
}

// f) the constraint force magnitudes:  M_0 nu = beta' - E_0^T a_0 - G_0,
// where a_0 = [0; -g_B] is the root acceleration standing in for gravity and
// beta' = beta + alpha^T a_0 re-adds that fictitious acceleration to the
// caller's physical beta (a root acceleration with no angular part is the same
// spatial vector at To).
template <int NC>
Status constraint_magnitudes(const AchdModel& model, AchdData& d, const ConstraintsIn& alpha_To_B,
                             const ConstraintValuesIn& beta) noexcept {
  using F = Fixed<NC>;
  auto nu = F::vec(d.nu);
  if constexpr (NC == 0) {
    return Status::Ok;
  } else {
    auto rhs = F::vec(d.rhs);
    const auto M = F::sq(d.M);
    const auto G = F::vec(d.G);
    const auto E_base = F::e(d.E_base);
    const Vec3 minus_g = -model.g_B;
    rhs = beta;
    rhs.noalias() += alpha_To_B.template bottomRows<3>().transpose() * minus_g;
    rhs.noalias() -= E_base.template bottomRows<3>().transpose() * minus_g;
    rhs -= G;
    // M_0 is negative definite unless this configuration is singular for the
    // constraints: Cholesky of -M_0 is exact and cheap for nc <= 6.
    const Eigen::LLT<typename F::Sq> llt(-M);
    const auto diag = llt.matrixLLT().diagonal();
    if (llt.info() == Eigen::Success && diag.minCoeff() > 1e-6 * diag.maxCoeff()) {
      nu = -llt.solve(rhs);
      return Status::Ok;
    }
    // Singular: a truncated eigen-decomposition pseudo-inverse keeps the
    // constraints that remain feasible (KDL truncates an SVD the same way,
    // with an absolute 1e-14 threshold).
    d.eig_M.compute(d.M);
    const auto& w = d.eig_M.eigenvalues();
    const auto& Q = d.eig_M.eigenvectors();
    const double tol = 1e-12 * std::max(w.cwiseAbs().maxCoeff(), 1e-300);
    typename F::Vec y = Q.transpose() * rhs;
    for (int k = 0; k < NC; ++k) y[k] = std::abs(w[k]) > tol ? y[k] / w[k] : 0.0;
    nu.noalias() = Q * y;
    return Status::ConstraintsDegraded;
  }
}

// g) outward: joint and segment accelerations, and the realising torque.
template <int NC>
void final_sweep(const AchdModel& model, AchdData& d, const JointIn& tau_ff,
                 const ConstraintsIn& alpha_To_B) noexcept {
  using F = Fixed<NC>;
  Vec3 f_c = Vec3::Zero(), n_c = Vec3::Zero();
  if constexpr (NC > 0) {
    const auto nu = F::vec(d.nu);
    f_c.noalias() = alpha_To_B.template bottomRows<3>() * nu;
    n_c.noalias() = alpha_To_B.template topRows<3>() * nu;
  }
  const int n = model.nq;
  d.qdd.resize(n);
  d.tau.resize(n);
  Vec6 a_P;
  a_P << Vec3::Zero(), -model.g_B;
  for (int i = 0; i < n; ++i) {
    const auto k = static_cast<std::size_t>(i);
    const SegmentModel& s = model.segments[k];
    const Vec6 a_from_parent = motion_to_child(d.X_PS[k], a_P);
    // u already holds -S^T IA c, so c is not in the projected acceleration.
    double qdd = (d.u[k] - d.U[k].dot(a_from_parent)) / d.D[k];
    if constexpr (NC > 0) qdd -= F::vec(d.EZ[k]).dot(F::vec(d.nu));  // EZ holds EZ / D
    d.qdd[i] = qdd;
    d.a[k] = a_from_parent + d.c[k];
    const Vec3 axis_B = d.X_BS[k].R * s.axis;
    // tau = tau_ff - J^T (alpha nu): the constraint wrench's moment about the
    // joint, projected on its axis.
    double Jt_F;
    if (s.type == JointType::Revolute) {
      d.a[k].head<3>() += s.axis * qdd;
      Jt_F = axis_B.dot(n_c + (d.X_BT.p - d.X_BS[k].p).cross(f_c));
    } else {
      d.a[k].tail<3>() += s.axis * qdd;
      Jt_F = axis_B.dot(f_c);
    }
    d.tau[i] = tau_ff[i] - Jt_F;
    a_P = d.a[k];
  }
}

template <int NC>
Status solve(const AchdModel& model, AchdData& d, const JointIn& tau_ff,
             const ConstraintsIn& alpha_To_B, const ConstraintValuesIn& beta) noexcept {
  if constexpr (NC > 0) constraints_to_tip_segment<NC>(model, d, alpha_To_B);
  inward_sweep<NC>(model, d, tau_ff);
  const Status status = constraint_magnitudes<NC>(model, d, alpha_To_B, beta);
  final_sweep<NC>(model, d, tau_ff, alpha_To_B);
  return status;
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
  switch (nc) {
    case 0:
      return solve<0>(model, d, tau_ff, alpha_To_B, beta);
    case 1:
      return solve<1>(model, d, tau_ff, alpha_To_B, beta);
    case 2:
      return solve<2>(model, d, tau_ff, alpha_To_B, beta);
    case 3:
      return solve<3>(model, d, tau_ff, alpha_To_B, beta);
    case 4:
      return solve<4>(model, d, tau_ff, alpha_To_B, beta);
    case 5:
      return solve<5>(model, d, tau_ff, alpha_To_B, beta);
    default:
      return solve<6>(model, d, tau_ff, alpha_To_B, beta);
  }
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
