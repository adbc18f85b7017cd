// Spatial algebra for the runtime: the one place that fixes layouts and frames.
//
// Units are SI throughout (m, kg, s, rad, N, N·m).
//
// Layout: every 6-vector is ANGULAR FIRST.
//   - a motion vector (twist, spatial acceleration) is [ω; v_Po], the angular
//     velocity and the velocity of the body point that coincides with the
//     reference point Po;
//   - a force vector (wrench) is [n_Po; f], the moment about Po and the force.
// This is Featherstone's and Drake's order. KDL's alpha matrix is linear first
// and KDL's Twist/Wrench types keep (vel, rot) / (force, torque): tests convert
// in one helper, never in the algorithms.
//
// Names follow monogram notation: X_AB is the pose of frame B in frame A
// (R_AB rotates B-coordinates into A-coordinates, p_AoBo_A is B's origin seen
// from A's origin, in A-coordinates); V_AB is B's twist relative to A; F_Bo_A
// is a wrench whose moment is taken about Bo, expressed in A.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <span>

namespace mospec::runtime {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Vec6 = Eigen::Matrix<double, 6, 1>;
using Mat6 = Eigen::Matrix<double, 6, 6>;

// A rigid transform X_AB without the 4x4 overhead: R = R_AB, p = p_AoBo_A.
struct Pose {
  Mat3 R = Mat3::Identity();
  Vec3 p = Vec3::Zero();

  static Pose identity() { return {}; }
  // X_AB * X_BC = X_AC.
  Pose operator*(const Pose& X_BC) const { return {R * X_BC.R, p + R * X_BC.p}; }
  // X_AB.inverse() = X_BA.
  Pose inverse() const { return {R.transpose(), -(R.transpose() * p)}; }
  // p_AoQ_A from p_BoQ_B.
  Vec3 apply(const Vec3& p_BoQ_B) const { return p + R * p_BoQ_B; }
};

// A rigid body's inertia about a reference point Po, seen by a frame A
// (Featherstone's ten parameters): the mass m, the first moment of mass
// h = m p_PoBcm_A, and the rotational inertia I_Po_A about Po (not about the
// centre of mass). Angular first, its spatial inertia is [I_Po, [h]x; [h]x^T, m 1].
struct RigidBodyInertia {
  double m = 0.0;
  Vec3 h = Vec3::Zero();
  Mat3 I = Mat3::Zero();
};

// From the IR's ten values: m; h; Ixx, Iyy, Izz, Ixy, Ixz, Iyz (the tensor's
// entries, as URDF writes them: I = [Ixx Ixy Ixz; Ixy Iyy Iyz; Ixz Iyz Izz]).
inline RigidBodyInertia rigid_body_inertia(std::span<const double, 10> v) {
  RigidBodyInertia M;
  M.m = v[0];
  M.h = Vec3(v[1], v[2], v[3]);
  M.I << v[4], v[7], v[8], v[7], v[5], v[9], v[8], v[9], v[6];
  return M;
}

inline Mat3 skew(const Vec3& w) {
  Mat3 S;
  S << 0.0, -w.z(), w.y(), w.z(), 0.0, -w.x(), -w.y(), w.x(), 0.0;
  return S;
}

// Motion vector expressed in A at Ao -> expressed in B at Bo, for X_AB.
// ω_B = R^T ω,  v_Bo = R^T (v_Ao + ω × p_AoBo).
inline Vec6 motion_to_child(const Pose& X_AB, const Vec6& m_A) {
  Vec6 out;
  out.head<3>().noalias() = X_AB.R.transpose() * m_A.head<3>();
  out.tail<3>().noalias() = X_AB.R.transpose() * (m_A.tail<3>() + m_A.head<3>().cross(X_AB.p));
  return out;
}

// Force vector expressed in B at Bo -> expressed in A at Ao, for X_AB.
// f_A = R f_B,  n_Ao = R n_Bo + p_AoBo × f_A.
inline Vec6 force_to_parent(const Pose& X_AB, const Vec6& f_B) {
  Vec6 out;
  out.tail<3>().noalias() = X_AB.R * f_B.tail<3>();
  out.head<3>().noalias() = X_AB.R * f_B.head<3>();
  out.head<3>() += X_AB.p.cross(out.tail<3>());
  return out;
}

// The 6x6 Plücker transform that maps motion vectors from A to B (for X_AB):
// [R^T, 0; -R^T [p]x, R^T]. Its transpose maps force vectors from B to A.
inline Mat6 motion_transform_to_child(const Pose& X_AB) {
  Mat6 X;
  const Mat3 Rt = X_AB.R.transpose();
  X.topLeftCorner<3, 3>() = Rt;
  X.topRightCorner<3, 3>().setZero();
  X.bottomLeftCorner<3, 3>().noalias() = -Rt * skew(X_AB.p);
  X.bottomRightCorner<3, 3>() = Rt;
  return X;
}

// A spatial inertia (rigid or articulated, symmetric) about So in S, moved to
// about Po in P for X_PS: X^T I X with X the motion transform P -> S. Done on
// 3x3 blocks because the 6x6 congruence costs twice as much. With
// I = [A, B; B^T, C] rotated into P (A', B', C') and Px = [p_PoSo]x:
// [A' + Px B'^T - B' Px - Px C' Px,  B' + Px C';  (B' + Px C')^T,  C'].
inline void add_inertia_to_parent(const Pose& X_PS, const Mat6& I_S, Mat6& I_P) {
  const Mat3& R = X_PS.R;
  const Mat3 A = R * I_S.topLeftCorner<3, 3>() * R.transpose();
  const Mat3 B = R * I_S.topRightCorner<3, 3>() * R.transpose();
  const Mat3 C = R * I_S.bottomRightCorner<3, 3>() * R.transpose();
  const Vec3& p = X_PS.p;
  // [p]x M and M [p]x column/row-wise as cross products (cheaper than 3x3 products).
  Mat3 PC, PBt;
  for (int c = 0; c < 3; ++c) {
    PC.col(c) = p.cross(C.col(c));
    PBt.col(c) = p.cross(B.row(c).transpose());
  }
  const Mat3 B_P = B + PC;
  Mat3 PCP;  // ([p]x C) [p]x: row r is -(p x row_r)^T
  for (int r = 0; r < 3; ++r) PCP.row(r) = -p.cross(PC.row(r).transpose()).transpose();
  I_P.topLeftCorner<3, 3>() += A + PBt + PBt.transpose() - PCP;
  I_P.topRightCorner<3, 3>() += B_P;
  I_P.bottomLeftCorner<3, 3>() += B_P.transpose();
  I_P.bottomRightCorner<3, 3>() += C;
}

// Spatial cross products: m ×m x (motion on motion) and m ×f f (motion on force).
inline Vec6 cross_motion(const Vec6& m, const Vec6& x) {
  Vec6 out;
  out.head<3>() = m.head<3>().cross(x.head<3>());
  out.tail<3>() = m.head<3>().cross(x.tail<3>()) + m.tail<3>().cross(x.head<3>());
  return out;
}
inline Vec6 cross_force(const Vec6& m, const Vec6& f) {
  Vec6 out;
  out.head<3>() = m.head<3>().cross(f.head<3>()) + m.tail<3>().cross(f.tail<3>());
  out.tail<3>() = m.head<3>().cross(f.tail<3>());
  return out;
}

// Rigid-body spatial inertia about the frame origin So, in S: mass, CoM
// p_SoScm_S and rotational inertia about the CoM I_Scm_S (angular first):
// [I_Scm + m [c]x [c]x^T, m [c]x; m [c]x^T, m 1].
inline Mat6 spatial_inertia(double mass, const Vec3& p_SoScm_S, const Mat3& I_Scm_S) {
  Mat6 I;
  const Mat3 cx = skew(p_SoScm_S);
  I.topLeftCorner<3, 3>() = I_Scm_S + mass * cx * cx.transpose();
  I.topRightCorner<3, 3>() = mass * cx;
  I.bottomLeftCorner<3, 3>() = mass * cx.transpose();
  I.bottomRightCorner<3, 3>() = mass * Mat3::Identity();
  return I;
}

}  // namespace mospec::runtime
