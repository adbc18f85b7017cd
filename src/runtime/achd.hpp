// Acceleration-constrained hybrid dynamics (ACHD): the Popov-Vereshchagin
// solver that the paper (Sec. III-B) runs for each arm.
//
// Given the state (q, qd) and three kinds of motion drivers
//   - feed-forward joint forces tau_ff,
//   - external wrenches F_ext on any segment,
//   - nc <= 6 acceleration constraints on the tip frame T:  alpha^T A_T = beta,
// it finds the motion that Gauss' principle of least constraint selects: the
// joint accelerations qdd closest (in the kinetic metric) to the free motion
// under gravity, tau_ff and F_ext that satisfies the constraints; with nc = 0 it
// is the articulated-body forward dynamics. Three O(n) sweeps plus one nc x nc
// solve, as in Vereshchagin (1989) and KDL's ChainHdSolver_Vereshchagin.
//
// Conventions (exact):
//   alpha_To_B  6 x nc. Column k is a unit constraint wrench [n; f] (angular
//               first) acting at the tip origin To, expressed in the root frame B.
//               (KDL's alpha has the same meaning but is linear first.)
//   beta        nc. The constraint is  alpha^T A_T = beta  where A_T = [ω̇; a_To]
//               is the tip's *physical* spatial acceleration relative to the
//               (inertial) root, at To, in B: gravity is NOT in it. Internally
//               gravity is a root acceleration -g_B (KDL's trick), which adds
//               alpha_f^T(-g_B) to the constrained quantity; the solver adds that
//               offset itself, so beta_KDL = beta - alpha_f^T g_B, where alpha_f
//               are alpha's force (lower three) rows. A_T is the spatial
//               (Featherstone) acceleration: its linear part is the derivative
//               of the velocity field at the point To, related to the classical
//               acceleration of the tip origin by  p̈_To = a_To + ω × v_To.
//   F_ext       empty, or nq wrenches: F_ext[i] acts ON segment i (from its
//               environment), moment about the segment origin So_i, expressed in
//               B, angular first — KDL's Vereshchagin convention but about So_i
//               (the child link's frame) rather than KDL's segment tip.
//   nu          nc constraint force magnitudes, KDL's sign: the constraint exerts
//               the wrench  -alpha nu  on the tip (at To, in B). Equivalently the
//               tip pushes on the constraint with +alpha nu.
//   tau         the joint forces a real robot must apply for qdd to happen
//               without the (virtual) constraint:
//                 tau = tau_ff - J_To_B^T (alpha nu),
//               with J_To_B as in kinematics.hpp (angular rows first). Hence
//               rne(q, qd, qdd, F_ext) == tau: the torque command to send.
//               (KDL's "constraint_torques" output is a different quantity: the
//               projection of the articulated-body-propagated constraint force,
//               which includes inertial coupling; it is not J^T alpha nu.)
#pragma once

#include "runtime/model.hpp"

namespace mospec::runtime {

// Solves the ACHD problem. Allocation-free and noexcept.
// \param q, qd, tau_ff  dim model.nq.
// \param F_ext          empty or model.nq wrenches (see above).
// \param alpha_To_B     6 x nc, nc <= kMaxConstraints (nc = 0: forward dynamics).
// \param beta           dim nc.
// \return Status::Ok; ConstraintsDegraded when the constraint coupling matrix
//         M_0 is singular in this configuration: the Cholesky factorisation of
//         -M_0 fails or its diagonal spans more than a factor 1e6 (a condition
//         number beyond about 1e12); then the directions whose eigenvalue is
//         below 1e-12 of the largest are dropped (minimum-norm nu). (At the
//         UR5e's wrist singularity that flags |q5| below about 1e-9 rad:
//         docs/models.md, wrist-singularity.) Or SizeMismatch (nothing written).
// Results: data.qdd (dim nq), data.nu (dim nc), data.tau (dim nq); also every
// segment's pose data.X_BS, data.X_BT, twist data.V and acceleration data.a
// (which includes the root acceleration -g_B).
Status achd(const AchdModel& model, AchdData& data, const JointIn& q, const JointIn& qd,
            const JointIn& tau_ff, SegmentWrenches F_ext, const ConstraintsIn& alpha_To_B,
            const ConstraintValuesIn& beta) noexcept;

// Setup-time argument check for achd(): throws mospec::Error naming the first
// argument whose size is wrong ("expected N, got M") or whose entries are not
// finite. The tick path calls achd() directly and reads its Status.
void check_achd_arguments(const AchdModel& model, const JointIn& q, const JointIn& qd,
                          const JointIn& tau_ff, SegmentWrenches F_ext,
                          const ConstraintsIn& alpha_To_B, const ConstraintValuesIn& beta);

}  // namespace mospec::runtime
