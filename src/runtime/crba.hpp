// Joint-space mass matrix (composite rigid body algorithm) and forward
// dynamics through it. Both are reference algorithms for setup and checks; the
// control tick uses achd(), which is O(n) and needs no factorisation.
#pragma once

#include "runtime/model.hpp"

namespace mospec::runtime {

// The symmetric joint-space inertia matrix H(q) (dim model.nq^2), including
// the joints' armature on the diagonal.
// \return the status; the result is data.H (both triangles filled).
Status mass_matrix(const AchdModel& model, AchdData& data, const JointIn& q) noexcept;

// The accelerations qdd = H^-1 (tau - rne(q, qd, 0, F_ext)) under gravity and
// the external wrenches F_ext (same convention as rne()).
// \return the status; the result is data.qdd (data.H and data.bias are
// overwritten on the way).
Status forward_dynamics(const AchdModel& model, AchdData& data, const JointIn& q, const JointIn& qd,
                        const JointIn& tau, SegmentWrenches F_ext) noexcept;

}  // namespace mospec::runtime
