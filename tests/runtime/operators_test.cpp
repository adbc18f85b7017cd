// Operators: identities (inverse, round trips, power invariance, antisymmetry)
// on random inputs and closed-form cases.
#include "runtime/operators.hpp"

#include <gtest/gtest.h>

#include <numbers>
#include <random>

#include "support/diagnostics.hpp"

namespace mospec::runtime {
namespace {

constexpr double kPi = std::numbers::pi;

class Random {
 public:
  explicit Random(unsigned seed) : rng_(seed) {}
  double uniform(double lo, double hi) { return std::uniform_real_distribution<>(lo, hi)(rng_); }
  Vec3 vec3(double scale = 1.0) {
    return Vec3(uniform(-scale, scale), uniform(-scale, scale), uniform(-scale, scale));
  }
  Vec6 vec6() {
    Vec6 v;
    v << vec3(), vec3();
    return v;
  }
  Pose pose() {
    Eigen::Quaterniond q(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1), uniform(-1, 1));
    q.normalize();
    return {q.toRotationMatrix(), vec3(2.0)};
  }

 private:
  std::mt19937 rng_;
};

::testing::AssertionResult near(const auto& a, const auto& b, double tol) {
  const double d = (a - b).cwiseAbs().maxCoeff();
  if (d <= tol) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "max difference " << d << " > " << tol << "\n"
                                       << a << "\nvs\n"
                                       << b;
}
::testing::AssertionResult near(const Pose& a, const Pose& b, double tol) {
  auto r = near(a.R, b.R, tol);
  return r ? near(a.p, b.p, tol) : r;
}

Mat3 rot_z(double a) {
  return Eigen::AngleAxisd(a, Vec3::UnitZ()).toRotationMatrix();
}

TEST(ComposePose, ComposingWithTheInverseGivesTheIdentity) {
  Random rnd(1);
  for (int k = 0; k < 100; ++k) {
    const Pose X_AB = rnd.pose();
    EXPECT_TRUE(near(compose_pose(X_AB, invert_pose(X_AB)), Pose::identity(), 1e-14));
    EXPECT_TRUE(near(compose_pose(invert_pose(X_AB), X_AB), Pose::identity(), 1e-14));
  }
}

TEST(ComposePose, IsAssociativeAndActsOnPoints) {
  Random rnd(2);
  for (int k = 0; k < 100; ++k) {
    const Pose X_AB = rnd.pose(), X_BC = rnd.pose(), X_CD = rnd.pose();
    EXPECT_TRUE(near(compose_pose(compose_pose(X_AB, X_BC), X_CD),
                     compose_pose(X_AB, compose_pose(X_BC, X_CD)), 1e-13));
    const Vec3 p_CoQ_C = rnd.vec3();
    EXPECT_TRUE(
        near(compose_pose(X_AB, X_BC).apply(p_CoQ_C), X_AB.apply(X_BC.apply(p_CoQ_C)), 1e-13));
  }
}

TEST(ComposePose, ClosedForm) {
  // Shoulder 0.3 m up the platform, turned 90° about z; the end-effector 0.5 m
  // along the shoulder's x: in the platform it is 0.5 m along the platform's y.
  const Pose X_PS{rot_z(kPi / 2), Vec3(0, 0, 0.3)};
  const Pose X_SE{Mat3::Identity(), Vec3(0.5, 0, 0)};
  const Pose X_PE = compose_pose(X_PS, X_SE);
  EXPECT_TRUE(near(X_PE.p, Vec3(0, 0.5, 0.3), 1e-15));
  EXPECT_TRUE(near(X_PE.R, rot_z(kPi / 2), 1e-15));
}

TEST(Rotate, ToDistalThenToProximalIsTheIdentity) {
  Random rnd(3);
  for (int k = 0; k < 100; ++k) {
    const Pose X_AB = rnd.pose(), X = rnd.pose();
    const Vec3 d = rnd.vec3();
    const Vec6 V = rnd.vec6(), F = rnd.vec6();
    EXPECT_TRUE(
        near(rotate_direction_to_proximal(X_AB, rotate_direction_to_distal(X_AB, d)), d, 1e-14));
    EXPECT_TRUE(near(rotate_twist_to_proximal(X_AB, rotate_twist_to_distal(X_AB, V)), V, 1e-14));
    EXPECT_TRUE(near(rotate_wrench_to_distal(X_AB, rotate_wrench_to_proximal(X_AB, F)), F, 1e-14));
    EXPECT_TRUE(near(rotate_pose_to_proximal(X_AB, rotate_pose_to_distal(X_AB, X)), X, 1e-14));
  }
}

TEST(Rotate, KeepsNormsAndPowerAndCommutesWithThePose) {
  Random rnd(4);
  for (int k = 0; k < 100; ++k) {
    const Pose X_AB = rnd.pose(), X_B = rnd.pose();
    const Vec6 V = rnd.vec6(), F = rnd.vec6();
    EXPECT_NEAR(power(rotate_twist_to_proximal(X_AB, V), rotate_wrench_to_proximal(X_AB, F)),
                power(V, F), 1e-13);
    const Vec3 x = rnd.vec3();
    // Applying the rotated pose to the rotated point = rotating the moved point.
    const Pose X_A = rotate_pose_to_proximal(X_AB, X_B);
    EXPECT_TRUE(near(X_A.apply(X_AB.R * x), X_AB.R * X_B.apply(x), 1e-13));
    EXPECT_NEAR(X_A.p.norm(), X_B.p.norm(), 1e-13);
  }
}

TEST(Rotate, ClosedForm) {
  // A force along the end-effector's x, with the end-effector turned 90° about
  // the platform's z: along the platform's y; the moment likewise.
  const Pose X_PE{rot_z(kPi / 2), Vec3(1, 2, 3)};
  Vec6 F_E;
  F_E << 0, 0, 0.5, 10, 0, 0;
  Vec6 expected;
  expected << 0, 0, 0.5, 0, 10, 0;
  EXPECT_TRUE(near(rotate_wrench_to_proximal(X_PE, F_E), expected, 1e-14));
  EXPECT_TRUE(near(rotate_direction_to_proximal(X_PE, Vec3::UnitX()), Vec3::UnitY(), 1e-15));
}

TEST(Transform, RoundTripsAndPowerInvariance) {
  Random rnd(5);
  for (int k = 0; k < 100; ++k) {
    const Pose X_AB = rnd.pose();
    const Vec6 V_Bo_B = rnd.vec6(), F_Bo_B = rnd.vec6();
    const Vec6 V_Ao_A = transform_twist_to_proximal(X_AB, V_Bo_B);
    const Vec6 F_Ao_A = transform_wrench_to_proximal(X_AB, F_Bo_B);
    EXPECT_TRUE(near(transform_twist_to_distal(X_AB, V_Ao_A), V_Bo_B, 1e-13));
    EXPECT_TRUE(near(transform_wrench_to_distal(X_AB, F_Ao_A), F_Bo_B, 1e-13));
    // The power of a wrench on a twist does not depend on where or in which
    // frame both are written.
    EXPECT_NEAR(power(V_Ao_A, F_Ao_A), power(V_Bo_B, F_Bo_B), 1e-12);
    // Against the 6x6 Plücker transform of spatial.hpp.
    EXPECT_TRUE(near(motion_transform_to_child(X_AB) * V_Ao_A, V_Bo_B, 1e-13));
    EXPECT_TRUE(near(motion_transform_to_child(X_AB).transpose() * F_Bo_B, F_Ao_A, 1e-13));
  }
}

TEST(Transform, WrenchClosedForm) {
  // 10 N along the shoulder's x, measured at the shoulder, which sits 0.2 m to
  // the left (+y) of the platform origin: 10 N along x and a moment of
  // p × f = (0, 0.2, 0) × (10, 0, 0) = (0, 0, -2) N·m about the platform origin.
  const Pose X_PS{Mat3::Identity(), Vec3(0, 0.2, 0)};
  Vec6 F_So_S;
  F_So_S << 0, 0, 0, 10, 0, 0;
  Vec6 expected;
  expected << 0, 0, -2, 10, 0, 0;
  EXPECT_TRUE(near(transform_wrench_to_proximal(X_PS, F_So_S), expected, 1e-15));
}

TEST(PoseToDistanceAndDirection, ClosedFormAndDegenerate) {
  const Pose X_SE{rot_z(0.3), Vec3(0.3, 0.4, 0)};
  EXPECT_DOUBLE_EQ(pose_to_linear_distance(X_SE), 0.5);
  Vec3 d;
  ASSERT_TRUE(pose_to_direction(X_SE, d));
  EXPECT_TRUE(near(d, Vec3(0.6, 0.8, 0), 1e-15));
  // The distance is frame-invariant: the same from the other side.
  EXPECT_NEAR(pose_to_linear_distance(invert_pose(X_SE)), 0.5, 1e-15);
  EXPECT_FALSE(pose_to_direction(Pose::identity(), d));
  EXPECT_EQ(d, Vec3::Zero());
}

TEST(WrenchFromPositionDirectionAndMagnitude, IsEquationOne) {
  // 5 N along z applied 0.5 m along x of the measurement point: moment
  // r × f = (0.5, 0, 0) × (0, 0, 5) = (0, -2.5, 0).
  Vec6 expected;
  expected << 0, -2.5, 0, 0, 0, 5;
  EXPECT_TRUE(near(wrench_from_position_direction_and_magnitude(Vec3(0.5, 0, 0), Vec3::UnitZ(), 5),
                   expected, 1e-15));
  // Moving the measurement point to the application point removes the moment;
  // linear in the magnitude.
  Random rnd(6);
  for (int k = 0; k < 50; ++k) {
    const Vec3 p_BoC = rnd.vec3(), d = rnd.vec3().normalized();
    const double f = rnd.uniform(-20, 20);
    const Vec6 F_Bo = wrench_from_position_direction_and_magnitude(p_BoC, d, f);
    const Pose X_BC{Mat3::Identity(), p_BoC};
    const Vec6 F_Co = transform_wrench_to_distal(X_BC, F_Bo);
    EXPECT_TRUE(near(F_Co.head<3>(), Vec3::Zero(), 1e-13));
    EXPECT_TRUE(near(F_Co.tail<3>(), f * d, 1e-13));
    EXPECT_TRUE(
        near(wrench_from_position_direction_and_magnitude(p_BoC, d, 2 * f), 2 * F_Bo, 1e-13));
  }
}

TEST(PoseToAngleAroundAxis, IsTheRotationAngleAboutThatAxis) {
  const Vec3 z = Vec3::UnitZ();
  for (double a : {0.0, 0.7, -2.5, kPi}) {
    EXPECT_NEAR(pose_to_angle_around_axis({rot_z(a), Vec3(1, 2, 3)}, z), a, 1e-12) << a;
  }
  // Beyond pi it wraps to (-pi, pi]; the axis' length does not matter.
  EXPECT_NEAR(pose_to_angle_around_axis({rot_z(3.5), Vec3::Zero()}, 2.0 * z), 3.5 - 2 * kPi, 1e-12);
  // About the opposite axis the angle changes sign.
  EXPECT_NEAR(pose_to_angle_around_axis({rot_z(0.4), Vec3::Zero()}, -z), -0.4, 1e-12);
  // A rotation about an orthogonal axis does not turn about z.
  const Mat3 R_x = Eigen::AngleAxisd(0.9, Vec3::UnitX()).toRotationMatrix();
  EXPECT_NEAR(pose_to_angle_around_axis({R_x, Vec3::Zero()}, z), 0.0, 1e-12);
  // The twist part: Rz(a) Rx(b) turns by a about z, whatever b.
  EXPECT_NEAR(pose_to_angle_around_axis({rot_z(0.6) * R_x, Vec3::Zero()}, z), 0.6, 1e-12);
  // A zero axis has no angle (0, not NaN).
  EXPECT_EQ(pose_to_angle_around_axis({rot_z(0.6), Vec3::Zero()}, Vec3::Zero()), 0.0);
}

TEST(WrenchAndTwistAlgebra, AddInvertAssign) {
  Random r(7);
  const Vec6 F1 = r.vec6(), F2 = r.vec6();
  EXPECT_EQ(add_wrench(F1, F2), F1 + F2);
  EXPECT_EQ(invert_wrench(F1), -F1);
  EXPECT_EQ(assign_wrench(F1), F1);
  EXPECT_EQ(add_velocity_twist(F1, F2), F1 + F2);
  // Power balance: the reaction does the opposite power on any twist.
  const Vec6 V = r.vec6();
  EXPECT_DOUBLE_EQ(power(V, invert_wrench(F1)), -power(V, F1));
}

// InertialWrench is V x* (M V). Checked against the 6x6 form (the spatial
// force cross product times spatial_inertia), and on two bodies whose answer
// is known without algebra.
TEST(InertialWrench, IsTheVelocityProductOfNewtonEuler) {
  Random r(11);
  for (int k = 0; k < 50; ++k) {
    const double m = r.uniform(0.1, 5.0);
    const Vec3 c = r.vec3(0.3);
    const Vec3 d(r.uniform(0.01, 0.1), r.uniform(0.01, 0.1), r.uniform(0.01, 0.1));
    const Mat3 I_cm = d.asDiagonal();
    const Mat6 I6 = spatial_inertia(m, c, I_cm);
    RigidBodyInertia M;
    M.m = m;
    M.h = m * c;
    M.I = I6.topLeftCorner<3, 3>();
    const Vec6 V = r.vec6();
    Mat6 crf = Mat6::Zero();  // V x*: [[w]x, [v]x; 0, [w]x]
    crf.topLeftCorner<3, 3>() = skew(V.head<3>());
    crf.topRightCorner<3, 3>() = skew(V.tail<3>());
    crf.bottomRightCorner<3, 3>() = skew(V.head<3>());
    EXPECT_LT((inertial_wrench(M, V) - crf * (I6 * V)).norm(), 1e-12);
  }
  // A body spinning about a principal axis through its centre of mass needs
  // no wrench to keep spinning.
  RigidBodyInertia top;
  top.m = 2.0;
  top.I = Vec3(0.1, 0.1, 0.3).asDiagonal();
  Vec6 spin;
  spin << 0, 0, 5.0, 0, 0, 0;
  EXPECT_LT(inertial_wrench(top, spin).norm(), 1e-15);
  // A point mass m at c, swung about the z axis through the reference point
  // at rate w: the force that keeps it on its circle is centripetal,
  // -m w^2 c, with the moment c x f = 0 about the axis point.
  const double mass = 3.0, w = 2.0;
  const Vec3 at(0.5, 0.0, 0.0);
  RigidBodyInertia point;
  point.m = mass;
  point.h = mass * at;
  point.I = mass * skew(at) * skew(at).transpose();
  Vec6 swing;
  swing << 0, 0, w, 0, 0, 0;
  const Vec6 F = inertial_wrench(point, swing);
  EXPECT_LT((F.tail<3>() - (-mass * w * w * at)).norm(), 1e-12);
  EXPECT_LT(F.head<3>().norm(), 1e-12);
}

TEST(PlanarAngle, IsSignedAboutTheNormal) {
  double a = 0;
  ASSERT_TRUE(planar_angle_from_directions(Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ(), a));
  EXPECT_NEAR(a, kPi / 2, 1e-15);
  ASSERT_TRUE(planar_angle_from_directions(Vec3::UnitY(), Vec3::UnitX(), Vec3::UnitZ(), a));
  EXPECT_NEAR(a, -kPi / 2, 1e-15);
  ASSERT_TRUE(planar_angle_from_directions(Vec3::UnitX(), Vec3::UnitY(), -Vec3::UnitZ(), a));
  EXPECT_NEAR(a, -kPi / 2, 1e-15);
  // 150° and -150°: a cosine (the authors' dot product) cannot tell them apart.
  const Vec3 d(std::cos(5 * kPi / 6), std::sin(5 * kPi / 6), 0);
  ASSERT_TRUE(planar_angle_from_directions(Vec3::UnitX(), d, Vec3::UnitZ(), a));
  EXPECT_NEAR(a, 5 * kPi / 6, 1e-14);
  ASSERT_TRUE(planar_angle_from_directions(d, Vec3::UnitX(), Vec3::UnitZ(), a));
  EXPECT_NEAR(a, -5 * kPi / 6, 1e-14);
  // Components along the normal do not matter; lengths do not matter.
  ASSERT_TRUE(planar_angle_from_directions(Vec3(2, 0, 5), Vec3(0, 0.1, -3), Vec3::UnitZ(), a));
  EXPECT_NEAR(a, kPi / 2, 1e-15);
}

TEST(PlanarAngle, AntisymmetryAndRotationOnRandomInputs) {
  Random rnd(7);
  for (int k = 0; k < 200; ++k) {
    const Vec3 n = rnd.vec3().normalized();
    const Vec3 d1 = rnd.vec3();
    const double theta = rnd.uniform(-3.1, 3.1);
    // d2 = d1's in-plane part rotated by theta about n.
    const Vec3 d1p = d1 - d1.dot(n) * n;
    const Vec3 d2 = Eigen::AngleAxisd(theta, n) * d1p + rnd.uniform(-1, 1) * n;
    double a12 = 0, a21 = 0, a_flipped = 0;
    ASSERT_TRUE(planar_angle_from_directions(d1, d2, n, a12));
    ASSERT_TRUE(planar_angle_from_directions(d2, d1, n, a21));
    ASSERT_TRUE(planar_angle_from_directions(d1, d2, -n, a_flipped));
    EXPECT_NEAR(a12, theta, 1e-12);
    EXPECT_NEAR(a21, -a12, 1e-12);
    EXPECT_NEAR(a_flipped, -a12, 1e-12);
    EXPECT_NEAR(invert_angle(a12), a21, 1e-12);
  }
}

TEST(PlanarAngle, UndefinedWhenADirectionIsAlongTheNormal) {
  double a = 1;
  EXPECT_FALSE(planar_angle_from_directions(Vec3::UnitZ(), Vec3::UnitX(), Vec3::UnitZ(), a));
  EXPECT_EQ(a, 0.0);
  EXPECT_FALSE(planar_angle_from_directions(Vec3::UnitX(), Vec3::UnitY(), Vec3::Zero(), a));
}

TEST(WrapAngle, IsInHalfOpenInterval) {
  EXPECT_DOUBLE_EQ(wrap_angle(kPi), kPi);
  EXPECT_DOUBLE_EQ(wrap_angle(-kPi), kPi);
  EXPECT_NEAR(wrap_angle(3 * kPi / 2), -kPi / 2, 1e-15);
  EXPECT_NEAR(wrap_angle(-7.0), -7.0 + 2 * kPi, 1e-15);
}

TEST(AddWrench, AddsAndChecksFramesAtSetup) {
  const AddWrench add({"platform-origin", "platform"}, {"platform-origin", "platform"});
  EXPECT_EQ(add.output_frames(), (WrenchFrames{"platform-origin", "platform"}));
  Vec6 a, b;
  a << 1, 2, 3, 4, 5, 6;
  b << -1, 0, 1, 0, 1, 0;
  EXPECT_EQ(add(a, b), a + b);
  try {
    AddWrench({"right-shoulder", "platform"}, {"platform-origin", "platform"});
    FAIL() << "expected a frame mismatch";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), "frame-mismatch");
    EXPECT_EQ(e.diagnostic().message,
              "AddWrench: the inputs must share reference point and frame; in1 is about "
              "'right-shoulder' seen by 'platform', in2 about 'platform-origin' seen by "
              "'platform' (transform one of them first, e.g. TransformWrenchToProximal)");
  }
  EXPECT_THROW(AddWrench({"o", "a"}, {"o", "b"}), Error);
}

TEST(Distances, PointLinePlaneClosedForms) {
  const Line x_axis{Vec3::Zero(), Vec3(2, 0, 0)};
  const Plane ground{Vec3(0, 0, 1), Vec3(0, 0, 3)};  // z = 1, normal up
  EXPECT_DOUBLE_EQ(point_point_distance(Vec3(1, 2, 3), Vec3(1, 2, 5)), 2.0);
  EXPECT_NEAR(point_line_distance(Vec3(5, 3, 4), x_axis), 5.0, 1e-15);
  EXPECT_NEAR(point_plane_distance(Vec3(7, 7, 4), ground), 3.0, 1e-15);
  EXPECT_NEAR(point_plane_distance(Vec3(7, 7, -1), ground), -2.0, 1e-15);
  // Skew lines: the x axis and a line along y through (0, 0, 2): 2 apart.
  const Line skew{Vec3(0, 0, 2), Vec3(0, 1, 0)};
  EXPECT_NEAR(line_line_distance(x_axis, skew), 2.0, 1e-15);
  EXPECT_NEAR(line_line_distance(skew, x_axis), 2.0, 1e-15);
  // Parallel lines fall back to the point-line distance.
  EXPECT_NEAR(line_line_distance(x_axis, Line{Vec3(3, 0, 4), Vec3(-1, 0, 0)}), 4.0, 1e-15);
  // Intersecting lines.
  EXPECT_NEAR(line_line_distance(x_axis, Line{Vec3(1, 1, 0), Vec3(0, 1, 0)}), 0.0, 1e-15);
  EXPECT_NEAR(line_plane_distance(x_axis, ground), -1.0, 1e-15);
  EXPECT_EQ(line_plane_distance(skew, Plane{Vec3::Zero(), Vec3(0, 1, 1)}), 0.0);
  EXPECT_NEAR(plane_plane_distance(ground, Plane{Vec3(5, 5, 4), Vec3(0, 0, -1)}), 3.0, 1e-15);
  EXPECT_EQ(plane_plane_distance(ground, Plane{Vec3::Zero(), Vec3(1, 0, 0)}), 0.0);
}

TEST(Distances, AnglesClosedForms) {
  EXPECT_NEAR(line_line_angle(Line{Vec3::Zero(), Vec3(1, 0, 0)}, Line{Vec3::Ones(), Vec3(1, 1, 0)}),
              kPi / 4, 1e-15);
  EXPECT_NEAR(
      line_line_angle(Line{Vec3::Zero(), Vec3(1, 0, 0)}, Line{Vec3::Ones(), Vec3(-1, 0, 0)}), kPi,
      1e-15);
  const Plane ground{Vec3::Zero(), Vec3::UnitZ()};
  EXPECT_NEAR(line_plane_angle(Line{Vec3::Zero(), Vec3(1, 0, 1)}, ground), kPi / 4, 1e-15);
  EXPECT_NEAR(line_plane_angle(Line{Vec3::Zero(), Vec3(1, 0, -1)}, ground), -kPi / 4, 1e-15);
  EXPECT_NEAR(line_plane_angle(Line{Vec3::Zero(), Vec3(1, 1, 0)}, ground), 0.0, 1e-15);
  EXPECT_NEAR(plane_plane_angle(ground, Plane{Vec3::Zero(), Vec3(0, 1, 1)}), kPi / 4, 1e-15);
  // Tiny angles are accurate (atan2, not acos).
  EXPECT_NEAR(angle_between(Vec3::UnitX(), Vec3(1, 1e-9, 0)), 1e-9, 1e-22);
}

TEST(Distances, InvariantUnderRigidMotion) {
  Random rnd(8);
  for (int k = 0; k < 50; ++k) {
    const Pose X = rnd.pose();
    const Line l1{rnd.vec3(), rnd.vec3()}, l2{rnd.vec3(), rnd.vec3()};
    const Line m1{X.apply(l1.point), X.R * l1.direction}, m2{X.apply(l2.point), X.R * l2.direction};
    EXPECT_NEAR(line_line_distance(l1, l2), line_line_distance(m1, m2), 1e-12);
    EXPECT_NEAR(line_line_angle(l1, l2), line_line_angle(m1, m2), 1e-12);
    const Vec3 p = rnd.vec3();
    EXPECT_NEAR(point_line_distance(p, l1), point_line_distance(X.apply(p), m1), 1e-12);
  }
}

TEST(Views, PickOneComponent) {
  Vec6 F;
  F << 1, 2, 3, 4, 5, 6;  // [n; f]
  EXPECT_EQ(view(F, {Part::Angular, Axis::X}), 1);
  EXPECT_EQ(view(F, {Part::Angular, Axis::Z}), 3);
  EXPECT_EQ(view(F, {Part::Linear, Axis::X}), 4);
  EXPECT_EQ(view(F, {Part::Linear, Axis::Z}), 6);
  EXPECT_NEAR(view_along(F, Part::Linear, Vec3(0, 0.6, 0.8)), 0.6 * 5 + 0.8 * 6, 1e-15);
  const Pose X{Eigen::AngleAxisd(0.4, Vec3::UnitY()).toRotationMatrix(), Vec3(7, 8, 9)};
  EXPECT_EQ(view(X, {Part::Linear, Axis::Y}), 8);
  EXPECT_NEAR(view(X, {Part::Angular, Axis::Y}), 0.4, 1e-15);
  EXPECT_NEAR(view(X, {Part::Angular, Axis::X}), 0.0, 1e-15);
  const Pose Y{Eigen::AngleAxisd(-2.5, Vec3::UnitZ()).toRotationMatrix(), Vec3::Zero()};
  EXPECT_NEAR(view(Y, {Part::Angular, Axis::Z}), -2.5, 1e-14);
  EXPECT_TRUE(near(rotation_vector(Mat3::Identity()), Vec3::Zero(), 0.0));
}

}  // namespace
}  // namespace mospec::runtime
