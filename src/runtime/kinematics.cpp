#include "runtime/kinematics.hpp"

namespace mospec::runtime {

Status forward_kinematics(const AchdModel& model, AchdData& data, const JointIn& q) noexcept {
  const int n = model.nq;
  if (data.nq != n || q.size() != n) return Status::SizeMismatch;
  Pose X_BP;  // the parent of segment i in B; B itself for i = 0
  for (int i = 0; i < n; ++i) {
    const auto k = static_cast<std::size_t>(i);
    data.X_PS[k] = segment_pose(model.segments[k], q[i]);
    data.X_BS[k] = X_BP * data.X_PS[k];
    X_BP = data.X_BS[k];
  }
  data.X_BT = X_BP * model.X_NT;
  return Status::Ok;
}

Status tip_jacobian(const AchdModel& model, AchdData& data, const JointIn& q) noexcept {
  const Status s = forward_kinematics(model, data, q);
  if (s != Status::Ok) return s;
  const Vec3& p_BTo = data.X_BT.p;
  for (int i = 0; i < model.nq; ++i) {
    const auto k = static_cast<std::size_t>(i);
    const Vec3 axis_B = data.X_BS[k].R * model.segments[k].axis;
    if (model.segments[k].type == JointType::Revolute) {
      data.J_To_B.col(i) << axis_B, axis_B.cross(p_BTo - data.X_BS[k].p);
    } else {
      data.J_To_B.col(i) << Vec3::Zero(), axis_B;
    }
  }
  return Status::Ok;
}

}  // namespace mospec::runtime
