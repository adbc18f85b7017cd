#include "runtime/crba.hpp"

#include "runtime/rne.hpp"

namespace mospec::runtime {

namespace {

void crba_into(const AchdModel& model, AchdData& data, const JointIn& q) noexcept {
  const int n = model.nq;
  for (int i = 0; i < n; ++i) {
    const auto k = static_cast<std::size_t>(i);
    data.X_PS[k] = segment_pose(model.segments[k], q[i]);
    data.IA[k] = model.segments[k].I_So_S;  // becomes the composite inertia
  }
  for (int i = n - 1; i > 0; --i) {
    const auto k = static_cast<std::size_t>(i);
    add_inertia_to_parent(data.X_PS[k], data.IA[k], data.IA[k - 1]);
  }
  for (int i = 0; i < n; ++i) {
    const auto k = static_cast<std::size_t>(i);
    Vec6 F = data.IA[k] * motion_subspace(model.segments[k]);
    data.H(i, i) = motion_subspace(model.segments[k]).dot(F) + model.segments[k].armature;
    for (int j = i; j > 0; --j) {
      const auto kj = static_cast<std::size_t>(j);
      F = force_to_parent(data.X_PS[kj], F);
      data.H(i, j - 1) = data.H(j - 1, i) = motion_subspace(model.segments[kj - 1]).dot(F);
    }
  }
}

}  // namespace

Status mass_matrix(const AchdModel& model, AchdData& data, const JointIn& q) noexcept {
  if (data.nq != model.nq || q.size() != model.nq) return Status::SizeMismatch;
  crba_into(model, data, q);
  return Status::Ok;
}

Status forward_dynamics(const AchdModel& model, AchdData& data, const JointIn& q, const JointIn& qd,
                        const JointIn& tau, SegmentWrenches F_ext) noexcept {
  const int n = model.nq;
  if (data.nq != n || q.size() != n || qd.size() != n || tau.size() != n ||
      (!F_ext.empty() && static_cast<int>(F_ext.size()) != n)) {
    return Status::SizeMismatch;
  }
  impl::rne_into(model, data, q, qd, nullptr, F_ext, data.bias);
  crba_into(model, data, q);
  data.llt_H.compute(data.H);
  // tau may alias data.tau but not data.qdd, so one expression is safe.
  data.qdd = tau - data.bias;
  data.llt_H.solveInPlace(data.qdd);
  return Status::Ok;
}

}  // namespace mospec::runtime
