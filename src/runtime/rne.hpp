// Inverse dynamics by the recursive Newton-Euler algorithm.
#pragma once

#include "runtime/model.hpp"

namespace mospec::runtime {

// The joint forces that give the chain the accelerations qdd at state (q, qd)
// under gravity model.g_B and the external wrenches F_ext:
//   tau = H(q) qdd + C(q, qd) qd + g(q) - sum_i J_i^T F_ext[i] (+ armature qdd).
// \param q, qd, qdd  dim model.nq.
// \param F_ext  empty, or model.nq wrenches: F_ext[i] is applied ON segment i by
//               its environment, moment about So_i, expressed in the root B
//               (angular first), as achd() takes them.
// \return the status; the result is data.tau.
// \note gravity compensation is rne(q, 0, 0, {}).
Status rne(const AchdModel& model, AchdData& data, const JointIn& q, const JointIn& qd,
           const JointIn& qdd, SegmentWrenches F_ext) noexcept;

namespace impl {
// rne() writing into `tau` (dim model.nq); with qdd == nullptr, qdd = 0.
// Sizes are the caller's responsibility.
void rne_into(const AchdModel& model, AchdData& data, const JointIn& q, const JointIn& qd,
              const JointIn* qdd, SegmentWrenches F_ext, JointVector& tau) noexcept;
}  // namespace impl

}  // namespace mospec::runtime
