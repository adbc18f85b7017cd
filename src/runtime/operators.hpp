// Operators: the paper's maps between 3D Cartesian quantities and 1D task
// quantities (Sec. II-C), plus the pose, twist and wrench algebra the authors'
// models use (ComposePose, Rotate...ToProximalWithPose, TransformWrenchToProximal,
// PoseToLinearDistance, PoseToDirection, PlanarAngleFromDirections, InvertAngle,
// AddWrench, WrenchFromPositionDirectionAndMagnitude) and passive views.
//
// Units are SI (m, rad, s, N, N·m); layouts and names are those of
// runtime/spatial.hpp: 6-vectors are ANGULAR FIRST (twist [ω; v_Po], wrench
// [n_Po; f]) and names are monograms. Every operator states its frame
// convention as four parts:
//   of            the body/frame whose quantity it is (pose of B, twist of B);
//   w.r.t.        the body/frame it is relative to (pose/twist relative to A);
//   ref. point    the point a twist's linear part or a wrench's moment is taken at;
//   as seen by    the frame whose coordinates express the vector.
// "Proximal" and "distal" are the two frames of a pose X_AB: A is proximal, B
// distal (for a kinematic chain, A is nearer the root).
//
// Every function here is noexcept and allocation-free; operators that can be
// undefined for their input (a direction of a zero vector, an angle between
// vectors without a component in the plane) return false and write a defined
// value (zero) instead of NaN. Checks that need the frames of their inputs
// (AddWrench) are made once, at setup, by constructing the operator.
#pragma once

#include <cmath>
#include <numbers>
#include <string>

#include "runtime/spatial.hpp"

namespace mospec::runtime {

// ---------------------------------------------------------------------------
// Poses

// ComposePose: X_AC = X_AB * X_BC.
//   in1 = pose of B w.r.t. A (as seen by A); in2 = pose of C w.r.t. B (as seen
//   by B); composite = pose of C w.r.t. A, as seen by A.
inline Pose compose_pose(const Pose& X_AB, const Pose& X_BC) noexcept {
  return X_AB * X_BC;
}

// The pose of A w.r.t. B from the pose of B w.r.t. A.
inline Pose invert_pose(const Pose& X_AB) noexcept {
  return X_AB.inverse();
}

// PoseToLinearDistance: |p_AoBo|, the distance between the origins of A and B.
// Frame-invariant (a distance references no frame).
inline double pose_to_linear_distance(const Pose& X_AB) noexcept {
  return X_AB.p.norm();
}

// PoseToDirection: the unit vector from Ao towards Bo, as seen by A
// (d_AoBo_A = p_AoBo_A / |p_AoBo_A|).
// \return false (and d = 0) when the origins coincide (|p| <= min_distance).
inline bool pose_to_direction(const Pose& X_AB, Vec3& d_AoBo_A,
                              double min_distance = 1e-12) noexcept {
  const double n = X_AB.p.norm();
  if (!(n > min_distance)) {
    d_AoBo_A.setZero();
    return false;
  }
  d_AoBo_A = X_AB.p / n;
  return true;
}

// ---------------------------------------------------------------------------
// Change of coordinates only ("rotate"): the quantity, its w.r.t. body and its
// reference point stay the same; only the frame it is seen by changes. With
// X_AB (pose of distal B w.r.t. proximal A):
//   ...ToProximal: as seen by B -> as seen by A (multiply by R_AB);
//   ...ToDistal:   as seen by A -> as seen by B (multiply by R_AB^T).

// RotateDirectionDistalToProximalWithPose: d_A = R_AB d_B (also for any free
// vector: a position difference, a linear or angular velocity, a force).
inline Vec3 rotate_direction_to_proximal(const Pose& X_AB, const Vec3& d_B) noexcept {
  return X_AB.R * d_B;
}
inline Vec3 rotate_direction_to_distal(const Pose& X_AB, const Vec3& d_A) noexcept {
  return X_AB.R.transpose() * d_A;
}

// RotateVelocityTwistToProximalWithPose: V_XY at point Q, seen by B -> the same
// twist at the same point Q, seen by A: [R ω; R v_Q].
inline Vec6 rotate_twist_to_proximal(const Pose& X_AB, const Vec6& V_B) noexcept {
  Vec6 out;
  out.head<3>().noalias() = X_AB.R * V_B.head<3>();
  out.tail<3>().noalias() = X_AB.R * V_B.tail<3>();
  return out;
}
inline Vec6 rotate_twist_to_distal(const Pose& X_AB, const Vec6& V_A) noexcept {
  Vec6 out;
  out.head<3>().noalias() = X_AB.R.transpose() * V_A.head<3>();
  out.tail<3>().noalias() = X_AB.R.transpose() * V_A.tail<3>();
  return out;
}

// RotateWrenchToProximalWithPose: F at point Q, seen by B -> the same wrench at
// the same point Q, seen by A: [R n_Q; R f]. (Same arithmetic as a twist; kept
// separate so the call says what it moves.)
inline Vec6 rotate_wrench_to_proximal(const Pose& X_AB, const Vec6& F_B) noexcept {
  return rotate_twist_to_proximal(X_AB, F_B);
}
inline Vec6 rotate_wrench_to_distal(const Pose& X_AB, const Vec6& F_A) noexcept {
  return rotate_twist_to_distal(X_AB, F_A);
}

// Rotating a pose: the relative pose X_CD (of D w.r.t. C) whose rotation
// operator and translation are written in B coordinates is re-expressed in A
// coordinates: the translation is rotated (p_A = R_AB p_B) and the rotation
// operator is conjugated (R_A = R_AB R_B R_AB^T). Then, for any vector x,
// R_A (R_AB x) = R_AB (R_B x): rotating commutes with applying the pose.
inline Pose rotate_pose_to_proximal(const Pose& X_AB, const Pose& X_B) noexcept {
  return {X_AB.R * X_B.R * X_AB.R.transpose(), X_AB.R * X_B.p};
}
inline Pose rotate_pose_to_distal(const Pose& X_AB, const Pose& X_A) noexcept {
  return {X_AB.R.transpose() * X_A.R * X_AB.R, X_AB.R.transpose() * X_A.p};
}

// ---------------------------------------------------------------------------
// Change of reference point and coordinates ("transform").

// TransformWrenchToProximal: F_Bo_B (moment about Bo, seen by B) ->
// F_Ao_A (moment about Ao, seen by A): f_A = R f_B, n_Ao = R n_Bo + p_AoBo_A × f_A.
inline Vec6 transform_wrench_to_proximal(const Pose& X_AB, const Vec6& F_Bo_B) noexcept {
  return force_to_parent(X_AB, F_Bo_B);
}
// The inverse: F_Ao_A -> F_Bo_B.
inline Vec6 transform_wrench_to_distal(const Pose& X_AB, const Vec6& F_Ao_A) noexcept {
  Vec6 out;
  const Vec3 n_Bo_A = F_Ao_A.head<3>() - X_AB.p.cross(F_Ao_A.tail<3>());
  out.head<3>().noalias() = X_AB.R.transpose() * n_Bo_A;
  out.tail<3>().noalias() = X_AB.R.transpose() * F_Ao_A.tail<3>();
  return out;
}

// Twist of some body w.r.t. some other, at point Ao seen by A -> at Bo seen by B:
// ω_B = R^T ω, v_Bo = R^T (v_Ao + ω × p_AoBo_A).
inline Vec6 transform_twist_to_distal(const Pose& X_AB, const Vec6& V_Ao_A) noexcept {
  return motion_to_child(X_AB, V_Ao_A);
}
// The inverse: at Bo seen by B -> at Ao seen by A: ω_A = R ω_B,
// v_Ao = R v_Bo - ω_A × p_AoBo_A.
inline Vec6 transform_twist_to_proximal(const Pose& X_AB, const Vec6& V_Bo_B) noexcept {
  Vec6 out;
  out.head<3>().noalias() = X_AB.R * V_Bo_B.head<3>();
  out.tail<3>().noalias() = X_AB.R * V_Bo_B.tail<3>();
  out.tail<3>() -= out.head<3>().cross(X_AB.p);
  return out;
}

// Power of a wrench on a twist (both at the same point, seen by the same
// frame): V · F = ω · n + v · f [W]. Invariant under every transform above.
inline double power(const Vec6& V, const Vec6& F) noexcept {
  return V.dot(F);
}

// ---------------------------------------------------------------------------
// 1D -> 3D

// WrenchFromPositionDirectionAndMagnitude, the paper's Eq. (1):
//   F_Bo_A = [ p_BoC_A × (f d_A) ; f d_A ]
// the wrench measured at point Bo and seen by A of a force of magnitude f [N]
// along the unit direction d_A applied at point C, with p_BoC_A the position of
// C relative to Bo seen by A. d_A is used as given (PoseToDirection makes it
// unit length).
inline Vec6 wrench_from_position_direction_and_magnitude(const Vec3& p_BoC_A, const Vec3& d_A,
                                                         double f) noexcept {
  Vec6 F;
  F.tail<3>() = f * d_A;
  F.head<3>() = p_BoC_A.cross(F.tail<3>());
  return F;
}

// ---------------------------------------------------------------------------
// Angles

// Wraps an angle to (-pi, pi].
inline double wrap_angle(double a) noexcept {
  const double w = std::remainder(a, 2.0 * std::numbers::pi);  // [-pi, pi]
  return w == -std::numbers::pi ? std::numbers::pi : w;
}

// PlanarAngleFromDirections: the SIGNED angle (-pi, pi] that rotates direction
// d1 onto direction d2 about the plane normal n (right-hand rule about n),
// after projecting both onto the plane orthogonal to n. All three vectors must
// be seen by the same frame; none needs unit length (n must be non-zero).
//   angle = atan2(n̂ · (d1 × d2), d1⊥ · d2⊥)
// Antisymmetric: angle(d1, d2, n) = -angle(d2, d1, n) = -angle(d1, d2, -n)
// (except at exactly pi). The authors' implementation returns the dot product
// d1 · d2 (a cosine, unsigned); this returns the angle itself.
// \return false (angle = 0) when a projection vanishes (a direction parallel to
//         n, or n = 0): the angle is undefined there.
bool planar_angle_from_directions(const Vec3& d1, const Vec3& d2, const Vec3& n,
                                  double& angle) noexcept;

// InvertAngle: -angle (the same angle measured the other way round, e.g. the
// angle of the table w.r.t. the shoulders -> of the shoulders w.r.t. the table).
inline double invert_angle(double angle) noexcept {
  return -angle;
}

// PoseToAngleAroundAxis: the angle (-pi, pi] by which the pose X_AB turns
// about the unit axis a (seen by A, and by B: the twist part of the swing-twist
// decomposition of R_AB about a). For a rotation about a it is that rotation's
// angle; a rotation about an axis orthogonal to a gives 0. From the quaternion
// (w, v) of R_AB: angle = 2 atan2(v . a, w), wrapped.
double pose_to_angle_around_axis(const Pose& X_AB, const Vec3& a) noexcept;

// ---------------------------------------------------------------------------
// Wrench and twist algebra (same reference point, same frame: the registry's
// frame rules, checked when the model is lowered).

// AddWrench: F1 + F2.
inline Vec6 add_wrench(const Vec6& F1, const Vec6& F2) noexcept {
  return F1 + F2;
}
// InvertWrench: -F (the reaction: what the body exerts on its environment).
inline Vec6 invert_wrench(const Vec6& F) noexcept {
  return -F;
}
// AssignWrench: a copy of F, e.g. to name a model's wrench as a solver input.
inline Vec6 assign_wrench(const Vec6& F) noexcept {
  return F;
}
// InertialWrench: the velocity-product wrench V x* (M V) of a rigid body with
// spatial inertia M moving with twist V (both about one point, seen by one
// frame): the Coriolis and centripetal part of Newton-Euler's
// F = M A + V x* (M V). For a body spinning about a principal axis through its
// centre of mass it is zero; for a flywheel spinning off-axis it is the
// gyroscopic moment.
inline Vec6 inertial_wrench(const RigidBodyInertia& M, const Vec6& V) noexcept {
  const Vec3 w = V.head<3>(), v = V.tail<3>();
  // The momentum M V: angular L = I w + h x v, linear p = m v - h x w.
  const Vec3 L = M.I * w + M.h.cross(v);
  const Vec3 p = M.m * v - M.h.cross(w);
  Vec6 F;
  F.head<3>() = w.cross(L) + v.cross(p);
  F.tail<3>() = w.cross(p);
  return F;
}
// AddVelocityTwist: V_CA = V_BA + V_CB (twists composed along B), all three at
// one reference point and seen by one frame.
inline Vec6 add_velocity_twist(const Vec6& V_BA, const Vec6& V_CB) noexcept {
  return V_BA + V_CB;
}

// ---------------------------------------------------------------------------
// AddWrench: F1 + F2. Both wrenches must have the same reference point and be
// seen by the same frame; that is checked once, when the operator is built from
// the inputs' frame descriptions (a model-level property), never per tick.

// Setup-time description of where a wrench lives: the point its moment is
// taken about and the frame it is seen by (names from the model or the IR).
struct WrenchFrames {
  std::string reference_point;
  std::string as_seen_by;
  friend bool operator==(const WrenchFrames&, const WrenchFrames&) = default;
};

class AddWrench {
 public:
  // Throws mospec::Error("frame-mismatch") naming both inputs' reference point
  // and frame when they differ.
  AddWrench(const WrenchFrames& in1, const WrenchFrames& in2);

  // The frames of the sum (those of the inputs).
  const WrenchFrames& output_frames() const { return out_; }

  Vec6 operator()(const Vec6& F1, const Vec6& F2) const noexcept { return F1 + F2; }

 private:
  WrenchFrames out_;
};

// ---------------------------------------------------------------------------
// Linear and angular distances between points, lines and planes (Sec. II-B).
// All inputs seen by one common frame; results are frame-invariant.
// A line is a point on it and a non-zero direction; a plane is a point on it
// and a non-zero normal (neither needs unit length).

struct Line {
  Vec3 point = Vec3::Zero();
  Vec3 direction = Vec3::UnitX();
};
struct Plane {
  Vec3 point = Vec3::Zero();
  Vec3 normal = Vec3::UnitZ();
};

// |q - p|.
inline double point_point_distance(const Vec3& p, const Vec3& q) noexcept {
  return (q - p).norm();
}
// Distance from p to the line: |(p - a) × û|.
double point_line_distance(const Vec3& p, const Line& l) noexcept;
// SIGNED distance from the plane to p: n̂ · (p - a), positive on the side the
// normal points to.
double point_plane_distance(const Vec3& p, const Plane& s) noexcept;
// Shortest distance between two lines: |(a2 - a1) · (u1 × u2)| / |u1 × u2|;
// for (near) parallel lines, the distance from a2 to line 1.
double line_line_distance(const Line& l1, const Line& l2) noexcept;
// SIGNED distance of a line parallel to the plane (that of its point); 0 when
// the line intersects the plane.
double line_plane_distance(const Line& l, const Plane& s) noexcept;
// SIGNED distance of plane s2 from a parallel plane s1 (that of s2's point,
// along s1's normal); 0 when the planes intersect.
double plane_plane_distance(const Plane& s1, const Plane& s2) noexcept;

// Unsigned angle between two directions, [0, pi]: atan2(|u × v|, u · v).
inline double angle_between(const Vec3& u, const Vec3& v) noexcept {
  return std::atan2(u.cross(v).norm(), u.dot(v));
}
// Angle between two (directed) lines, [0, pi].
inline double line_line_angle(const Line& l1, const Line& l2) noexcept {
  return angle_between(l1.direction, l2.direction);
}
// SIGNED angle of a line against a plane, [-pi/2, pi/2]: positive when the
// line's direction points to the normal's side; 0 when parallel to the plane.
inline double line_plane_angle(const Line& l, const Plane& s) noexcept {
  return 0.5 * std::numbers::pi - angle_between(l.direction, s.normal);
}
// Angle between two planes (between their normals), [0, pi].
inline double plane_plane_angle(const Plane& s1, const Plane& s2) noexcept {
  return angle_between(s1.normal, s2.normal);
}

// ---------------------------------------------------------------------------
// Views: one scalar component of a 3D quantity, read in place (the paper's
// passive 3D -> 1D map). The component is taken along an axis of the frame the
// quantity is seen by; the quantity's other frame parts are unchanged.

enum class Part : int { Angular = 0, Linear = 3 };  // offset in a 6-vector
enum class Axis : int { X = 0, Y = 1, Z = 2 };

struct View {
  Part part = Part::Linear;
  Axis axis = Axis::X;
  // Index into an angular-first 6-vector.
  constexpr int index() const { return static_cast<int>(part) + static_cast<int>(axis); }
};

// A component of a twist or wrench: e.g. {Linear, Z} of F_Bo_A is f_z seen by A,
// {Angular, Z} is the moment about the z axis through Bo.
inline double view(const Vec6& twist_or_wrench, View v) noexcept {
  return twist_or_wrench[v.index()];
}
// The component along any unit axis u (seen by the quantity's frame).
inline double view_along(const Vec6& twist_or_wrench, Part part, const Vec3& u) noexcept {
  return twist_or_wrench.segment<3>(static_cast<int>(part)).dot(u);
}
// A component of a pose X_AB: Linear is p_AoBo_A along the axis [m]; Angular is
// that component of the rotation vector θ·k of R_AB (axis-angle, |θ| <= pi)
// [rad] — for a rotation about that axis alone, exactly the rotation angle.
double view(const Pose& X_AB, View v) noexcept;

// The rotation vector θ·k of R (|θ| <= pi), seen by the rotation's frame.
Vec3 rotation_vector(const Mat3& R) noexcept;

}  // namespace mospec::runtime
