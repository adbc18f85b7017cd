// Model/Data split for the runtime's chain algorithms (Pinocchio's shape).
//
// AchdModel is the constant description the algorithms read: per-segment joint
// placement, axis and spatial inertia (precomputed from a Chain), the tip
// offset and gravity. It is built once at setup and never changes.
//
// AchdData is the workspace: every intermediate and every result, in fixed-size
// Eigen types whose capacity is the compile-time kMaxSegments / kMaxConstraints,
// so no algorithm ever allocates. One Data serves every algorithm of
// src/runtime (achd, rne, forward kinematics, Jacobian, mass matrix, forward
// dynamics); each writes its results into named fields and returns a status.
// A Data is made for one Model (same nq); the algorithms check it.
#pragma once

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <array>
#include <cmath>
#include <span>
#include <string_view>

#include "runtime/chain.hpp"
#include "runtime/spatial.hpp"

namespace mospec::runtime {

inline constexpr int kMaxConstraints = 6;

// Joint-space vectors and matrices with a fixed maximum size.
using JointVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxJoints, 1>;
using JointMatrix =
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxJoints, kMaxJoints>;
// 6 x nc unit constraint wrenches (angular first) and nc-vectors.
using ConstraintMatrix = Eigen::Matrix<double, 6, Eigen::Dynamic, 0, 6, kMaxConstraints>;
using ConstraintVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxConstraints, 1>;
using ConstraintSquare =
    Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxConstraints, kMaxConstraints>;
// 6 x nq Jacobian (angular rows first).
using Jacobian = Eigen::Matrix<double, 6, Eigen::Dynamic, 0, 6, kMaxJoints>;

// Inputs are taken by Eigen::Ref so any contiguous vector binds without a copy.
using JointIn = Eigen::Ref<const Eigen::VectorXd>;
using ConstraintsIn = Eigen::Ref<const Eigen::Matrix<double, 6, Eigen::Dynamic>>;
using ConstraintValuesIn = Eigen::Ref<const Eigen::VectorXd>;
// One wrench per segment (nq of them), or an empty span for "no external forces".
using SegmentWrenches = std::span<const Vec6>;

// KDL's solver convention, kept: 0 ok, > 0 usable but degraded, < 0 failed
// (outputs untouched).
enum class Status : int {
  Ok = 0,
  // The constraint coupling matrix was (near) singular: the constraint
  // directions lost in this configuration were dropped (minimum-norm ν) and the
  // remaining ones are met.
  ConstraintsDegraded = 1,
  SizeMismatch = -1,  // an argument's size differs from the model's
};
std::string_view to_string(Status);

struct SegmentModel {
  JointType type = JointType::Revolute;
  Pose X_PJ;                   // joint frame in the parent segment frame (or root B)
  Vec3 axis = Vec3::UnitZ();   // unit, in J and S
  Mat6 I_So_S = Mat6::Zero();  // spatial inertia about So, in S
  double armature = 0.0;
  int unit_axis = -1;  // 0, 1, 2 when axis is +x, +y, +z exactly (a cheaper rotation)
};

class AchdModel {
 public:
  // g_B: gravitational acceleration in the root frame B [m/s^2]. Gravity enters
  // the algorithms as a root acceleration of -g_B (the usual trick); see achd.hpp
  // for how that keeps beta physical.
  explicit AchdModel(const Chain& chain, const Vec3& g_B = Vec3(0.0, 0.0, -9.81));

  int nq = 0;
  std::array<SegmentModel, kMaxSegments> segments{};
  Pose X_NT;  // tip frame T in the last segment frame N
  Vec3 g_B = Vec3::Zero();
};

// The pose X_PS(q) of segment S in its parent P.
inline Pose segment_pose(const SegmentModel& s, double q) {
  if (s.type == JointType::Revolute) {
    if (s.unit_axis >= 0) {
      // R_PJ Rot(e_k, q): columns k+1 and k+2 of R_PJ turn in their plane.
      const int a = (s.unit_axis + 1) % 3, b = (s.unit_axis + 2) % 3;
      const double c = std::cos(q), sn = std::sin(q);
      Pose X{s.X_PJ.R, s.X_PJ.p};
      X.R.col(a) = c * s.X_PJ.R.col(a) + sn * s.X_PJ.R.col(b);
      X.R.col(b) = c * s.X_PJ.R.col(b) - sn * s.X_PJ.R.col(a);
      return X;
    }
    return {s.X_PJ.R * Eigen::AngleAxisd(q, s.axis).toRotationMatrix(), s.X_PJ.p};
  }
  return {s.X_PJ.R, s.X_PJ.p + s.X_PJ.R * (s.axis * q)};
}

// The joint's motion subspace S (unit twist of S relative to P, in S at So).
inline Vec6 motion_subspace(const SegmentModel& s) {
  Vec6 S;
  if (s.type == JointType::Revolute) {
    S << s.axis, Vec3::Zero();
  } else {
    S << Vec3::Zero(), s.axis;
  }
  return S;
}

struct AchdData {
  explicit AchdData(const AchdModel& model);

  int nq = 0;

  // Kinematics (forward_kinematics, and every dynamics pass).
  std::array<Pose, kMaxSegments> X_PS{};  // segment i in its parent
  std::array<Pose, kMaxSegments> X_BS{};  // segment i in the root B
  Pose X_BT;                              // tip T in the root B
  Jacobian J_To_B;                        // tip Jacobian: qd -> [ω_BT; v_BTo] expressed in B

  // Per-segment recursion quantities, all in S_i at So_i.
  std::array<Vec6, kMaxSegments> V{};   // twist of S_i (relative to B)
  std::array<Vec6, kMaxSegments> c{};   // velocity-product acceleration V ×m S qd
  std::array<Vec6, kMaxSegments> a{};   // spatial acceleration, including -g
  std::array<Vec6, kMaxSegments> f{};   // RNE: wrench transmitted across joint i
  std::array<Mat6, kMaxSegments> IA{};  // articulated-body inertia
  std::array<Vec6, kMaxSegments> pA{};  // articulated bias force
  std::array<Vec6, kMaxSegments> U{};   // IA S
  std::array<double, kMaxSegments> D{};
  std::array<double, kMaxSegments> u{};
  std::array<ConstraintMatrix, kMaxSegments> E{};   // constraint wrenches seen at S_i
  std::array<ConstraintVector, kMaxSegments> EZ{};  // E_i^T S_i
  ConstraintMatrix E_base;                          // ... propagated into B
  ConstraintMatrix alpha_No_N;                      // alpha moved to the last segment
  ConstraintSquare M;                               // constraint coupling, M_0
  ConstraintVector G;                               // bias acceleration energy, G_0
  ConstraintVector rhs;
  Eigen::SelfAdjointEigenSolver<ConstraintSquare> eig_M;  // fallback when singular

  // Results.
  JointVector qdd;      // achd, forward_dynamics
  JointVector tau;      // rne; achd: the torque that realises its qdd
  ConstraintVector nu;  // achd: constraint force magnitudes
  JointMatrix H;        // mass_matrix
  JointVector bias;     // forward_dynamics: rne(q, qd, 0, F_ext)
  Eigen::LLT<JointMatrix> llt_H;
};

}  // namespace mospec::runtime
