// KELO base: force composition and distribution identities (G F_d = F_p,
// G N = 0, disabled drives), optimality against a direct KKT solve, power
// consistency of the force and velocity maps, alignment reference, closed forms.
#include "runtime/kelo.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <numbers>
#include <random>
#include <string>

#include "kelo_base.hpp"
#include "support/diagnostics.hpp"

namespace mospec::runtime {
namespace {

constexpr double kPi = std::numbers::pi;

::testing::AssertionResult near(const auto& a, const auto& b, double tol) {
  const double d = (a - b).cwiseAbs().maxCoeff();
  if (d <= tol) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "max difference " << d << " > " << tol << "\n"
                                       << a.transpose() << "\nvs\n"
                                       << b.transpose();
}

// The paper's base (robots/kelo-base.jsonld) has four drives.
constexpr int kKeloDrives = 4;
constexpr int kWheels = 2 * kKeloDrives;

class Random {
 public:
  explicit Random(unsigned seed) : rng_(seed) {}
  double uniform(double lo, double hi) { return std::uniform_real_distribution<>(lo, hi)(rng_); }
  Vec4 pivots() { return Vec4(angle(), angle(), angle(), angle()); }
  Vec3 wrench() { return Vec3(uniform(-200, 200), uniform(-200, 200), uniform(-50, 50)); }
  KeloDriveVector drive_vector(double scale) {
    KeloDriveVector v(kWheels);
    for (int k = 0; k < v.size(); ++k) v[k] = uniform(-scale, scale);
    return v;
  }

 private:
  double angle() { return uniform(-kPi, kPi); }
  std::mt19937 rng_;
};

// robots/kelo-base.jsonld, read by description::load_base, is the paper's
// robot with the numbers mospec's C++ had before they were model data (the
// same doubles: the radius is exactly half the former 0.115 m diameter).
TEST(KeloGeometry, PaperRobot) {
  const KeloGeometry g = ::mospec::testing::paper_base().geometry;
  EXPECT_EQ(g.p_PoAi_P[0], Vec2(0.195, 0.21));   // front-left
  EXPECT_EQ(g.p_PoAi_P[1], Vec2(-0.195, 0.21));  // rear-left
  EXPECT_EQ(g.p_PoAi_P[2], Vec2(-0.195, -0.21));
  EXPECT_EQ(g.p_PoAi_P[3], Vec2(0.195, -0.21));
  EXPECT_EQ(g.wheel_radius, 0.5 * 0.115);
  EXPECT_EQ(g.wheel_distance, 0.0775);
  EXPECT_EQ(g.castor_offset, 0.01);
  const KeloModel model(::mospec::testing::paper_base());
  EXPECT_EQ(model.wheel_radius, 0.0575);
  EXPECT_DOUBLE_EQ(model.lateral_ratio, 0.0775 / 0.02);
}

TEST(KeloComposition, ClosedFormColumns) {
  const KeloModel model(::mospec::testing::paper_base());
  KeloData data(model);
  kelo_set_pivots(model, data, Vec4(0, kPi / 2, 0, 0));
  // Drive 0 at (0.195, 0.21), aligned with x: a longitudinal force f gives
  // (f, 0) and a moment -y f; a lateral one gives (0, f) and x f.
  EXPECT_TRUE(near(data.G.col(0), Vec3(1, 0, -0.21), 1e-15));
  EXPECT_TRUE(near(data.G.col(1), Vec3(0, 1, 0.195), 1e-15));
  // Drive 1 at (-0.195, 0.21) turned to +y: longitudinal is +y, lateral -x.
  EXPECT_TRUE(near(data.G.col(2), Vec3(0, 1, -0.195), 1e-15));
  EXPECT_TRUE(near(data.G.col(3), Vec3(-1, 0, 0.21), 1e-15));
}

TEST(KeloDistribution, ReproducesThePlatformWrench) {
  Random rnd(1);
  const KeloModel model(::mospec::testing::paper_base());
  KeloData data(model);
  for (int k = 0; k < 500; ++k) {
    const Vec4 q = rnd.pivots();
    const Vec3 F_p = rnd.wrench();
    kelo_set_pivots(model, data, q);
    // With no reference, with the alignment reference, with a random one.
    kelo_distribute(model, data, F_p, KeloDriveVector::Zero(kWheels));
    ASSERT_TRUE(near(data.G * data.F_d, F_p, 1e-10));
    kelo_force_step(model, data, q, F_p);
    ASSERT_TRUE(near(data.G * data.F_d, F_p, 1e-10));
    kelo_distribute(model, data, F_p, rnd.drive_vector(100));
    ASSERT_TRUE(near(data.G * data.F_d, F_p, 1e-10));
  }
}

TEST(KeloDistribution, NullspaceProjectorProperties) {
  Random rnd(2);
  const KeloModel model(::mospec::testing::paper_base());
  KeloData data(model);
  for (int k = 0; k < 200; ++k) {
    kelo_set_pivots(model, data, rnd.pivots());
    const KeloProjector N = kelo_nullspace_projector(data);
    ASSERT_LT((data.G * N).cwiseAbs().maxCoeff(), 1e-13);
    ASSERT_LT((N * N - N).cwiseAbs().maxCoeff(), 1e-13);  // a projection
    ASSERT_LT((data.G * data.G_pinv - Mat3::Identity()).cwiseAbs().maxCoeff(), 1e-13);
    // The implicit projection in kelo_distribute equals N times the reference.
    const KeloDriveVector ref = rnd.drive_vector(10);
    kelo_distribute(model, data, Vec3::Zero(), ref);
    ASSERT_TRUE(near(data.F_d_null, N * ref, 1e-12));
  }
}

// The weighted least-squares problem of Eq. (2) solved directly (KKT system
// with W = diag(1/w)), for enabled drives only.
KeloDriveVector kkt_solution(const KeloModel& model, const KeloComposition& G, const Vec3& F_p,
                             const KeloDriveVector& F_ref) {
  std::vector<int> active;
  for (int k = 0; k < 2 * model.drives; ++k) {
    if (model.w_inv[k] > 0) active.push_back(k);
  }
  const int n = static_cast<int>(active.size());
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(n + 3, n + 3);
  Eigen::VectorXd rhs(n + 3);
  for (int a = 0; a < n; ++a) {
    K(a, a) = 1.0 / model.w_inv[active[a]];
    K.block(n, a, 3, 1) = G.col(active[a]);
    K.block(a, n, 1, 3) = G.col(active[a]).transpose();
    rhs[a] = K(a, a) * F_ref[active[a]];
  }
  rhs.tail<3>() = F_p;
  const Eigen::VectorXd x = K.fullPivLu().solve(rhs);
  KeloDriveVector F_d = KeloDriveVector::Zero(2 * model.drives);
  for (int a = 0; a < n; ++a) F_d[active[a]] = x[a];
  return F_d;
}

// Every drive count a model may give (four runs fixed-size kernels, the others
// runtime-sized ones): the distribution is Eq. (2)'s minimiser, and the
// velocity maps invert each other.
TEST(KeloDistribution, EveryDriveCountSolvesTheWeightedLeastSquaresProblem) {
  Random rnd(11);
  for (int n = 2; n <= kMaxKeloDrives; ++n) {
    SCOPED_TRACE("drives: " + std::to_string(n));
    KeloConfig config = ::mospec::testing::paper_base();
    config.geometry.p_PoAi_P.clear();
    config.drive_weight.clear();
    config.align_force_weight.assign(static_cast<size_t>(n), 1.0);
    config.align_moment_weight.assign(static_cast<size_t>(n), 1.0);
    for (int i = 0; i < n; ++i) {
      const double a = 2.0 * kPi * i / n + 0.3;
      config.geometry.p_PoAi_P.emplace_back(0.3 * std::cos(a), 0.2 * std::sin(a));
      config.drive_weight.push_back(rnd.uniform(0.2, 3.0));
    }
    config.rescale_reference = false;  // α = 1: exactly Eq. (2)'s minimiser
    const KeloModel model(config);
    KeloData data(model);
    for (int k = 0; k < 50; ++k) {
      KeloPivotVector q(n);
      for (int i = 0; i < n; ++i) q[i] = rnd.uniform(-kPi, kPi);
      const Vec3 F_p = rnd.wrench();
      KeloDriveVector ref(2 * n);
      for (int j = 0; j < 2 * n; ++j) ref[j] = rnd.uniform(-50, 50);
      kelo_set_pivots(model, data, q);
      kelo_distribute(model, data, F_p, ref);
      ASSERT_TRUE(near(data.F_d, kkt_solution(model, data.G, F_p, ref), 1e-9));
      ASSERT_TRUE(near(data.G * data.F_d, F_p, 1e-10));
      const Vec3 xd(rnd.uniform(-1, 1), rnd.uniform(-1, 1), rnd.uniform(-2, 2));
      const KeloDriveVector w = kelo_wheel_rates(model, data, xd);
      ASSERT_TRUE(near(kelo_platform_twist(model, data, w), xd, 1e-12));
    }
  }
}

TEST(KeloDistribution, SolvesTheWeightedLeastSquaresProblem) {
  Random rnd(3);
  KeloConfig config = ::mospec::testing::paper_base();
  config.drive_weight = {1.0, 0.25, 3.0, 0.5};
  config.rescale_reference = false;  // α = 1: exactly Eq. (2)'s minimiser
  const KeloModel model(config);
  KeloData data(model);
  for (int k = 0; k < 200; ++k) {
    const Vec3 F_p = rnd.wrench();
    const KeloDriveVector ref = rnd.drive_vector(50);
    kelo_set_pivots(model, data, rnd.pivots());
    kelo_distribute(model, data, F_p, ref);
    ASSERT_TRUE(near(data.F_d, kkt_solution(model, data.G, F_p, ref), 1e-9));
  }
}

TEST(KeloDistribution, ZeroWeightDisablesADrive) {
  Random rnd(4);
  for (int off = 0; off < kKeloDrives; ++off) {
    KeloConfig config = ::mospec::testing::paper_base();
    config.drive_weight[off] = 0.0;
    const KeloModel model(config);
    KeloData data(model);
    for (int k = 0; k < 100; ++k) {
      const Vec4 q = rnd.pivots();
      const Vec3 F_p = rnd.wrench();
      kelo_force_step(model, data, q, F_p);  // with the alignment reference
      ASSERT_EQ(data.F_d.segment<2>(2 * off), Vec2::Zero()) << "drive " << off;
      ASSERT_EQ(data.tau_wheel.segment<2>(2 * off), Vec2::Zero());
      ASSERT_TRUE(near(data.G * data.F_d, F_p, 1e-10));
      kelo_distribute(model, data, F_p, rnd.drive_vector(100));  // any reference
      ASSERT_EQ(data.F_d.segment<2>(2 * off), Vec2::Zero());
      ASSERT_TRUE(near(data.G * data.F_d, F_p, 1e-10));
    }
  }
  // Two diagonal drives suffice.
  KeloConfig two = ::mospec::testing::paper_base();
  two.drive_weight = {1.0, 0.0, 1.0, 0.0};
  const KeloModel model(two);
  KeloData data(model);
  kelo_force_step(model, data, Vec4(0.3, 0, -1.2, 0), Vec3(10, -5, 3));
  EXPECT_TRUE(near(data.G * data.F_d, Vec3(10, -5, 3), 1e-10));
}

TEST(KeloDistribution, AlphaRecoversTheGreatestReferenceForce) {
  Random rnd(5);
  const KeloModel model(::mospec::testing::paper_base());
  KeloData data(model);
  for (int k = 0; k < 200; ++k) {
    kelo_set_pivots(model, data, rnd.pivots());
    const KeloDriveVector ref = rnd.drive_vector(20);
    kelo_distribute(model, data, rnd.wrench(), ref);
    double max_ref = 0, max_scaled = 0;
    for (int i = 0; i < kKeloDrives; ++i) {
      max_ref = std::max(max_ref, ref.segment<2>(2 * i).norm());
      max_scaled = std::max(max_scaled, (data.alpha * data.F_d_null.segment<2>(2 * i)).norm());
    }
    ASSERT_GT(data.alpha, 0.0);
    ASSERT_NEAR(max_scaled, max_ref, 1e-10);
  }
  // A reference entirely in the range of G⁺ is projected to nothing: α = 0.
  kelo_set_pivots(model, data, Vec4::Zero());
  const KeloDriveVector in_range = data.G_pinv * Vec3(1, 2, 3);
  kelo_distribute(model, data, Vec3::Zero(), in_range);
  EXPECT_EQ(data.alpha, 0.0);
  EXPECT_LT(data.F_d.norm(), 1e-12);
}

TEST(KeloHubTorques, ClosedForms) {
  const KeloModel model(::mospec::testing::paper_base());
  KeloData data(model);
  const double r = 0.0575, s = 0.01, d = 0.0775;
  data.F_d.setZero();
  data.F_d[0] = 10.0;  // drive 0 pushes forward: both wheels half
  data.F_d[3] = 2.0;   // drive 1 pushes left: differential
  kelo_hub_torques(model, data);
  EXPECT_DOUBLE_EQ(data.f_wheel[0], 5.0);
  EXPECT_DOUBLE_EQ(data.f_wheel[1], 5.0);
  EXPECT_NEAR(data.f_wheel[2], -s / d * 2.0, 1e-15);  // left wheel backwards
  EXPECT_NEAR(data.f_wheel[3], s / d * 2.0, 1e-15);   // right wheel forwards
  EXPECT_NEAR(data.tau_wheel[3], r * s / d * 2.0, 1e-15);
  // Moment of the wheel forces about the pivot is balanced by s f_y.
  EXPECT_NEAR(d / 2 * (data.f_wheel[3] - data.f_wheel[2]), s * 2.0, 1e-15);
}

TEST(KeloVelocity, ClosedFormStraightAndTurningOnTheSpot) {
  const KeloModel model(::mospec::testing::paper_base());
  KeloData data(model);
  const double r = 0.0575;
  kelo_set_pivots(model, data, Vec4::Zero());
  KeloDriveVector w = KeloDriveVector::Constant(kWheels, 10.0);  // every wheel forwards at 10 rad/s
  EXPECT_TRUE(near(kelo_platform_twist(model, data, w), Vec3(10 * r, 0, 0), 1e-14));
  // All drives tangential (counter-clockwise), rolling at the same speed:
  // a pure rotation, ω = v / |p|.
  Vec4 q;
  for (int i = 0; i < kKeloDrives; ++i) {
    const Vec2& p = model.config.geometry.p_PoAi_P[i];
    q[i] = std::atan2(p.x(), -p.y());
  }
  kelo_set_pivots(model, data, q);
  const double rho = Vec2(0.195, 0.21).norm();
  const Vec3 xd = kelo_platform_twist(model, data, w);
  EXPECT_TRUE(near(xd, Vec3(0, 0, 10 * r / rho), 1e-13));
}

TEST(KeloVelocity, WheelRatesRoundTripAndLeastSquares) {
  Random rnd(6);
  const KeloModel model(::mospec::testing::paper_base());
  KeloData data(model);
  for (int k = 0; k < 200; ++k) {
    kelo_set_pivots(model, data, rnd.pivots());
    const Vec3 xd(rnd.uniform(-1, 1), rnd.uniform(-1, 1), rnd.uniform(-2, 2));
    const KeloDriveVector w = kelo_wheel_rates(model, data, xd);
    ASSERT_TRUE(near(kelo_platform_twist(model, data, w), xd, 1e-12));
    // Inconsistent rates (slip): the result is the least-squares twist, so the
    // residual is orthogonal (in the W^{-1} metric) to G^T's range.
    const KeloDriveVector slipping = w + rnd.drive_vector(1.0);
    kelo_platform_twist(model, data, slipping);
    const KeloDriveVector residual = data.u_pivot - data.G.transpose() * data.xd_platform;
    ASSERT_TRUE(near(data.G * model.w_inv.asDiagonal() * residual, Vec3::Zero(), 1e-12));
  }
}

TEST(KeloPower, PlatformPowerEqualsWheelPower) {
  // For a consistent motion (wheel rates of a platform twist) and the drive
  // forces distributed from a platform wrench: xd_p · F_p = Σ τ ω.
  Random rnd(7);
  KeloConfig config = ::mospec::testing::paper_base();
  config.drive_weight = {1.0, 2.0, 0.5, 1.5};
  const KeloModel model(config);
  KeloData data(model);
  for (int k = 0; k < 500; ++k) {
    const Vec4 q = rnd.pivots();
    const Vec3 F_p = rnd.wrench();
    const Vec3 xd(rnd.uniform(-1, 1), rnd.uniform(-1, 1), rnd.uniform(-2, 2));
    kelo_force_step(model, data, q, F_p);
    const KeloDriveVector w = kelo_wheel_rates(model, data, xd);
    const double platform_power = xd.dot(F_p);
    const double wheel_power = data.tau_wheel.dot(w);
    ASSERT_NEAR(wheel_power, platform_power, 1e-9 * (1 + std::abs(platform_power)));
    // Per drive, too: pivot velocity · drive force = wheel power.
    for (int i = 0; i < kKeloDrives; ++i) {
      ASSERT_NEAR(data.u_pivot.segment<2>(2 * i).dot(data.F_d.segment<2>(2 * i)),
                  data.tau_wheel.segment<2>(2 * i).dot(w.segment<2>(2 * i)), 1e-9);
    }
  }
}

TEST(KeloVelocity, PivotRatesFollowTheDriveTurn) {
  // A drive aligned with a pure forward platform motion does not turn; a
  // lateral pivot velocity turns the drive at u_y / s.
  const KeloModel model(::mospec::testing::paper_base());
  KeloData data(model);
  kelo_set_pivots(model, data, Vec4::Zero());
  kelo_wheel_rates(model, data, Vec3(0.5, 0, 0));
  EXPECT_TRUE(near(data.qd_pivot, Vec4::Zero(), 1e-15));
  kelo_wheel_rates(model, data, Vec3(0, 0.1, 0));
  EXPECT_TRUE(near(data.qd_pivot, Vec4::Constant(0.1 / 0.01), 1e-12));
}

TEST(KeloAlignment, ReferenceTurnsDrivesTowardsTheTasks) {
  KeloConfig config = ::mospec::testing::paper_base();
  config.align_moment_weight = {0, 0, 0, 0};  // force task only
  const KeloModel force_only(config);
  KeloData data(force_only);
  // Platform force along +x. Drive 0 aligned: nothing; drive 1 at +90°: turn
  // clockwise (negative); drive 2 at -30°: turn counter-clockwise (positive).
  kelo_set_pivots(force_only, data, Vec4(0, kPi / 2, -kPi / 6, kPi));
  kelo_alignment_reference(force_only, data, Vec3(100, 0, 0));
  EXPECT_EQ(data.F_d_ref[0], 0.0);
  EXPECT_EQ(data.F_d_ref[1], 0.0);
  EXPECT_NEAR(data.F_d_ref[3], 100 * (-kPi / 2), 1e-12);
  EXPECT_NEAR(data.F_d_ref[5], 100 * (kPi / 6), 1e-12);
  EXPECT_NEAR(std::abs(data.F_d_ref[7]), 100 * kPi, 1e-12);  // backwards: the unstable point
  for (int i = 0; i < kKeloDrives; ++i) EXPECT_EQ(data.F_d_ref[2 * i], 0.0);  // lateral only

  config.align_moment_weight = {1, 1, 1, 1};
  config.align_force_weight = {0, 0, 0, 0};  // moment task only
  const KeloModel moment_only(config);
  KeloData md(moment_only);
  Vec4 tangent;
  for (int i = 0; i < kKeloDrives; ++i) {
    const Vec2& p = moment_only.config.geometry.p_PoAi_P[i];
    tangent[i] = std::atan2(p.x(), -p.y());
  }
  kelo_set_pivots(moment_only, md, tangent);
  kelo_alignment_reference(moment_only, md, Vec3(0, 0, 5.0));
  EXPECT_LT(md.F_d_ref.norm(), 1e-12);  // aligned for a positive moment
  // A negative moment is best served by the opposite direction: the aligned
  // drives are at the task's unstable point, the reversed ones at its zero.
  kelo_set_pivots(moment_only, md, (tangent.array() + kPi).matrix());
  kelo_alignment_reference(moment_only, md, Vec3(0, 0, -5.0));
  EXPECT_LT(md.F_d_ref.norm(), 1e-9);
  // Slightly off (+0.1 rad): pushed back (negative), in proportion to |m|/|p|.
  kelo_set_pivots(moment_only, md, (tangent.array() + 0.1).matrix());
  kelo_alignment_reference(moment_only, md, Vec3(0, 0, 5.0));
  const double rho = Vec2(0.195, 0.21).norm();
  for (int i = 0; i < kKeloDrives; ++i) EXPECT_NEAR(md.F_d_ref[2 * i + 1], -5.0 / rho * 0.1, 1e-12);
}

TEST(KeloAlignment, NullspaceReferenceLeavesThePlatformWrenchAlone) {
  // The aligning reference changes the drive forces but not their sum.
  const KeloModel model(::mospec::testing::paper_base());
  KeloData data(model);
  const Vec4 q(0.0, kPi / 2, kPi / 3, -kPi / 4);
  const Vec3 F_p(50, 20, 5);
  kelo_force_step(model, data, q, F_p);
  const KeloDriveVector with_reference = data.F_d;
  kelo_distribute(model, data, F_p, KeloDriveVector::Zero(kWheels));
  EXPECT_GT((with_reference - data.F_d).norm(), 1.0);
  EXPECT_TRUE(near(data.G * with_reference, F_p, 1e-10));
}

TEST(KeloForceStep, NonFiniteInputCommandsZeroAndFlagsIt) {
  const KeloModel model(::mospec::testing::paper_base());
  KeloData data(model);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  kelo_force_step(model, data, Vec4::Zero(), Vec3(10, 0, 0));
  EXPECT_FALSE(data.input_fault);
  EXPECT_GT(data.tau_wheel.norm(), 0.0);
  kelo_force_step(model, data, Vec4(0, nan, 0, 0), Vec3(10, 0, 0));
  EXPECT_TRUE(data.input_fault);
  EXPECT_EQ(data.tau_wheel, KeloDriveVector::Zero(kWheels));
  EXPECT_EQ(data.F_d, KeloDriveVector::Zero(kWheels));
  kelo_force_step(model, data, Vec4::Zero(), Vec3(10, 0, std::numeric_limits<double>::infinity()));
  EXPECT_TRUE(data.input_fault);
  EXPECT_EQ(data.tau_wheel, KeloDriveVector::Zero(kWheels));
  kelo_force_step(model, data, Vec4::Zero(), Vec3(10, 0, 0));
  EXPECT_FALSE(data.input_fault);
  EXPECT_TRUE(data.G.allFinite());  // the bad tick did not touch G
  EXPECT_TRUE(near(data.G * data.F_d, Vec3(10, 0, 0), 1e-12));
}

TEST(KeloPlanar, ConvertsFromAndToSpatialVectors) {
  Vec6 F_Po_P;
  F_Po_P << 1, 2, 3, 4, 5, 6;  // [n; f]
  EXPECT_EQ(planar_wrench(F_Po_P), Vec3(4, 5, 3));
  Vec6 V;
  V << 0, 0, 3, 1, 2, 0;
  EXPECT_EQ(spatial_twist(Vec3(1, 2, 3)), V);
  // Power is the same in both layouts for planar quantities.
  EXPECT_DOUBLE_EQ(spatial_twist(Vec3(1, 2, 3)).dot(F_Po_P),
                   Vec3(1, 2, 3).dot(planar_wrench(F_Po_P)));
}

std::string error_of(const KeloConfig& config) {
  try {
    KeloModel model(config);
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), "invalid-kelo");
    return e.diagnostic().message;
  }
  return "(no error)";
}

TEST(KeloModel, SetupChecks) {
  KeloConfig c = ::mospec::testing::paper_base();
  c.geometry.castor_offset = 0.0;
  EXPECT_EQ(error_of(c), "KELO base: castor offset must be finite and > 0, got 0");
  c = ::mospec::testing::paper_base();
  c.geometry.wheel_radius = -0.1;
  EXPECT_EQ(error_of(c),
            "KELO base: wheel radius must be finite and > 0, got -0.10000000000000001");
  c = ::mospec::testing::paper_base();
  c.drive_weight = {1, 0, 0, 0};
  EXPECT_EQ(error_of(c),
            "KELO base: at least two enabled drives (drive weight > 0) at distinct pivot "
            "positions are needed to produce every platform wrench");
  c = ::mospec::testing::paper_base();
  c.drive_weight[2] = -1;
  EXPECT_EQ(error_of(c), "KELO base: drive weight of drive 2 must be finite and >= 0, got -1");
  c = ::mospec::testing::paper_base();
  c.geometry.p_PoAi_P[1] = Vec2::Zero();
  EXPECT_EQ(error_of(c),
            "KELO base: drive 1 is at the platform centre, so it cannot align with the moment; "
            "set its moment-alignment weight to 0");
  c.align_moment_weight[1] = 0;
  EXPECT_EQ(error_of(c), "(no error)");
}

}  // namespace
}  // namespace mospec::runtime
