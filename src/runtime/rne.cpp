#include "runtime/rne.hpp"

namespace mospec::runtime {

namespace impl {

void rne_into(const AchdModel& model, AchdData& data, const JointIn& q, const JointIn& qd,
              const JointIn* qdd, SegmentWrenches F_ext, JointVector& tau) noexcept {
  const int n = model.nq;
  // Gravity as a root acceleration of -g: every body then feels its weight
  // through the inertial term I a, with no per-body gravity wrench.
  Vec6 a_P;
  a_P << Vec3::Zero(), -model.g_B;
  Vec6 V_P = Vec6::Zero();
  Pose X_BP;
  for (int i = 0; i < n; ++i) {
    const auto k = static_cast<std::size_t>(i);
    const SegmentModel& s = model.segments[k];
    const Pose X_PS = segment_pose(s, q[i]);
    data.X_PS[k] = X_PS;
    data.X_BS[k] = X_BP * X_PS;
    const Vec6 S = motion_subspace(s);
    const Vec6 vJ = S * qd[i];
    data.V[k] = motion_to_child(X_PS, V_P) + vJ;
    data.c[k] = cross_motion(data.V[k], vJ);
    data.a[k] = motion_to_child(X_PS, a_P) + data.c[k];
    if (qdd != nullptr) data.a[k] += S * (*qdd)[i];
    const Vec6 IV = s.I_So_S * data.V[k];
    data.f[k].noalias() = s.I_So_S * data.a[k];
    data.f[k] += cross_force(data.V[k], IV);
    if (!F_ext.empty()) {
      const Mat3& R_BS = data.X_BS[k].R;
      data.f[k].head<3>().noalias() -= R_BS.transpose() * F_ext[k].head<3>();
      data.f[k].tail<3>().noalias() -= R_BS.transpose() * F_ext[k].tail<3>();
    }
    V_P = data.V[k];
    a_P = data.a[k];
    X_BP = data.X_BS[k];
  }
  data.X_BT = X_BP * model.X_NT;
  for (int i = n - 1; i >= 0; --i) {
    const auto k = static_cast<std::size_t>(i);
    const SegmentModel& s = model.segments[k];
    tau[i] = motion_subspace(s).dot(data.f[k]);
    if (qdd != nullptr) tau[i] += s.armature * (*qdd)[i];
    if (i > 0) data.f[k - 1] += force_to_parent(data.X_PS[k], data.f[k]);
  }
}

}  // namespace impl

Status rne(const AchdModel& model, AchdData& data, const JointIn& q, const JointIn& qd,
           const JointIn& qdd, SegmentWrenches F_ext) noexcept {
  const int n = model.nq;
  if (data.nq != n || q.size() != n || qd.size() != n || qdd.size() != n ||
      (!F_ext.empty() && static_cast<int>(F_ext.size()) != n)) {
    return Status::SizeMismatch;
  }
  impl::rne_into(model, data, q, qd, &qdd, F_ext, data.tau);
  return Status::Ok;
}

}  // namespace mospec::runtime
