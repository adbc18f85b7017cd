// The KELO mobile base (paper Sec. III-C): n drives (the paper's base has
// four; 2 <= n <= kMaxKeloDrives), each a pair of
// hub-driven wheels (a differential drive) on a passive pivot joint whose axis
// is displaced from the wheel axle by a castor offset. Each drive can push its
// pivot point in any planar direction; the platform wrench is distributed over
// the drives by weighted least squares (Eq. 2-3), and wheel rates are composed
// into a platform twist.
//
// Frames (SI units; all planar vectors lie in the horizontal plane):
//   P    the platform frame: origin Po at the platform centre, x forward,
//        y left, z up.
//   D_i  drive i's pivot frame: origin on its pivot axis at p_PoAi_P, z up, x
//        along the drive's rolling (longitudinal) direction, y lateral (left).
//        q_i, the pivot angle, is the angle from x_P to x_Di about +z
//        (counter-clockwise seen from above): R_PDi = Rot_z(q_i). A pivot
//        encoder that counts the other way is negated at the robot interface.
//   The wheel axle's midpoint trails the pivot axis by the castor offset s:
//   it is at (-s, 0) in D_i. The LEFT wheel (+y_Di) and the RIGHT wheel
//   (-y_Di) touch the ground at (-s, ±d/2), where d = wheel_distance is the
//   distance BETWEEN the two wheels (each is d/2 from the drive's mid-plane).
//   (hddc2b's drive functions use its 0.0775 m "wheel distance" the same way:
//   as the full separation.)
//
// Layouts (the paper's and hddc2b's order, LINEAR FIRST — unlike the
// angular-first 6-vectors of spatial.hpp; planar_wrench()/spatial_twist() are
// the one place that converts):
//   F_p  = [f_x, f_y, m_z]      platform wrench: force on the platform and its
//                               moment about Po, seen by P [N, N, N·m];
//   xd_p = [v_x, v_y, ω_z]      platform twist: velocity of Po and angular
//                               velocity, relative to the ground, seen by P;
//   F_d  = [f_1x, f_1y, …, f_nx, f_ny]  the force drive i exerts on the
//                               platform at its pivot point, seen by D_i [N];
//   wheel quantities = [1 left, 1 right, 2 left, …]: traction force f (the
//   ground's force on the wheel along +x_Di), hub torque τ = r f, wheel rate ω
//   (positive rolling forward, +x_Di) [N, N·m, rad/s]. Motors mounted mirrored
//   are sign-flipped at the robot interface, not here.
//
// Drive model (massless drives, rolling without lateral slip): with r the
// wheel radius, the pivot force and the wheel forces are related by
//   f_x = f_l + f_r,    f_y = (d / 2s) (f_r - f_l)
// (the passive pivot carries no torque, so the differential traction's moment
// about the pivot, (d/2)(f_r - f_l), is balanced by a lateral ground force at
// the axle, s f_y); and the pivot point's velocity seen by D_i is
//   v_x = r (ω_l + ω_r) / 2,   v_y = s r (ω_r - ω_l) / d.
// The two maps are power-consistent: f_x v_x + f_y v_y = τ_l ω_l + τ_r ω_r.
//
// Force composition: F_p = G(q) F_d with drive i's 3x2 block
//   G_i = [R(q_i); p_i × R(q_i)]  =  [ c   -s ;  s   c ;  x s - y c   x c + y s ]
// (c = cos q_i, s = sin q_i, (x, y) = p_PoAi_P). The pivot velocities are
// u = G^T xd_p (the pivot point moves with the platform).
//
// Distribution (Eq. 2-3): F_d minimises ½ |F_d - F̄_d|²_W subject to
// G F_d = F_p. With the drive weights w_i on the diagonal of W^{-1} (both
// components of drive i; w_i = 0 DISABLES drive i: it gets zero force),
//   G⁺ = W^{-1} G^T (G W^{-1} G^T)^{-1},    N = I - G⁺ G,
//   F_d = G⁺ F_p + α N F̄_d.
// (The paper prints N = I - G⁺; the projector needs the G.) A disabled drive's
// reference is ignored. α recovers the magnitude of the greatest reference
// drive force after projection: α = max_i |F̄_d,i| / max_i |(N F̄_d)_i| over
// the enabled drives (0 when the projection leaves less than 1e-9 of it).
//
// Alignment reference (the two competing tasks of Sec. III-C, as in hddc2b's
// pivot "alignment distance"): for drive i, the signed angles (wrapped to
// (-π, π]) from x_Di to the direction that best serves
//   - the platform force: along (f_x, f_y);
//   - the platform moment: tangential at p_i, sign(m_z) ẑ × p_i / |p_i|;
// weighted by the magnitude each task asks of the drive and by dimensionless
// per-drive task weights, give a LATERAL reference force
//   F̄_d,i = [0,  w_f,i |f_xy| Δθ_f,i + w_m,i (|m_z| / |p_i|) Δθ_m,i]  [N].
// A lateral pivot force is a differential wheel torque, i.e. a torque s f_y
// about the pivot that turns x_Di towards the task direction (Δθ > 0 turns
// it counter-clockwise); it vanishes once the drive is aligned. (hddc2b
// multiplies the signed moment by the angle to the counter-clockwise tangent,
// which for a negative moment is largest, not zero, at the best alignment;
// here the target flips with the moment's sign.)
//
// Velocity composition: the platform twist is the least-squares solution of
// G^T xd_p = u with the same weights (disabled drives are ignored):
//   xd_p = (G W^{-1} G^T)^{-1} G W^{-1} u = G⁺^T u,
// so that xd_p · F_p = u · F_d for any consistent u (u = G^T xd_p).
//
// Model/Data: KeloModel is constant (geometry and weights, checked at setup);
// KeloData holds every per-tick quantity. All per-tick functions are noexcept
// and allocation-free; each writes named fields of KeloData and returns a
// reference to its main result.
#pragma once

#include <Eigen/Cholesky>
#include <array>
#include <vector>

#include "runtime/spatial.hpp"

namespace mospec::runtime {

// The most drives a base may have: the workspace's fixed capacity.
inline constexpr int kMaxKeloDrives = 8;

using Vec2 = Eigen::Vector2d;
using Vec4 = Eigen::Vector4d;
// Sized by the model's drive count n, within fixed capacities (no allocation).
using KeloPivotVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxKeloDrives, 1>;  // n
using KeloDriveVector =
    Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 2 * kMaxKeloDrives, 1>;  // 2n: F_d, wheels
using KeloComposition =
    Eigen::Matrix<double, 3, Eigen::Dynamic, 0, 3, 2 * kMaxKeloDrives>;  // G, 3 x 2n
using KeloDistribution =
    Eigen::Matrix<double, Eigen::Dynamic, 3, 0, 2 * kMaxKeloDrives, 3>;  // G⁺, 2n x 3
using KeloProjector = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 2 * kMaxKeloDrives,
                                    2 * kMaxKeloDrives>;  // N, 2n x 2n

struct KeloGeometry {
  std::vector<Vec2> p_PoAi_P;   // pivot axis of drive i, seen by P [m]; one per drive
  double wheel_radius = 0.0;    // r [m]
  double wheel_distance = 0.0;  // d: between the two wheels of a drive [m]
  double castor_offset = 0.0;   // s: pivot axis to wheel axle [m]
  // No numbers here: a base's geometry and weights are model data, read from
  // the robot description a platform solver's `configuration` names
  // (description/base_rdf.hpp; the paper's base is robots/kelo-base.jsonld).
};

struct KeloConfig {
  KeloGeometry geometry;
  // One per drive. Diagonal of W^{-1} per drive (>= 0; 0 disables the drive).
  // At least two drives at distinct pivot positions must be enabled.
  std::vector<double> drive_weight;
  // Alignment task weights (dimensionless, >= 0): force task and moment task.
  std::vector<double> align_force_weight;
  std::vector<double> align_moment_weight;
  // Scale the projected reference by α (the paper); false: α = 1.
  bool rescale_reference = true;
};

class KeloModel {
 public:
  // Throws mospec::Error("invalid-kelo") naming the offending drive/field:
  // a drive count outside [2, kMaxKeloDrives] or weights not one per drive,
  // non-finite positions, wheel radius/distance/castor offset <= 0, negative
  // or non-finite weights, fewer than two enabled drives at distinct
  // positions, or a moment-alignment weight on a drive at the platform centre.
  explicit KeloModel(const KeloConfig& config);

  KeloConfig config;
  int drives = 0;              // n
  double wheel_radius = 0.0;   // r
  double lateral_ratio = 0.0;  // d / (2 s): f_y = lateral_ratio (f_r - f_l)
  KeloDriveVector w_inv;       // diagonal of W^{-1} (each weight twice)
  std::array<bool, kMaxKeloDrives> enabled{};
};

struct KeloData {
  explicit KeloData(const KeloModel& model);

  // Every vector below is sized for the model's n drives here, once.

  // kelo_set_pivots
  KeloPivotVector q_pivot;    // [rad]
  KeloComposition G;          // F_p = G F_d
  Eigen::LLT<Mat3> llt_GWGt;  // G W^{-1} G^T, factorised
  KeloDistribution G_pinv;    // G⁺ = W^{-1} G^T (G W^{-1} G^T)^{-1}

  // kelo_alignment_reference
  KeloDriveVector F_d_ref;  // F̄_d, seen by each D_i [N]

  // kelo_distribute
  KeloDriveVector ref;       // F̄_d of the enabled drives (a workspace)
  KeloDriveVector F_d_null;  // N F̄_d (before α)
  double alpha = 0.0;
  KeloDriveVector F_d;  // the distributed drive forces [N]

  // kelo_force_step: the last tick's inputs were not finite (zero command).
  bool input_fault = false;

  // kelo_hub_torques
  KeloDriveVector f_wheel;    // traction forces [N]
  KeloDriveVector tau_wheel;  // hub torques [N·m]

  // kelo_platform_twist / kelo_wheel_rates
  KeloDriveVector u_pivot;          // pivot velocities, seen by D_i [m/s]
  Vec3 xd_platform = Vec3::Zero();  // [v_x, v_y, ω_z]
  KeloDriveVector wheel_rates;      // [rad/s]
  KeloPivotVector qd_pivot;         // pivot rates that go with wheel_rates [rad/s]
};

// The platform wrench [f_x, f_y, m_z] of a spatial wrench F_Po_P (angular
// first, moment about Po, seen by P): its projection on the horizontal plane.
inline Vec3 planar_wrench(const Vec6& F_Po_P) noexcept {
  return {F_Po_P[3], F_Po_P[4], F_Po_P[2]};
}
// The spatial twist (angular first, at Po, seen by P) of a planar twist.
inline Vec6 spatial_twist(const Vec3& xd_p) noexcept {
  Vec6 V;
  V << 0.0, 0.0, xd_p[2], xd_p[0], xd_p[1], 0.0;
  return V;
}

// G(q) and its weighted pseudo-inverse for the pivot angles q_pivot [rad].
// \return data.G. Call once per tick before the functions below.
// q_pivot has one angle per drive.
const KeloComposition& kelo_set_pivots(const KeloModel& model, KeloData& data,
                                       const KeloPivotVector& q_pivot) noexcept;

// The alignment reference F̄_d for the platform wrench F_p = [f_x, f_y, m_z].
// \return data.F_d_ref (zero for disabled drives).
const KeloDriveVector& kelo_alignment_reference(const KeloModel& model, KeloData& data,
                                                const Vec3& F_p) noexcept;

// Eq. (3): F_d = G⁺ F_p + α N F̄_d. Also writes data.F_d_null and data.alpha.
// \return data.F_d.
const KeloDriveVector& kelo_distribute(const KeloModel& model, KeloData& data, const Vec3& F_p,
                                       const KeloDriveVector& F_d_ref) noexcept;

// Drive forces (data.F_d) -> wheel traction forces and hub torques.
// \return data.tau_wheel.
const KeloDriveVector& kelo_hub_torques(const KeloModel& model, KeloData& data) noexcept;

// The whole force path of one tick: set_pivots, alignment reference,
// distribute, hub torques. A non-finite pivot angle or platform wrench sets
// data.input_fault and commands zero drive forces and hub torques for this
// tick (the base stops pushing) instead of NaN; the next valid tick clears it.
// \return data.tau_wheel.
const KeloDriveVector& kelo_force_step(const KeloModel& model, KeloData& data,
                                       const KeloPivotVector& q_pivot, const Vec3& F_p) noexcept;

// Wheel rates -> pivot velocities (data.u_pivot) -> platform twist by weighted
// least squares, at the pivot angles of the last kelo_set_pivots.
// \return data.xd_platform.
const Vec3& kelo_platform_twist(const KeloModel& model, KeloData& data,
                                const KeloDriveVector& wheel_rates) noexcept;

// The inverse (for simulation and tests): the wheel rates and pivot rates that
// realise the platform twist xd_p at the current pivot angles (rolling, no
// slip). \return data.wheel_rates; data.qd_pivot and data.u_pivot are set too.
const KeloDriveVector& kelo_wheel_rates(const KeloModel& model, KeloData& data,
                                        const Vec3& xd_p) noexcept;

// N = I - G⁺ G at the current pivot angles (2n x 2n; for analysis and tests — the
// tick never forms it).
KeloProjector kelo_nullspace_projector(const KeloData& data) noexcept;

}  // namespace mospec::runtime
