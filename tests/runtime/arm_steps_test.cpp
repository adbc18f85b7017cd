// The arm steps the IR runs (runtime/steps.hpp) on the toy arm: what the
// command is when the task solve has gravity (the paper's least-constrained
// motion: directions no driver controls fall) and when it is gravity
// compensated, and the idle behaviours of mos-slv:when-idle.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "description/urdf_import.hpp"
#include "runtime/crba.hpp"
#include "runtime/kinematics.hpp"
#include "runtime/rne.hpp"
#include "runtime/steps.hpp"
#include "test_robots.hpp"

namespace mospec::runtime {
namespace {

const Vec3 kGravity(0.0, 0.0, -9.81);

struct Arm {
  Arm() : chain(description::chain_from_urdf(testing::kToyUrdf, "world", "tool")) {}
  Chain chain;
};

// The torque rne computes for (q, qd, qdd) with gravity, no external wrenches.
JointVector inverse_dynamics(const AchdModel& model, const JointVector& q, const JointVector& qd,
                             const JointVector& qdd) {
  AchdData data(model);
  JointVector tau(model.nq);
  const JointIn qdd_in(qdd);
  impl::rne_into(model, data, q, qd, &qdd_in, {}, tau);
  return tau;
}

// A state of the toy arm after its first valid sample.
steps::ArmWorkspace sampled(const AchdModel& model, AchdData& data, std::mt19937& rng) {
  steps::ArmWorkspace ws(model, 0);
  const testing::RandomState s = testing::random_state(rng, model.nq);
  std::vector<double> q(s.q.data(), s.q.data() + model.nq), qd(s.qd.data(), s.qd.data() + model.nq);
  steps::arm_kinematics(model, data, ws, q, qd);
  return ws;
}

TEST(ArmSteps, WithoutDriversATaskSolvedUnderGravityCommandsNothing) {
  // Gauss' least constraint with no driver is free fall: the command that
  // realises it on the real arm (same gravity) is zero torque.
  const Arm arm;
  const AchdModel physical(arm.chain, kGravity);
  AchdData data(physical);
  std::mt19937 rng(7);
  for (int trial = 0; trial < 20; ++trial) {
    steps::ArmWorkspace ws = sampled(physical, data, rng);
    std::vector<double> tau(static_cast<size_t>(physical.nq));
    steps::arm_solve(physical, physical, data, ws, tau);
    for (double t : tau) EXPECT_NEAR(t, 0.0, 1e-9) << "trial " << trial;
  }
}

TEST(ArmSteps, AGravityCompensatedTaskHoldsUndrivenDirectionsAgainstGravity) {
  // Without gravity in the task, an arm at rest with no driver stays at rest:
  // the command is exactly the gravity torque.
  const Arm arm;
  const AchdModel physical(arm.chain, kGravity), task(arm.chain, Vec3::Zero());
  AchdData data(physical);
  std::mt19937 rng(11);
  for (int trial = 0; trial < 20; ++trial) {
    steps::ArmWorkspace ws = sampled(physical, data, rng);
    ws.qd.setZero();
    std::vector<double> tau(static_cast<size_t>(physical.nq));
    steps::arm_solve(task, physical, data, ws, tau);
    const JointVector zero = JointVector::Zero(physical.nq);
    const JointVector gravity = inverse_dynamics(physical, ws.q, zero, zero);
    ASSERT_GT(gravity.norm(), 1.0);
    for (int i = 0; i < physical.nq; ++i)
      EXPECT_NEAR(tau[static_cast<size_t>(i)], gravity[i], 1e-9) << "trial " << trial;
  }
}

TEST(ArmSteps, ASolveWithMoreConstraintsThanJointsReportsItDegraded) {
  // The toy arm has five joints: six tip constraints cannot all hold, and the
  // solve says so (the IR logs it as the solve's `.degraded` flag); three can.
  const Arm arm;
  const AchdModel model(arm.chain, kGravity);
  AchdData data(model);
  std::mt19937 rng(13);
  for (const int nc : {3, 6}) {
    steps::ArmWorkspace ws(model, nc);
    const testing::RandomState s = testing::random_state(rng, model.nq);
    std::vector<double> q(s.q.data(), s.q.data() + model.nq),
        qd(static_cast<size_t>(model.nq), 0.0);
    steps::arm_kinematics(model, data, ws, q, qd);
    for (int k = 0; k < nc; ++k) ws.alpha_To_B(k, k) = 1.0;
    ws.beta.setZero();
    std::vector<double> tau(static_cast<size_t>(model.nq));
    steps::arm_solve(model, model, data, ws, tau);
    EXPECT_EQ(ws.status, nc == 6 ? Status::ConstraintsDegraded : Status::Ok)
        << nc << " constraints";
  }
}

TEST(ArmSteps, ADisengagedColumnLeavesItsDirectionFree) {
  // A one-sided (less-than/greater-than) row is disengaged while its bound is
  // satisfied: the solve is exactly the one without that column, whatever its
  // beta says, and not one that holds the direction at beta (issue #15).
  const Arm arm;
  const AchdModel model(arm.chain, kGravity);
  AchdData data(model);
  std::mt19937 rng(17);
  for (int trial = 0; trial < 10; ++trial) {
    const testing::RandomState s = testing::random_state(rng, model.nq);
    std::vector<double> q(s.q.data(), s.q.data() + model.nq),
        qd(s.qd.data(), s.qd.data() + model.nq);
    // Three rows (angular z, linear x, linear z); the middle one disengaged.
    steps::ArmWorkspace three(model, 3);
    three.alpha_To_B(2, 0) = three.alpha_To_B(3, 1) = three.alpha_To_B(5, 2) = 1.0;
    three.beta << 0.5, 7.0, -1.0;
    three.engaged[1] = false;
    steps::arm_kinematics(model, data, three, q, qd);
    std::vector<double> tau_three(static_cast<size_t>(model.nq));
    steps::arm_solve(model, model, data, three, tau_three);
    const JointVector qdd_three = data.qdd;
    // The same without the row.
    steps::ArmWorkspace two(model, 2);
    two.alpha_To_B(2, 0) = two.alpha_To_B(5, 1) = 1.0;
    two.beta << 0.5, -1.0;
    steps::arm_kinematics(model, data, two, q, qd);
    std::vector<double> tau_two(static_cast<size_t>(model.nq));
    steps::arm_solve(model, model, data, two, tau_two);
    EXPECT_EQ(tau_three, tau_two) << "trial " << trial;
    EXPECT_EQ(three.status, two.status);
    // Engaged, the row changes the motion.
    three.engaged[1] = true;
    steps::arm_solve(model, model, data, three, tau_three);
    EXPECT_GT((data.qdd - qdd_three).norm(), 1e-3) << "trial " << trial;
  }
}

TEST(ArmSteps, AOneSidedRowEngagesBeyondHalfItsToleranceAndReleasesWithinAQuarter) {
  // An inequality with a 1 mm tolerance (a position's default): the error is
  // 0 inside the bound, the signed distance to it beyond.
  constexpr double tol = 1e-3;
  // Inside the bound: never engaged.
  EXPECT_FALSE(steps::one_sided_engaged(false, 0.0, tol));
  EXPECT_FALSE(steps::one_sided_engaged(true, 0.0, tol));
  // Starts 1 cm beyond (violated): engaged, and stays so while a PD brings it
  // back, until within a quarter of the tolerance (it need not reach the
  // bound, which a PD reaches only asymptotically).
  bool engaged = true;  // ArmWorkspace's initial state
  std::vector<bool> trace;
  for (double error : {-1e-2, -5e-3, -1e-3, -6e-4, -3e-4, -2.4e-4, -1e-4, -2e-4, -4e-4})
    trace.push_back(engaged = steps::one_sided_engaged(engaged, error, tol));
  // Released at -2.4e-4 (<= 2.5e-4); not re-engaged at -4e-4 (<= 5e-4).
  EXPECT_EQ(trace, (std::vector<bool>{true, true, true, true, true, false, false, false, false}));
  // Pushed out again: engaged beyond half the tolerance, inside the band
  // (1 mm) where the constraint is satisfied.
  EXPECT_TRUE(steps::one_sided_engaged(false, -5.1e-4, tol));
  EXPECT_FALSE(steps::one_sided_engaged(false, -5e-4, tol));
  EXPECT_TRUE(steps::one_sided_engaged(true, -3e-4, tol));
  // The sign does not matter (a greater-than's error is positive beyond).
  EXPECT_TRUE(steps::one_sided_engaged(false, 6e-4, tol));
  // Without a tolerance: engaged exactly while the error is not 0.
  EXPECT_TRUE(steps::one_sided_engaged(false, -1e-12, 0.0));
  EXPECT_FALSE(steps::one_sided_engaged(true, 0.0, 0.0));
  // A NaN error keeps the row engaged (the solve then faults on it).
  EXPECT_TRUE(steps::one_sided_engaged(false, std::nan(""), tol));
}

TEST(ArmSteps, BrakeAndHoldDecaysEveryJointVelocityWithTheModelsTimeConstant) {
  const Arm arm;
  const AchdModel physical(arm.chain, kGravity);
  AchdData data(physical);
  std::mt19937 rng(3);
  for (const double time_constant : {0.1, 0.25, 2.0}) {
    steps::ArmWorkspace ws = sampled(physical, data, rng);
    std::vector<double> tau(static_cast<size_t>(physical.nq));
    steps::arm_hold(physical, data, ws, time_constant, tau);
    const JointVector expected =
        inverse_dynamics(physical, ws.q, ws.qd, JointVector(-ws.qd / time_constant));
    for (int i = 0; i < physical.nq; ++i)
      EXPECT_DOUBLE_EQ(tau[static_cast<size_t>(i)], expected[i])
          << "time constant " << time_constant;
  }
}

TEST(ArmSteps, FloatIsGravityCompensationAlone) {
  const Arm arm;
  const AchdModel physical(arm.chain, kGravity);
  AchdData data(physical);
  std::mt19937 rng(5);
  steps::ArmWorkspace ws = sampled(physical, data, rng);
  std::vector<double> tau(static_cast<size_t>(physical.nq));
  steps::arm_hold(physical, data, ws, steps::kFloatTimeConstant, tau);
  const JointVector expected =
      inverse_dynamics(physical, ws.q, ws.qd, JointVector::Zero(physical.nq));
  for (int i = 0; i < physical.nq; ++i)
    EXPECT_NEAR(tau[static_cast<size_t>(i)], expected[i], 1e-12);
}

// The estimated wrench (issue #16 item 4) checked against rne: measured
// torques that hold the arm still against a wrench F on a segment are
// rne(q, qd, 0, F); the estimate from them must produce the same joint torques
// (the part of F the joints feel: the toy arm has five joints, so J^T has a
// null space), and equal F where F is in the range of J.
TEST(ArmSteps, TheEstimatedWrenchProducesTheMeasuredTorquesDeviationFromTheModel) {
  const Arm arm;
  const AchdModel physical(arm.chain, kGravity);
  AchdData data(physical);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-5.0, 5.0);
  const int n = physical.nq;
  for (int trial = 0; trial < 20; ++trial) {
    steps::ArmWorkspace ws = sampled(physical, data, rng);
    const int segment = trial % n;
    std::vector<Vec6> F_ext(static_cast<size_t>(n), Vec6::Zero());
    Vec6 F;
    for (int k = 0; k < 6; ++k) F[k] = u(rng);
    F_ext[static_cast<size_t>(segment)] = F;
    AchdData scratch(physical);
    JointVector tau(n), zero = JointVector::Zero(n);
    const JointIn zero_in(zero);
    impl::rne_into(physical, scratch, ws.q, ws.qd, &zero_in, F_ext, tau);
    std::vector<double> measured(tau.data(), tau.data() + n);
    const Vec6 F_est = steps::estimated_wrench(physical, data, ws, measured, segment);
    std::vector<Vec6> F_est_ext(static_cast<size_t>(n), Vec6::Zero());
    F_est_ext[static_cast<size_t>(segment)] = F_est;
    JointVector tau_est(n);
    impl::rne_into(physical, scratch, ws.q, ws.qd, &zero_in, F_est_ext, tau_est);
    for (int i = 0; i < n; ++i)
      EXPECT_NEAR(tau_est[i], tau[i], 1e-6) << "trial " << trial << ", joint " << i;
  }
}

TEST(ArmSteps, WithoutAnExternalWrenchTheEstimateIsZeroAndANaNTorqueKeepsTheLastSample) {
  const Arm arm;
  const AchdModel physical(arm.chain, kGravity);
  AchdData data(physical);
  std::mt19937 rng(3);
  steps::ArmWorkspace ws = sampled(physical, data, rng);
  const int n = physical.nq;
  AchdData scratch(physical);
  JointVector tau(n), zero = JointVector::Zero(n);
  const JointIn zero_in(zero);
  impl::rne_into(physical, scratch, ws.q, ws.qd, &zero_in, {}, tau);
  std::vector<double> measured(tau.data(), tau.data() + n);
  EXPECT_LT(steps::estimated_wrench(physical, data, ws, measured, n - 1).norm(), 1e-9);
  measured[1] = std::nan("");
  const Vec6 F = steps::estimated_wrench(physical, data, ws, measured, n - 1);
  EXPECT_TRUE(F.allFinite());
  EXPECT_LT(F.norm(), 1e-9);
  EXPECT_EQ(steps::joint_torque(ws, measured, 1), tau[1]);
}

// The toy arm's tool (link 'tool', fixed to the last moving link l5 by
// f_tool: xyz 0.01 0 0.1, rpy 0 0 1), as the URDF states it: built here
// independently of the chain's folding.
Pose toy_tool_offset() {
  return {Eigen::AngleAxisd(1.0, Vec3::UnitZ()).toRotationMatrix(), Vec3(0.01, 0.0, 0.1)};
}

// The same arm ending at its last moving link (no tool): its tip is l5's frame.
Chain toy_without_tool() {
  return description::chain_from_urdf(testing::kToyUrdf, "world", "l5");
}

TEST(ArmSteps, TheToolFramesPoseTwistAndWrenchAreTheLastLinksComposedWithItsFixedOffset) {
  const Arm arm;
  const Chain bare = toy_without_tool();
  const AchdModel physical(arm.chain, kGravity), last(bare, kGravity);
  ASSERT_EQ(last.nq, physical.nq);
  AchdData data(physical), kin(physical), kin_last(last);
  const Pose X_NT = toy_tool_offset();
  std::mt19937 rng(23);
  for (int trial = 0; trial < 20; ++trial) {
    steps::ArmWorkspace ws = sampled(physical, data, rng);
    // The pose: l5's frame (from the chain without the tool) composed with
    // the URDF's fixed offset.
    const Pose X_BT = steps::tip_pose(physical, data);
    ASSERT_EQ(forward_kinematics(last, kin_last, ws.q), Status::Ok);
    const Pose want = kin_last.X_BS[static_cast<size_t>(last.nq - 1)] * X_NT;
    EXPECT_TRUE(testing::near(X_BT.R, want.R, 1e-12)) << "trial " << trial;
    EXPECT_TRUE(testing::near(X_BT.p, want.p, 1e-12)) << "trial " << trial;
    // Not the last link's own pose: the offset is there.
    EXPECT_GT((X_BT.p - kin_last.X_BS[static_cast<size_t>(last.nq - 1)].p).norm(), 0.09);
    // The twist at To, against the pose differentiated along q + qd t.
    const auto pose_at = [&](double t) {
      forward_kinematics(last, kin_last, ws.q + ws.qd * t);
      return kin_last.X_BS[static_cast<size_t>(last.nq - 1)] * X_NT;
    };
    const double h = 1e-6;
    const Pose ahead = pose_at(h), behind = pose_at(-h);
    const Vec3 v = (ahead.p - behind.p) / (2 * h);
    const Mat3 W = (ahead.R - behind.R) / (2 * h) * X_BT.R.transpose();  // [w]x
    const Vec6 V = steps::tip_twist(physical, data);
    EXPECT_TRUE(testing::near(Vec3(V.tail<3>()), v, 1e-7)) << "trial " << trial;
    EXPECT_TRUE(testing::near(Vec3(V.head<3>()), Vec3(W(2, 1), W(0, 2), W(1, 0)), 1e-7))
        << "trial " << trial;
    // A wrench at To moved to No does the same virtual work on every joint:
    // J_To^T F_To = J_No^T F_No.
    Vec6 F_To;
    F_To << 0.3, -0.2, 0.5, 4.0, -7.0, 2.5;
    const Vec6 F_No = steps::tip_wrench_at_segment_origin(physical, data, F_To);
    ASSERT_EQ(tip_jacobian(physical, kin, ws.q), Status::Ok);
    ASSERT_EQ(tip_jacobian(last, kin_last, ws.q), Status::Ok);
    EXPECT_TRUE(testing::near(JointVector(kin_last.J_To_B.transpose() * F_No),
                              JointVector(kin.J_To_B.transpose() * F_To), 1e-12))
        << "trial " << trial;
  }
}

// The linear acceleration of a point of the last link, from outside the
// solver: the twist J(q) qd at that point differentiated along q + qd t +
// qdd t^2 / 2, less w x v (the spatial acceleration ACHD's beta is on).
Vec3 point_acceleration(const AchdModel& model, const Eigen::VectorXd& q, const Eigen::VectorXd& qd,
                        const Eigen::VectorXd& qdd) {
  AchdData kin(model);
  const auto twist_at = [&](double t) {
    tip_jacobian(model, kin, q + qd * t + 0.5 * qdd * t * t);
    return Vec6(kin.J_To_B * (qd + qdd * t));
  };
  const auto central = [&](double h) { return Vec6((twist_at(h) - twist_at(-h)) / (2.0 * h)); };
  const double h = 1e-4;
  const Vec6 V = twist_at(0.0);
  const Vec6 dV = (4.0 * central(h / 2) - central(h)) / 3.0;
  return dV.tail<3>() - V.head<3>().cross(V.tail<3>());
}

TEST(ArmSteps, AnAccelerationConstraintAtTheToolIsMetAtTheToolNotAtTheLastLinksOrigin) {
  // The task model whose tip is the tool (the drivers attached to it): three
  // linear acceleration constraints there. The command, applied to the arm
  // (forward dynamics under real gravity), gives the tool's origin exactly
  // that acceleration; the last link's origin gets another one.
  const Arm arm;
  const Chain bare = toy_without_tool();
  const AchdModel physical(arm.chain, kGravity), task(arm.chain, Vec3::Zero());
  const AchdModel last(bare, kGravity);
  AchdData data(physical), fd(physical);
  const Vec3 beta(0.5, -0.3, 0.2);
  std::mt19937 rng(29);
  for (int trial = 0; trial < 10; ++trial) {
    steps::ArmWorkspace ws(physical, 3);
    const testing::RandomState s = testing::random_state(rng, physical.nq);
    std::vector<double> q(s.q.data(), s.q.data() + physical.nq);
    std::vector<double> qd(s.qd.data(), s.qd.data() + physical.nq);
    steps::arm_kinematics(physical, data, ws, q, qd);
    for (int c = 0; c < 3; ++c) ws.alpha_To_B(3 + c, c) = 1.0;
    ws.beta = beta;
    std::vector<double> tau(static_cast<size_t>(physical.nq));
    steps::arm_solve(task, physical, data, ws, tau);
    ASSERT_EQ(ws.status, Status::Ok) << "trial " << trial;
    const Eigen::VectorXd command = Eigen::Map<const Eigen::VectorXd>(tau.data(), physical.nq);
    ASSERT_EQ(forward_dynamics(physical, fd, ws.q, ws.qd, command, {}), Status::Ok);
    const Eigen::VectorXd qdd = fd.qdd, q_now = ws.q, qd_now = ws.qd;
    EXPECT_TRUE(testing::near(point_acceleration(physical, q_now, qd_now, qdd), beta, 1e-6))
        << "trial " << trial;
    EXPECT_GT((point_acceleration(last, q_now, qd_now, qdd) - beta).norm(), 1e-2)
        << "trial " << trial;
  }
}

}  // namespace
}  // namespace mospec::runtime
