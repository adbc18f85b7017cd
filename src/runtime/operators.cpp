#include "runtime/operators.hpp"

#include <Eigen/Geometry>
#include <algorithm>

#include "support/diagnostics.hpp"

namespace mospec::runtime {

bool planar_angle_from_directions(const Vec3& d1, const Vec3& d2, const Vec3& n,
                                  double& angle) noexcept {
  const double nn = n.norm();
  if (!(nn > 0.0)) {
    angle = 0.0;
    return false;
  }
  const Vec3 u = n / nn;
  // Projections onto the plane orthogonal to u; their cross product is along u,
  // so u · (d1⊥ × d2⊥) = u · (d1 × d2).
  const Vec3 a = d1 - d1.dot(u) * u;
  const Vec3 b = d2 - d2.dot(u) * u;
  const double scale = std::max(d1.norm(), d2.norm());
  constexpr double kParallel = 1e-12;  // relative: a projection this short has no direction
  if (!(a.norm() > kParallel * scale) || !(b.norm() > kParallel * scale)) {
    angle = 0.0;
    return false;
  }
  angle = std::atan2(u.dot(a.cross(b)), a.dot(b));
  return true;
}

double pose_to_angle_around_axis(const Pose& X_AB, const Vec3& a) noexcept {
  const double n = a.norm();
  if (!(n > 0.0)) return 0.0;
  const Eigen::Quaterniond q(X_AB.R);
  const double angle = 2.0 * std::atan2(q.vec().dot(a) / n, q.w());
  return wrap_angle(angle);
}

AddWrench::AddWrench(const WrenchFrames& in1, const WrenchFrames& in2) : out_(in1) {
  if (!(in1 == in2)) {
    throw Error("frame-mismatch",
                "AddWrench: the inputs must share reference point and frame; in1 is about '" +
                    in1.reference_point + "' seen by '" + in1.as_seen_by + "', in2 about '" +
                    in2.reference_point + "' seen by '" + in2.as_seen_by +
                    "' (transform one of them first, e.g. TransformWrenchToProximal)");
  }
}

double point_line_distance(const Vec3& p, const Line& l) noexcept {
  return (p - l.point).cross(l.direction).norm() / l.direction.norm();
}

double point_plane_distance(const Vec3& p, const Plane& s) noexcept {
  return s.normal.dot(p - s.point) / s.normal.norm();
}

namespace {
// |u × v| below this fraction of |u||v| counts as parallel (about 1e-9 rad).
constexpr double kParallelSine = 1e-9;
}  // namespace

double line_line_distance(const Line& l1, const Line& l2) noexcept {
  const Vec3 c = l1.direction.cross(l2.direction);
  const double cn = c.norm();
  if (!(cn > kParallelSine * l1.direction.norm() * l2.direction.norm())) {
    return point_line_distance(l2.point, l1);
  }
  return std::abs((l2.point - l1.point).dot(c)) / cn;
}

double line_plane_distance(const Line& l, const Plane& s) noexcept {
  const double sine = std::abs(l.direction.dot(s.normal)) / (l.direction.norm() * s.normal.norm());
  return sine > kParallelSine ? 0.0 : point_plane_distance(l.point, s);
}

double plane_plane_distance(const Plane& s1, const Plane& s2) noexcept {
  const double sine = s1.normal.cross(s2.normal).norm() / (s1.normal.norm() * s2.normal.norm());
  return sine > kParallelSine ? 0.0 : point_plane_distance(s2.point, s1);
}

Vec3 rotation_vector(const Mat3& R) noexcept {
  const Eigen::AngleAxisd aa(R);
  return aa.angle() * aa.axis();
}

double view(const Pose& X_AB, View v) noexcept {
  const int k = static_cast<int>(v.axis);
  if (v.part == Part::Linear) return X_AB.p[k];
  return rotation_vector(X_AB.R)[k];
}

}  // namespace mospec::runtime
