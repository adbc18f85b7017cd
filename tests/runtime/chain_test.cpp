// Chain model and URDF import: unit checks, then forward kinematics, Jacobians
// and mass matrices against KDL built from the same URDF.
#include <gtest/gtest.h>
#include <unistd.h>

#include <kdl/chaindynparam.hpp>
#include <kdl/chainfksolverpos_recursive.hpp>
#include <kdl/chainjnttojacsolver.hpp>

#include "description/urdf_import.hpp"
#include "kdl_reference.hpp"
#include "runtime/crba.hpp"
#include "runtime/kinematics.hpp"
#include "support/diagnostics.hpp"
#include "test_robots.hpp"

namespace mospec::runtime {
namespace {

using namespace mospec::description;  // the chain importers under test

using testing::near;

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(RigidInertia, MergingTwoPointMassesUsesTheParallelAxisTheorem) {
  RigidInertia a{1.0, Vec3(1, 0, 0), Mat3::Zero()};
  RigidInertia b{3.0, Vec3(-1, 0, 0), Mat3::Zero()};
  const RigidInertia s = a + b;
  EXPECT_DOUBLE_EQ(s.mass, 4.0);
  EXPECT_TRUE(near(s.p_SoScm_S, Vec3(-0.5, 0, 0), 1e-15));
  // About the CoM at x = -0.5: 1 kg at 1.5 m and 3 kg at 0.5 m -> 3 kg m^2 about y and z.
  EXPECT_TRUE(near(s.I_Scm_S, Eigen::Vector3d(0, 3, 3).asDiagonal().toDenseMatrix(), 1e-15));
}

TEST(RigidInertia, MergedSpatialInertiaIsTheSum) {
  const RigidInertia a{1.3, Vec3(0.1, -0.2, 0.3),
                       (Mat3() << 0.02, 0.001, 0, 0.001, 0.03, 0.002, 0, 0.002, 0.01).finished()};
  Pose X;
  X.R = Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  X.p = Vec3(0.4, 0.5, -0.6);
  const RigidInertia b =
      RigidInertia{0.4, Vec3(0, 0, 0.1), Mat3::Identity() * 1e-3}.expressed_in(X);
  EXPECT_TRUE(near((a + b).spatial(), a.spatial() + b.spatial(), 1e-14));
  // Massless bodies add only rotational inertia.
  const RigidInertia z{0.0, Vec3::Zero(), Mat3::Identity() * 1e-4};
  EXPECT_TRUE(near((z + z).spatial(), 2.0 * z.spatial(), 1e-15));
}

TEST(Chain, RejectsWhatIsNotAChain) {
  Chain chain("root");
  Segment s;
  s.link = "l";
  s.joint = "j";
  s.axis_J = Vec3(0, 0, 2);
  EXPECT_EQ(error_of([&] { chain.add_segment(s); }),
            "mospec: error: joint 'j': axis must be a unit vector, got norm 2");
  s.axis_J = Vec3::UnitZ();
  s.inertia.mass = -1;
  EXPECT_EQ(error_of([&] { chain.add_segment(s); }),
            "mospec: error: link 'l': mass must be finite and >= 0, got -1 kg");
  s.inertia.mass = 1;
  s.inertia.I_Scm_S = Vec3(1, 1, -1).asDiagonal();
  EXPECT_NE(error_of([&] { chain.add_segment(s); }).find("not positive semi-definite"),
            std::string::npos);
  s.inertia.I_Scm_S.setZero();
  for (int i = 0; i < kMaxSegments; ++i) chain.add_segment(s);
  EXPECT_EQ(error_of([&] { chain.add_segment(s); }),
            "mospec: error: joint 'j' (child link 'l'): a chain holds at most 8 moving joints");
}

TEST(UrdfImport, ErrorsNameTheOffender) {
  EXPECT_EQ(
      error_of([] { chain_from_urdf(testing::kToyUrdf, "world", "nope", "toy.urdf"); }),
      "toy.urdf:1:1: error: robot 'toy' has no link 'nope' (links: base, l1, l2, l2b, l3, l4, "
      "l5, tool, world)");
  EXPECT_EQ(
      error_of([] { chain_from_urdf(testing::kToyUrdf, "l3", "l1", "toy.urdf"); }),
      "toy.urdf:7:3: error: link 'l3' is not an ancestor of link 'l1' (the path from 'l1' ends "
      "at the root link 'world')");
  EXPECT_EQ(error_of([] { chain_from_urdf("<robot name='x'", "a", "b", "x.urdf"); }),
            "x.urdf:1:1: error: unterminated start tag <robot>");
  std::string floating = testing::kToyUrdf;
  floating.replace(floating.find("type=\"prismatic\""), 16, "type=\"floating\"");
  EXPECT_NE(
      error_of([&] {
        chain_from_urdf(floating, "world", "tool", "f.urdf");
      }).find("f.urdf:14:3: error: joint 'j2': only revolute, continuous, prismatic and fixed"),
      std::string::npos);
}

TEST(UrdfImport, FoldsFixedJoints) {
  const Chain chain = chain_from_urdf(testing::kToyUrdf, "world", "tool");
  ASSERT_EQ(chain.size(), 5);
  EXPECT_EQ(chain.root(), "world");
  EXPECT_EQ(chain.tip(), "tool");
  EXPECT_EQ(chain.root_folded_links(), std::vector<std::string>{"base"});
  EXPECT_EQ(chain.segment(1).link, "l2");
  EXPECT_EQ(chain.segment(1).type, JointType::Prismatic);
  EXPECT_EQ(chain.segment(1).folded_links, std::vector<std::string>{"l2b"});
  EXPECT_EQ(chain.segment(4).folded_links, std::vector<std::string>{"tool"});
  EXPECT_EQ(chain.segment(3).limits.lower, -std::numeric_limits<double>::infinity());
  EXPECT_DOUBLE_EQ(chain.segment(0).limits.effort, 50.0);
  EXPECT_NEAR(chain.segment(1).inertia.mass, 2.2, 1e-15);
  EXPECT_FALSE(chain.X_NT().p.isZero());
}

// FK of every segment and of the tip, tip Jacobian and mass matrix equal KDL's
// on 100 random configurations.
void compare_with_kdl(const Chain& chain, const KDL::Chain& kdl, unsigned seed) {
  const AchdModel model(chain);
  AchdData data(model);
  KDL::ChainFkSolverPos_recursive fk(kdl);
  KDL::ChainJntToJacSolver jac(kdl);
  KDL::ChainDynParam dyn(kdl, KDL::Vector(0, 0, -9.81));
  const int n = model.nq;
  ASSERT_EQ(static_cast<int>(kdl.getNrOfJoints()), n);
  // KDL segment index of each moving joint (fixed segments are extra entries).
  std::vector<int> kdl_segment;
  for (unsigned i = 0; i < kdl.getNrOfSegments(); ++i) {
    if (kdl.getSegment(i).getJoint().getType() != KDL::Joint::Fixed) {
      kdl_segment.push_back(static_cast<int>(i));
    }
  }
  std::mt19937 rng(seed);
  for (int trial = 0; trial < 100; ++trial) {
    const auto s = testing::random_state(rng, n);
    const KDL::JntArray q = testing::to_kdl(s.q);
    ASSERT_EQ(forward_kinematics(model, data, s.q), Status::Ok);
    for (int i = 0; i < n; ++i) {
      KDL::Frame F;
      ASSERT_GE(fk.JntToCart(q, F, kdl_segment[static_cast<std::size_t>(i)] + 1), 0);
      const Pose X = testing::from_kdl(F);
      EXPECT_TRUE(near(data.X_BS[static_cast<std::size_t>(i)].R, X.R, 1e-9)) << "segment " << i;
      EXPECT_TRUE(near(data.X_BS[static_cast<std::size_t>(i)].p, X.p, 1e-9)) << "segment " << i;
    }
    KDL::Frame F_tip;
    ASSERT_GE(fk.JntToCart(q, F_tip), 0);
    EXPECT_TRUE(near(data.X_BT.R, testing::from_kdl(F_tip).R, 1e-9));
    EXPECT_TRUE(near(data.X_BT.p, testing::from_kdl(F_tip).p, 1e-9));

    ASSERT_EQ(tip_jacobian(model, data, s.q), Status::Ok);
    KDL::Jacobian J(static_cast<unsigned>(n));
    ASSERT_GE(jac.JntToJac(q, J), 0);
    EXPECT_TRUE(near(Eigen::MatrixXd(data.J_To_B), testing::from_kdl(J), 1e-9)) << trial;

    ASSERT_EQ(mass_matrix(model, data, s.q), Status::Ok);
    KDL::JntSpaceInertiaMatrix H(static_cast<unsigned>(n));
    ASSERT_GE(dyn.JntToMass(q, H), 0);
    EXPECT_TRUE(near(Eigen::MatrixXd(data.H), H.data, 1e-9)) << trial;
  }
}

TEST(ChainVsKdl, ToyArmWithFixedAndPrismaticJoints) {
  const Chain chain = chain_from_urdf(testing::kToyUrdf, "world", "tool");
  const std::string path =
      ::testing::TempDir() + "/mospec_toy_" + std::to_string(::getpid()) + ".urdf";
  {
    std::FILE* f = std::fopen(path.c_str(), "w");
    ASSERT_NE(f, nullptr);
    std::fputs(testing::kToyUrdf.c_str(), f);
    std::fclose(f);
  }
  const KDL::Tree tree = testing::kdl_tree_from_urdf_file(path);
  compare_with_kdl(chain, testing::kdl_chain(tree, "world", "tool"), 7);
}

TEST(ChainVsKdl, KinovaGen3) {
  const std::string path = testing::gen3_urdf_path();
  if (path.empty())
    GTEST_SKIP() << "needs " MOSPEC_SHARED_DIR "/upstream/kinova/GEN3_URDF_V12.urdf";
  const Chain chain = chain_from_urdf_file(path, testing::kGen3Root, testing::kGen3Tip);
  ASSERT_EQ(chain.size(), 7);
  EXPECT_EQ(chain.segment(6).link, "Bracelet_Link");
  EXPECT_EQ(chain.segment(6).folded_links, std::vector<std::string>{"EndEffector_Link"});
  EXPECT_NEAR(chain.X_NT().p.z(), -0.0615250000000001, 1e-15);
  const KDL::Tree tree = testing::kdl_tree_from_urdf_file(path);
  compare_with_kdl(chain, testing::kdl_chain(tree, testing::kGen3Root, testing::kGen3Tip), 42);
}

}  // namespace
}  // namespace mospec::runtime
