// Forward position kinematics and the tip Jacobian of a chain.
#pragma once

#include "runtime/model.hpp"

namespace mospec::runtime {

// Poses of every segment and of the tip for joint positions q (dim model.nq).
// \return Status::SizeMismatch (nothing written) or Ok; the results are
// data.X_PS, data.X_BS and data.X_BT.
Status forward_kinematics(const AchdModel& model, AchdData& data, const JointIn& q) noexcept;

// The geometric Jacobian of the tip: [ω_BT; v_BTo]_B = J_To_B qd, angular rows
// first, the linear rows the velocity of the tip origin To, both expressed in
// the root frame B (dim 6 x model.nq). Also runs forward_kinematics.
// \return the status; the result is data.J_To_B.
Status tip_jacobian(const AchdModel& model, AchdData& data, const JointIn& q) noexcept;

}  // namespace mospec::runtime
