// The tick path allocates nothing: every heap entry point of this executable
// (operator new/delete and the C allocator) is replaced by a counting one, and
// 10 000 calls of each runtime algorithm must leave the counter at zero.
//
// Own executable because it replaces the global allocator. Skipped under
// AddressSanitizer, which owns malloc itself.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <kdl/chainhdsolver_vereshchagin.hpp>
#include <vector>

#include "description/urdf_import.hpp"
#include "kdl_reference.hpp"
#include "runtime/achd.hpp"
#include "runtime/crba.hpp"
#include "runtime/kinematics.hpp"
#include "runtime/rne.hpp"
#include "runtime/steps.hpp"
#include "test_robots.hpp"
// Defines the replacement allocator: this translation unit only, and last.
#include "alloc_counter.hpp"  // NOLINT(llvm-include-order)

namespace mospec::runtime {
namespace {

using namespace mospec::description;  // the chain importers under test

class NoAllocation : public ::testing::Test {
 protected:
  void SetUp() override {
#ifdef MOSPEC_NO_ALLOC_COUNTING
    GTEST_SKIP() << "allocation counting is off under AddressSanitizer";
#endif
  }
};

TEST_F(NoAllocation, TheCounterSeesEveryKindOfAllocation) {
  EXPECT_EQ(alloc_counter::during([] { std::vector<int> v(10); }), 1);
  EXPECT_EQ(alloc_counter::during([] { Eigen::VectorXd v(10); }), 1);
  EXPECT_EQ(alloc_counter::during([] { std::free(std::malloc(8)); }), 1);
  EXPECT_EQ(alloc_counter::during([] { Eigen::Matrix<double, 6, Eigen::Dynamic> m(6, 20); }), 1);
  EXPECT_EQ(alloc_counter::during([] {}), 0);
}

void run_all_algorithms(const Chain& chain, int nc) {
  const AchdModel model(chain);
  AchdData data(model);
  std::mt19937 rng(11);
  const auto s = testing::random_state(rng, model.nq);
  const ConstraintMatrix alpha = testing::random_alpha(rng, nc, false);
  const ConstraintVector beta = ConstraintVector::Constant(nc, 0.3);
  // Two identical constraints: the singular (eigen-decomposition) branch.
  ConstraintMatrix singular(6, 2);
  singular << alpha.col(0), alpha.col(0);
  const ConstraintVector singular_beta = ConstraintVector::Constant(2, 0.1);
  const Eigen::Matrix<double, 6, Eigen::Dynamic> none(6, 0);
  const Eigen::VectorXd no_beta(0);
  JointVector q = s.q, qd = s.qd, tau = s.tau;
  int statuses_ok = 0;
  const long n = alloc_counter::during([&] {
    for (int k = 0; k < 10000; ++k) {
      q[k % model.nq] += 1e-4;  // a moving state, as in a control loop
      statuses_ok += achd(model, data, q, qd, tau, s.F_ext, alpha, beta) == Status::Ok;
    }
  });
  EXPECT_EQ(n, 0) << "achd, nc = " << nc;
  EXPECT_EQ(statuses_ok, 10000);
  EXPECT_EQ(alloc_counter::during([&] {
              for (int k = 0; k < 10000; ++k) {
                achd(model, data, q, qd, tau, {}, none, no_beta);
                achd(model, data, q, qd, tau, s.F_ext, singular, singular_beta);
              }
            }),
            0)
      << "achd without constraints / singular";
  EXPECT_EQ(alloc_counter::during([&] {
              for (int k = 0; k < 10000; ++k) {
                rne(model, data, q, qd, s.qdd, s.F_ext);
                forward_kinematics(model, data, q);
                tip_jacobian(model, data, q);
                mass_matrix(model, data, q);
                forward_dynamics(model, data, q, qd, tau, s.F_ext);
              }
            }),
            0)
      << "rne, forward_kinematics, tip_jacobian, mass_matrix, forward_dynamics";
}

// The arm solve step packs the engaged columns of one-sided constraints into
// setup-sized storage: engaging and disengaging rows allocates nothing.
TEST_F(NoAllocation, ArmSolveWithOneSidedRows) {
  const Chain chain = chain_from_urdf(testing::kToyUrdf, "world", "tool");
  const AchdModel model(chain, Vec3(0.0, 0.0, -9.81));
  AchdData data(model);
  steps::ArmWorkspace ws(model, 3);
  ws.alpha_To_B(2, 0) = ws.alpha_To_B(3, 1) = ws.alpha_To_B(5, 2) = 1.0;
  ws.beta << 0.5, 7.0, -1.0;
  std::vector<double> q(static_cast<size_t>(model.nq), 0.3), qd(q.size(), 0.1), tau(q.size());
  int disengaged = 0;
  const long n = alloc_counter::during([&] {
    for (int k = 0; k < 10000; ++k) {
      q[static_cast<size_t>(k % model.nq)] += 1e-4;
      for (int c = 0; c < 3; ++c) ws.engaged[static_cast<size_t>(c)] = ((k >> c) & 1) != 0;
      disengaged += !ws.engaged[1];
      steps::arm_kinematics(model, data, ws, q, qd);
      steps::arm_solve(model, model, data, ws, tau);
    }
  });
  EXPECT_EQ(n, 0);
  EXPECT_GT(disengaged, 0);
}

// The tool frame's outputs and a force on the tool (the toy arm's tip is a
// tool fixed to its last moving link): read and applied every tick.
TEST_F(NoAllocation, ToolFrameOutputsAndForce) {
  const Chain chain = chain_from_urdf(testing::kToyUrdf, "world", "tool");
  const AchdModel model(chain, Vec3(0.0, 0.0, -9.81));
  AchdData data(model);
  steps::ArmWorkspace ws(model, 3);
  ws.alpha_To_B(3, 0) = ws.alpha_To_B(4, 1) = ws.alpha_To_B(5, 2) = 1.0;
  ws.beta << 0.5, -0.3, 0.2;
  std::vector<double> q(static_cast<size_t>(model.nq), 0.3), qd(q.size(), 0.1), tau(q.size());
  const Pose X_BR = Pose::identity();
  Vec6 F_To;
  F_To << 0.1, 0.2, 0.3, 1.0, 2.0, 3.0;
  double sum = 0.0;
  const long n = alloc_counter::during([&] {
    for (int k = 0; k < 10000; ++k) {
      q[static_cast<size_t>(k % model.nq)] += 1e-4;
      steps::arm_kinematics(model, data, ws, q, qd);
      sum += steps::tip_pose(model, data).p.x() +
             steps::tip_pose_in_chain_root(model, data, X_BR).p.y() +
             steps::tip_twist(model, data)[3];
      ws.F_ext.fill(Vec6::Zero());
      ws.F_ext[static_cast<size_t>(model.nq - 1)] +=
          steps::tip_wrench_at_segment_origin(model, data, F_To);
      steps::arm_solve(model, model, data, ws, tau);
    }
  });
  EXPECT_EQ(n, 0);
  EXPECT_TRUE(std::isfinite(sum));
}

TEST_F(NoAllocation, ToyArm) {
  const Chain chain = chain_from_urdf(testing::kToyUrdf, "world", "tool");
  for (int nc : {1, 3, 5}) run_all_algorithms(chain, nc);
}

TEST_F(NoAllocation, KinovaGen3) {
  const std::string path = std::string(MOSPEC_SHARED_DIR) + "/upstream/kinova/GEN3_URDF_V12.urdf";
  if (!std::ifstream(path)) GTEST_SKIP() << "needs " << path;
  const Chain chain = chain_from_urdf_file(path, "base_link", "EndEffector_Link");
  for (int nc : {5, 6}) run_all_algorithms(chain, nc);
}

// For the record (not a requirement on KDL): how often KDL's ACHD allocates
// per call on the same problem. STYLE.md reports one per segment plus one.
TEST_F(NoAllocation, KdlVereshchaginForComparison) {
  const std::string path = testing::gen3_urdf_path();
  if (path.empty()) GTEST_SKIP() << "needs the Gen3 URDF in " MOSPEC_SHARED_DIR;
  const KDL::Chain chain = testing::fold_fixed_segments(testing::kdl_chain(
      testing::kdl_tree_from_urdf_file(path), testing::kGen3Root, testing::kGen3Tip));
  const unsigned n = chain.getNrOfJoints(), nc = 5;
  KDL::ChainHdSolver_Vereshchagin solver(
      chain, KDL::Twist(KDL::Vector(0, 0, 9.81), KDL::Vector::Zero()), nc);
  KDL::JntArray q(n), qd(n), qdd(n), ff(n), tc(n), beta(nc);
  KDL::Jacobian alpha(nc);
  alpha.data.setIdentity();
  KDL::Wrenches f_ext(chain.getNrOfSegments());
  const long total = alloc_counter::during([&] {
    for (int k = 0; k < 100; ++k) solver.CartToJnt(q, qd, qdd, alpha, beta, f_ext, ff, tc);
  });
  RecordProperty("kdl_allocations_per_call", std::to_string(total / 100));
  std::printf("KDL ChainHdSolver_Vereshchagin: %ld allocations per call (Gen3, nc = 5)\n",
              total / 100);
}

}  // namespace
}  // namespace mospec::runtime
