// ACHD against KDL's ChainHdSolver_Vereshchagin, and against the runtime's own
// identities: tau = RNE(q, qd, qdd), FD(tau) = qdd, ACHD without constraints =
// FD, and the constraints hold.
#include "runtime/achd.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <kdl/chainfksolverpos_recursive.hpp>
#include <kdl/chainhdsolver_vereshchagin.hpp>
#include <kdl/chainidsolver_recursive_newton_euler.hpp>
#include <limits>
#include <memory>

#include "description/urdf_import.hpp"
#include "kdl_reference.hpp"
#include "runtime/crba.hpp"
#include "runtime/kinematics.hpp"
#include "runtime/rne.hpp"
#include "support/diagnostics.hpp"
#include "test_robots.hpp"

namespace mospec::runtime {
namespace {

using namespace mospec::description;  // the chain importers under test

using testing::near;
constexpr double kTol = 1e-9;

// A robot under test: our model, and KDL's chain (with fixed segments, for
// RNE) and folded chain (for Vereshchagin).
struct Robot {
  Chain chain;
  KDL::Chain kdl;
  KDL::Chain kdl_folded;
};

Robot toy() {
  // One file per process: ctest runs the cases of this executable in parallel.
  const std::string path =
      ::testing::TempDir() + "/mospec_achd_toy_" + std::to_string(::getpid()) + ".urdf";
  std::FILE* f = std::fopen(path.c_str(), "w");
  std::fputs(testing::kToyUrdf.c_str(), f);
  std::fclose(f);
  const KDL::Chain kdl =
      testing::kdl_chain(testing::kdl_tree_from_urdf_file(path), "world", "tool");
  std::remove(path.c_str());
  return {chain_from_urdf(testing::kToyUrdf, "world", "tool"), kdl,
          testing::fold_fixed_segments(kdl)};
}

std::unique_ptr<Robot> gen3() {
  const std::string path = testing::gen3_urdf_path();
  if (path.empty()) return nullptr;
  const KDL::Chain kdl = testing::kdl_chain(testing::kdl_tree_from_urdf_file(path),
                                            testing::kGen3Root, testing::kGen3Tip);
  return std::make_unique<Robot>(
      Robot{chain_from_urdf_file(path, testing::kGen3Root, testing::kGen3Tip), kdl,
            testing::fold_fixed_segments(kdl)});
}
#define SKIP_WITHOUT_GEN3(robot) \
  if (!(robot)) GTEST_SKIP() << "needs " MOSPEC_SHARED_DIR "/upstream/kinova/GEN3_URDF_V12.urdf"

// KDL's ACHD on the same problem. Conversions: alpha linear rows first; beta
// includes the root acceleration (beta_KDL = beta - alpha_f^T g); f_ext at each
// KDL segment's tip (the folded chain's last tip is T, ours is So_N), in B.
struct KdlAchd {
  Eigen::VectorXd qdd, nu, constraint_torques;
};
KdlAchd kdl_achd(const Robot& r, const AchdModel& model, const testing::RandomState& s,
                 const Eigen::Matrix<double, 6, Eigen::Dynamic>& alpha,
                 const Eigen::VectorXd& beta) {
  const int n = model.nq;
  const auto nc = static_cast<unsigned>(alpha.cols());
  const KDL::Vector g(model.g_B.x(), model.g_B.y(), model.g_B.z());
  KDL::ChainHdSolver_Vereshchagin solver(r.kdl_folded, KDL::Twist(-g, KDL::Vector::Zero()), nc);
  KDL::Jacobian alpha_kdl(nc);
  alpha_kdl.data.topRows(3) = alpha.bottomRows(3);
  alpha_kdl.data.bottomRows(3) = alpha.topRows(3);
  KDL::JntArray beta_kdl(nc);
  beta_kdl.data = beta - alpha.bottomRows(3).transpose() * model.g_B;

  AchdData data(model);
  forward_kinematics(model, data, s.q);
  KDL::ChainFkSolverPos_recursive fk(r.kdl_folded);
  const KDL::JntArray q = testing::to_kdl(s.q);
  KDL::Wrenches f_ext(r.kdl_folded.getNrOfSegments());
  for (int i = 0; i < n; ++i) {
    KDL::Frame X_B_tip;
    fk.JntToCart(q, X_B_tip, i + 1);
    const Vec6& F = s.F_ext[static_cast<std::size_t>(i)];
    Vec6 F_tip = F;
    const Vec3 p_tipSo = data.X_BS[static_cast<std::size_t>(i)].p - testing::from_kdl(X_B_tip).p;
    F_tip.head<3>() += p_tipSo.cross(F.tail<3>());
    f_ext[static_cast<std::size_t>(i)] = testing::to_kdl_wrench(F_tip);
  }
  KDL::JntArray qdd(static_cast<unsigned>(n)), tau_c(static_cast<unsigned>(n));
  const int rc = solver.CartToJnt(q, testing::to_kdl(s.qd), qdd, alpha_kdl, beta_kdl, f_ext,
                                  testing::to_kdl(s.tau), tau_c);
  EXPECT_EQ(rc, 0);
  KdlAchd out;
  out.qdd = qdd.data;
  out.nu.resize(nc);
  solver.getContraintForceMagnitude(out.nu);
  out.constraint_torques = tau_c.data;
  return out;
}

// KDL's RNE on the unfolded chain: f_ext in each segment's tip frame (the
// moving segments' tips are our segment frames), zero on fixed segments.
Eigen::VectorXd kdl_rne(const Robot& r, const AchdModel& model, AchdData& data,
                        const testing::RandomState& s, const Eigen::VectorXd& qdd) {
  const KDL::Vector g(model.g_B.x(), model.g_B.y(), model.g_B.z());
  KDL::ChainIdSolver_RNE rne_kdl(r.kdl, g);
  forward_kinematics(model, data, s.q);
  KDL::Wrenches f_ext(r.kdl.getNrOfSegments(), KDL::Wrench::Zero());
  int j = 0;
  for (unsigned i = 0; i < r.kdl.getNrOfSegments(); ++i) {
    if (r.kdl.getSegment(i).getJoint().getType() == KDL::Joint::Fixed) continue;
    const auto k = static_cast<std::size_t>(j++);
    const Mat3 R_SB = data.X_BS[k].R.transpose();
    Vec6 F_S;
    F_S << R_SB * s.F_ext[k].head<3>(), R_SB * s.F_ext[k].tail<3>();
    f_ext[i] = testing::to_kdl_wrench(F_S);
  }
  KDL::JntArray tau(static_cast<unsigned>(model.nq));
  EXPECT_EQ(rne_kdl.CartToJnt(testing::to_kdl(s.q), testing::to_kdl(s.qd), testing::to_kdl(qdd),
                              f_ext, tau),
            0);
  return tau.data;
}

// The tip's physical spatial acceleration [ω̇; a_To] in B from data.a (which
// includes the root acceleration -g).
Vec6 tip_acceleration(const AchdModel& model, const AchdData& data) {
  const auto N = static_cast<std::size_t>(model.nq - 1);
  const Vec6& a_N = data.a[N];
  Vec6 a_T_N;
  a_T_N << a_N.head<3>(), a_N.tail<3>() + a_N.head<3>().cross(model.X_NT.p);
  const Mat3& R_BN = data.X_BS[N].R;
  Vec6 A;
  A << R_BN * a_T_N.head<3>(), R_BN * a_T_N.tail<3>() + model.g_B;
  return A;
}

void check_against_kdl(const Robot& r, unsigned seed, int nc) {
  const AchdModel model(r.chain);
  AchdData data(model);
  AchdData scratch(model);
  const int n = model.nq;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  double kdl_constraint_torque_gap = 0.0;
  for (int trial = 0; trial < 100; ++trial) {
    SCOPED_TRACE("trial " + std::to_string(trial));
    const auto s = testing::random_state(rng, n);
    const auto alpha = testing::random_alpha(rng, nc, trial % 2 == 0);
    Eigen::VectorXd beta(nc);
    for (int c = 0; c < nc; ++c) beta[c] = 3.0 * unit(rng);

    ASSERT_EQ(achd(model, data, s.q, s.qd, s.tau, s.F_ext, alpha, beta), Status::Ok);
    const Eigen::VectorXd qdd = data.qdd, nu = data.nu, tau = data.tau;

    const KdlAchd kdl = kdl_achd(r, model, s, alpha, beta);
    EXPECT_TRUE(near(qdd, kdl.qdd, kTol));
    EXPECT_TRUE(near(nu, kdl.nu, kTol));
    kdl_constraint_torque_gap =
        std::max(kdl_constraint_torque_gap, (tau - s.tau - kdl.constraint_torques).norm());

    // The constraints hold on the physical tip acceleration.
    EXPECT_TRUE(
        near(Eigen::VectorXd(alpha.transpose() * tip_acceleration(model, data)), beta, kTol));

    // tau realises qdd: inverse dynamics (ours and KDL's) at qdd give tau back ...
    ASSERT_EQ(rne(model, scratch, s.q, s.qd, qdd, s.F_ext), Status::Ok);
    EXPECT_TRUE(near(Eigen::VectorXd(scratch.tau), tau, kTol));
    EXPECT_TRUE(near(kdl_rne(r, model, scratch, s, qdd), tau, kTol));
    // ... and tau = tau_ff - J^T alpha nu.
    ASSERT_EQ(tip_jacobian(model, scratch, s.q), Status::Ok);
    EXPECT_TRUE(
        near(Eigen::VectorXd(s.tau - scratch.J_To_B.transpose() * (alpha * nu)), tau, kTol));
    // ... and forward dynamics with tau reproduces qdd.
    ASSERT_EQ(forward_dynamics(model, scratch, s.q, s.qd, tau, s.F_ext), Status::Ok);
    EXPECT_TRUE(near(Eigen::VectorXd(scratch.qdd), qdd, kTol));
  }
  // KDL's constraint_torques are not J^T alpha nu (see achd.hpp); recorded, not asserted.
  ::testing::Test::RecordProperty("max_norm_kdl_constraint_torques_minus_ours",
                                  std::to_string(kdl_constraint_torque_gap));
}

TEST(AchdVsKdl, KinovaGen3FiveConstraints) {
  const auto r = gen3();
  SKIP_WITHOUT_GEN3(r);
  check_against_kdl(*r, 1, 5);
}

TEST(AchdVsKdl, KinovaGen3OtherConstraintCounts) {
  const auto r = gen3();
  SKIP_WITHOUT_GEN3(r);
  for (int nc : {1, 3, 6}) check_against_kdl(*r, 10 + static_cast<unsigned>(nc), nc);
}

TEST(AchdVsKdl, ToyArmWithFixedAndPrismaticJoints) {
  const Robot r = toy();
  for (int nc : {2, 4}) check_against_kdl(r, 20 + static_cast<unsigned>(nc), nc);
}

// RNE against KDL's RNE directly, with random accelerations.
TEST(Rne, EqualsKdl) {
  for (const bool use_gen3 : {false, true}) {
    std::unique_ptr<Robot> r = use_gen3 ? gen3() : std::make_unique<Robot>(toy());
    if (!r) continue;
    const AchdModel model(r->chain);
    AchdData data(model), scratch(model);
    std::mt19937 rng(3);
    for (int trial = 0; trial < 100; ++trial) {
      const auto s = testing::random_state(rng, model.nq);
      ASSERT_EQ(rne(model, data, s.q, s.qd, s.qdd, s.F_ext), Status::Ok);
      EXPECT_TRUE(near(Eigen::VectorXd(data.tau), kdl_rne(*r, model, scratch, s, s.qdd), kTol));
    }
  }
}

TEST(Achd, WithoutConstraintsEqualsForwardDynamics) {
  for (const bool use_gen3 : {false, true}) {
    std::unique_ptr<Robot> r = use_gen3 ? gen3() : std::make_unique<Robot>(toy());
    if (!r) continue;
    const AchdModel model(r->chain);
    AchdData data(model), fd(model);
    std::mt19937 rng(5);
    const Eigen::Matrix<double, 6, Eigen::Dynamic> none(6, 0);
    const Eigen::VectorXd no_beta(0);
    for (int trial = 0; trial < 100; ++trial) {
      const auto s = testing::random_state(rng, model.nq);
      ASSERT_EQ(achd(model, data, s.q, s.qd, s.tau, s.F_ext, none, no_beta), Status::Ok);
      ASSERT_EQ(forward_dynamics(model, fd, s.q, s.qd, s.tau, s.F_ext), Status::Ok);
      EXPECT_TRUE(near(Eigen::VectorXd(data.qdd), Eigen::VectorXd(fd.qdd), kTol));
      EXPECT_TRUE(near(Eigen::VectorXd(data.tau), s.tau, 0.0));
      EXPECT_EQ(data.nu.size(), 0);
      // Without external wrenches too.
      ASSERT_EQ(achd(model, data, s.q, s.qd, s.tau, {}, none, no_beta), Status::Ok);
      ASSERT_EQ(forward_dynamics(model, fd, s.q, s.qd, s.tau, {}), Status::Ok);
      EXPECT_TRUE(near(Eigen::VectorXd(data.qdd), Eigen::VectorXd(fd.qdd), kTol));
    }
  }
}

TEST(Achd, GravityCompensationHoldsStill) {
  // rne(q, 0, 0) is gravity compensation: fed as tau_ff, the arm does not move,
  // and a "stay" constraint (beta = 0) then needs no constraint force.
  const Robot r = toy();
  const AchdModel model(r.chain);
  AchdData data(model);
  const Eigen::VectorXd q = Eigen::VectorXd::LinSpaced(model.nq, -1.0, 1.0);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(model.nq);
  ASSERT_EQ(rne(model, data, q, zero, zero, {}), Status::Ok);
  const Eigen::VectorXd g_comp = data.tau;
  const Eigen::Matrix<double, 6, Eigen::Dynamic> alpha = Mat6::Identity().leftCols(5);
  const Eigen::VectorXd beta = Eigen::VectorXd::Zero(5);
  ASSERT_EQ(achd(model, data, q, zero, g_comp, {}, alpha, beta), Status::Ok);
  EXPECT_TRUE(near(Eigen::VectorXd(data.qdd), zero, 1e-10));
  EXPECT_TRUE(near(Eigen::VectorXd(data.nu), beta, 1e-9));
  // Without the compensation the constraint holds the arm (5 joints, 5
  // constraints: qdd = 0) and tau is exactly the compensation.
  ASSERT_EQ(achd(model, data, q, zero, zero, {}, alpha, beta), Status::Ok);
  EXPECT_TRUE(near(Eigen::VectorXd(data.qdd), zero, 1e-9));
  EXPECT_TRUE(near(Eigen::VectorXd(data.tau), g_comp, 1e-9));
  // Six constraints on five joints cannot all be independent: degraded, yet
  // "stay" is still feasible and met.
  const Eigen::Matrix<double, 6, Eigen::Dynamic> all = Mat6::Identity();
  ASSERT_EQ(achd(model, data, q, zero, zero, {}, all, Eigen::VectorXd::Zero(6)),
            Status::ConstraintsDegraded);
  EXPECT_TRUE(near(Eigen::VectorXd(data.qdd), zero, 1e-9));
  EXPECT_TRUE(near(Eigen::VectorXd(data.tau), g_comp, 1e-9));
}

// beta's documented meaning, checked from outside the solver: differentiate
// the tip twist J(q) qd numerically along the solved motion. With
// [ω; v_To] = J qd, the tip's spatial acceleration is [ω̇; p̈_To - ω × v_To]
// (p̈_To = d/dt v_To), and alpha^T of it must be beta: gravity is not in it.
TEST(Achd, BetaConstrainsThePhysicalSpatialAccelerationOfTheTip) {
  const Robot r = toy();
  const AchdModel model(r.chain);
  AchdData data(model), kin(model);
  std::mt19937 rng(13);
  for (int trial = 0; trial < 10; ++trial) {
    const auto s = testing::random_state(rng, model.nq);
    const auto alpha = testing::random_alpha(rng, 4, trial % 2 == 0);
    const Eigen::Vector4d beta(0.3, -1.2, 2.0, 0.7);
    ASSERT_EQ(achd(model, data, s.q, s.qd, s.tau, s.F_ext, alpha, beta), Status::Ok);
    const Eigen::VectorXd qdd = data.qdd;
    const auto twist_at = [&](double t) {
      const Eigen::VectorXd q = s.q + s.qd * t + 0.5 * qdd * t * t;
      const Eigen::VectorXd qd = s.qd + qdd * t;
      tip_jacobian(model, kin, q);
      return Vec6(kin.J_To_B * qd);
    };
    // Central differences with one Richardson step: error O(h^4).
    const auto central = [&](double h) { return Vec6((twist_at(h) - twist_at(-h)) / (2.0 * h)); };
    const double h = 1e-4;
    const Vec6 V = twist_at(0.0);
    const Vec6 dV = (4.0 * central(h / 2) - central(h)) / 3.0;
    Vec6 A;
    A << dV.head<3>(), dV.tail<3>() - V.head<3>().cross(V.tail<3>());
    EXPECT_TRUE(near(Eigen::VectorXd(alpha.transpose() * A), Eigen::VectorXd(beta), 1e-7))
        << "trial " << trial;
  }
}

TEST(Achd, SingularConstraintsDegradeAndKeepTheFeasibleOnes) {
  const Robot r = toy();
  const AchdModel model(r.chain);
  AchdData data(model), scratch(model);
  std::mt19937 rng(9);
  const auto s = testing::random_state(rng, model.nq);
  // The same constraint twice: M_0 has rank 2 of 3.
  Eigen::Matrix<double, 6, Eigen::Dynamic> alpha = Eigen::Matrix<double, 6, 3>::Zero();
  alpha(3, 0) = alpha(3, 1) = 1.0;
  alpha(1, 2) = 1.0;
  const Eigen::Vector3d beta(0.5, 0.5, -0.2);
  EXPECT_EQ(achd(model, data, s.q, s.qd, s.tau, s.F_ext, alpha, beta), Status::ConstraintsDegraded);
  EXPECT_TRUE(near(Eigen::VectorXd(alpha.transpose() * tip_acceleration(model, data)),
                   Eigen::VectorXd(beta), 1e-9));
  ASSERT_EQ(rne(model, scratch, s.q, s.qd, data.qdd, s.F_ext), Status::Ok);
  EXPECT_TRUE(near(Eigen::VectorXd(scratch.tau), Eigen::VectorXd(data.tau), 1e-9));
  EXPECT_NEAR(data.nu[0], data.nu[1], 1e-9);  // minimum norm splits the force evenly
}

TEST(Achd, SizeMismatchIsAStatusAtTickTimeAndANamedErrorAtSetup) {
  const Robot r = toy();
  const AchdModel model(r.chain);
  AchdData data(model);
  const Eigen::VectorXd q = Eigen::VectorXd::Zero(model.nq), q_short = Eigen::VectorXd::Zero(2);
  const Eigen::Matrix<double, 6, Eigen::Dynamic> alpha = Eigen::Matrix<double, 6, 2>::Zero();
  const Eigen::VectorXd beta = Eigen::VectorXd::Zero(3);
  data.qdd.setConstant(42.0);
  EXPECT_EQ(achd(model, data, q, q_short, q, {}, alpha, Eigen::VectorXd::Zero(2)),
            Status::SizeMismatch);
  EXPECT_EQ(data.qdd[0], 42.0);  // untouched
  EXPECT_EQ(achd(model, data, q, q, q, {}, alpha, beta), Status::SizeMismatch);
  try {
    check_achd_arguments(model, q, q_short, q, {}, alpha, Eigen::VectorXd::Zero(2));
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), "size-mismatch");
    EXPECT_STREQ(e.what(), "mospec: error: achd: qd has 2 entries, expected 5 (model.nq)");
  }
  try {
    check_achd_arguments(model, q, q, q, {}, alpha, beta);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(),
                 "mospec: error: achd: beta has 3 entries, expected 2 (one per alpha column)");
  }
  try {
    Eigen::VectorXd q_nan = q;
    q_nan[1] = std::numeric_limits<double>::quiet_NaN();
    check_achd_arguments(model, q_nan, q, q, {}, alpha, Eigen::VectorXd::Zero(2));
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), "non-finite");
    EXPECT_STREQ(e.what(), "mospec: error: achd: q has non-finite entries");
  }
  AchdData other(AchdModel(chain_from_urdf(testing::kToyUrdf, "world", "l3")));
  EXPECT_EQ(achd(model, other, q, q, q, {}, alpha, Eigen::VectorXd::Zero(2)), Status::SizeMismatch);
}

}  // namespace
}  // namespace mospec::runtime
