// robots/kinova-gen3.jsonld: it is exactly what the generator makes from
// Kinova's URDF, it loads through the project's JSON-LD loader with every term
// defined, and it reads back into the same chain (same kinematics and dynamics),
// both against the authors' metamodels (../shared) and against mospec's own
// (metamodels/, needing nothing from ../shared).
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <vector>

#include "app/app.hpp"
#include "description/chain_jsonld.hpp"
#include "description/chain_rdf.hpp"
#include "description/urdf_import.hpp"
#include "runtime/crba.hpp"
#include "runtime/kinematics.hpp"
#include "runtime/rne.hpp"
#include "support/diagnostics.hpp"
#include "support/io.hpp"
#include "test_robots.hpp"

namespace mospec::runtime {
namespace {

using namespace mospec::description;  // the chain importers under test

using testing::near;

const std::string kModel = std::string(MOSPEC_SOURCE_DIR) + "/robots/kinova-gen3.jsonld";
const std::string kUrdf = std::string(MOSPEC_SHARED_DIR) + "/upstream/kinova/GEN3_URDF_V12.urdf";
const std::string kMetamodels =
    std::string(MOSPEC_SHARED_DIR) + "/upstream/motion-spec-ral/comp-rob2b/metamodels";
const std::string kBase = "https://mospec.example/robots/kinova-gen3/";

#define NEED(path) \
  if (!std::filesystem::exists(path)) GTEST_SKIP() << "needs " << (path)

Chain gen3_from_urdf() {
  return chain_from_urdf_file(kUrdf, "base_link", "EndEffector_Link");
}

TEST(RobotModel, CommittedGen3FileIsTheGeneratorsOutput) {
  NEED(kUrdf);
  ChainJsonldOptions options;
  options.base = kBase;
  const std::string generated = chain_to_jsonld(gen3_from_urdf(), options);
  // MOSPEC_REGENERATE_ROBOTS=1 rewrites the committed file instead of comparing.
  if (const char* regen = std::getenv("MOSPEC_REGENERATE_ROBOTS"); regen && *regen == '1') {
    write_output(kModel, generated);
  }
  EXPECT_EQ(read_file(kModel), generated)
      << "robots/kinova-gen3.jsonld is stale: run this test with MOSPEC_REGENERATE_ROBOTS=1";
}

TEST(RobotModel, PrismaticJointsHaveNoPublishedTerm) {
  const Chain toy = chain_from_urdf(testing::kToyUrdf, "world", "tool");
  try {
    chain_to_jsonld(toy);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(),
                 "mospec: error: joint 'j2': the published kinematic-chain vocabulary has no "
                 "prismatic joint");
  }
}

// mospec's own metamodels (metamodels/): the model needs nothing from ../shared.
const std::string kOwnMetamodels = std::string(MOSPEC_SOURCE_DIR) + "/metamodels";

// The committed model loaded against the given metamodels (default: the authors').
app::LoadedModel load_gen3(const std::string& metamodels = kMetamodels) {
  app::LoadOptions options;
  options.maps.emplace_back("https://comp-rob2b.github.io/metamodels/", metamodels);
  return app::load({kModel}, options);
}

// Same links and joints, and the same kinematics (tip pose and Jacobian) and
// dynamics (mass matrix, inverse dynamics) at random states.
void expect_same_chain(const Chain& loaded, const Chain& expected, double tolerance) {
  ASSERT_EQ(loaded.size(), expected.size());
  EXPECT_EQ(loaded.root(), expected.root());
  EXPECT_EQ(loaded.tip(), expected.tip());
  for (int i = 0; i < expected.size(); ++i) {
    EXPECT_EQ(loaded.segment(i).link, expected.segment(i).link);
    EXPECT_EQ(loaded.segment(i).joint, expected.segment(i).joint);
  }
  const AchdModel a(loaded), b(expected);
  AchdData da(a), db(b);
  std::mt19937 rng(17);
  for (int trial = 0; trial < 20; ++trial) {
    const auto s = testing::random_state(rng, a.nq);
    tip_jacobian(a, da, s.q);
    tip_jacobian(b, db, s.q);
    EXPECT_TRUE(near(da.X_BT.p, db.X_BT.p, tolerance));
    EXPECT_TRUE(near(da.X_BT.R, db.X_BT.R, tolerance));
    EXPECT_TRUE(near(Eigen::MatrixXd(da.J_To_B), Eigen::MatrixXd(db.J_To_B), tolerance));
    mass_matrix(a, da, s.q);
    mass_matrix(b, db, s.q);
    EXPECT_TRUE(near(Eigen::MatrixXd(da.H), Eigen::MatrixXd(db.H), tolerance));
    rne(a, da, s.q, s.qd, s.qdd, s.F_ext);
    rne(b, db, s.q, s.qd, s.qdd, s.F_ext);
    EXPECT_TRUE(near(Eigen::VectorXd(da.tau), Eigen::VectorXd(db.tau), tolerance));
  }
}

TEST(RobotModel, LoadsWithEveryTermDefined) {
  NEED(kMetamodels);
  const app::LoadedModel model = load_gen3();
  for (const auto& d : model.diagnostics().diagnostics()) ADD_FAILURE() << format(d);
  EXPECT_GT(model.dataset().size(), 600u);
}

// The chain read back from the loaded graph has the URDF chain's kinematics
// and dynamics (the RDF literals carry 16 significant digits, so not bit-equal).
TEST(RobotModel, ReadsBackIntoTheSameChain) {
  NEED(kMetamodels);
  NEED(kUrdf);
  const rdf::Dataset graph = load_gen3().flattened();
  const Chain loaded = chain_from_rdf(graph, kBase + "chain");
  const Chain urdf = gen3_from_urdf();
  EXPECT_EQ(loaded.root(), "base_link");
  EXPECT_EQ(loaded.tip(), "EndEffector_Link");
  expect_same_chain(loaded, urdf, 1e-12);
}

// The same model against mospec's own metamodels (no ../shared needed): every
// term defined, and it reads back into the URDF's chain: its links, joints and
// masses, and its tip position and joint-space inertia at q = 0 (reference values
// from the URDF chain; with ../shared present the test also compares the whole
// chain with the URDF's and with the one read through the authors' metamodels).
TEST(RobotModelOwnMetamodels, LoadsWithEveryTermDefined) {
  const app::LoadedModel model = load_gen3(kOwnMetamodels);
  for (const auto& d : model.diagnostics().diagnostics()) ADD_FAILURE() << format(d);
  EXPECT_GT(model.dataset().size(), 600u);
}

TEST(RobotModelOwnMetamodels, ReadsBackIntoTheSameChain) {
  const Chain loaded = chain_from_rdf(load_gen3(kOwnMetamodels).flattened(), kBase + "chain");
  struct Expected {
    const char* link;
    const char* joint;
    double mass;  // kg, the URDF's link masses
  };
  const Expected segments[] = {
      {"Shoulder_Link", "Actuator1", 1.3773},        {"HalfArm1_Link", "Actuator2", 1.1636},
      {"HalfArm2_Link", "Actuator3", 1.1636},        {"ForeArm_Link", "Actuator4", 0.9302},
      {"SphericalWrist1_Link", "Actuator5", 0.6781}, {"SphericalWrist2_Link", "Actuator6", 0.6781},
      {"Bracelet_Link", "Actuator7", 0.5006},
  };
  ASSERT_EQ(loaded.size(), 7);
  EXPECT_EQ(loaded.root(), "base_link");
  EXPECT_EQ(loaded.tip(), "EndEffector_Link");
  for (int i = 0; i < 7; ++i) {
    EXPECT_EQ(loaded.segment(i).link, segments[i].link);
    EXPECT_EQ(loaded.segment(i).joint, segments[i].joint);
    EXPECT_EQ(loaded.segment(i).type, JointType::Revolute);
    EXPECT_NEAR(loaded.segment(i).inertia.mass, segments[i].mass, 1e-12);
  }
  const AchdModel model(loaded);
  AchdData data(model);
  const Eigen::VectorXd q = Eigen::VectorXd::Zero(model.nq);
  tip_jacobian(model, data, q);
  mass_matrix(model, data, q);
  EXPECT_TRUE(near(data.X_BT.p, Vec3(0.0, -0.024859601294874054, 1.1873847699190927), 1e-12));
  const double diagonal[] = {0.0082209332893274176, 1.5188724873808117,    0.0039231400401279837,
                             0.25673264835153947,   0.0016049686641863529, 0.012634920650303319,
                             0.00067412033323899993};
  for (int i = 0; i < 7; ++i)
    EXPECT_NEAR(data.H(i, i), diagonal[i], 1e-12) << "H(" << i << ", " << i << ")";
  if (std::filesystem::exists(kMetamodels)) {
    expect_same_chain(loaded, chain_from_rdf(load_gen3().flattened(), kBase + "chain"), 0.0);
  }
  if (std::filesystem::exists(kUrdf)) expect_same_chain(loaded, gen3_from_urdf(), 1e-12);
}

// Without any mapping the model resolves the published IRIs to mospec's
// metamodels by itself (app::builtin_metamodels_dir()) and gives the same graph.
TEST(RobotModelOwnMetamodels, BuiltinFallbackGivesTheSameGraph) {
  if (const char* env = std::getenv("MOSPEC_METAMODELS_DIR"); env != nullptr && *env != '\0') {
    GTEST_SKIP() << "MOSPEC_METAMODELS_DIR is set";
  }
  const app::LoadedModel builtin = app::load({kModel}, app::LoadOptions{});
  for (const auto& d : builtin.diagnostics().diagnostics()) ADD_FAILURE() << format(d);
  const Chain a = chain_from_rdf(builtin.flattened(), kBase + "chain");
  const Chain b = chain_from_rdf(load_gen3(kOwnMetamodels).flattened(), kBase + "chain");
  EXPECT_EQ(builtin.dataset().size(), load_gen3(kOwnMetamodels).dataset().size());
  expect_same_chain(a, b, 0.0);
}

TEST(RobotModel, ReadingNamesWhatIsWrong) {
  NEED(kMetamodels);
  const rdf::Dataset graph = load_gen3().flattened();
  try {
    chain_from_rdf(graph, kBase + "no-such-chain");
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(),
                 "mospec: error: no KinematicChain named "
                 "<https://mospec.example/robots/kinova-gen3/no-such-chain> in the model");
  }
}

TEST(RobotModel, WrongUnitsAreRejectedNotConverted) {
  NEED(kMetamodels);
  std::string text = read_file(kModel);
  const std::string from = "\"unit\": \"KiloGM\"";
  text.replace(text.find(from), from.size(), "\"unit\": \"GM\"");
  const std::string path =
      ::testing::TempDir() + "/mospec-gen3-grams-" + std::to_string(::getpid()) + ".jsonld";
  write_output(path, text);
  app::LoadOptions options;
  options.maps.emplace_back("https://comp-rob2b.github.io/metamodels/", kMetamodels);
  const rdf::Dataset graph = app::load({path}, options).flattened();
  try {
    chain_from_rdf(graph, kBase + "chain");
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(),
                 "mospec: error: https://mospec.example/robots/kinova-gen3/mass-Shoulder_Link: "
                 "unit must be {http://qudt.org/vocab/unit/KiloGM}, got "
                 "{http://qudt.org/vocab/unit/GM}");
  }
}

// robots/ur5e.jsonld: the UR5e written for mospec (robots/ur5e.urdf, from
// Universal Robots' published DH and dynamics parameters). Both files are in
// the repository, so these tests need nothing from ../shared.
const std::string kUr5eUrdf = std::string(MOSPEC_SOURCE_DIR) + "/robots/ur5e.urdf";
const std::string kUr5eModel = std::string(MOSPEC_SOURCE_DIR) + "/robots/ur5e.jsonld";
const std::string kUr5eBase = "https://mospec.example/robots/ur5e/";

Chain ur5e_from_urdf() {
  return chain_from_urdf_file(kUr5eUrdf, "base_link", "wrist_3_link");
}

Chain ur5e_from_jsonld() {
  app::LoadOptions options;
  options.maps.emplace_back("https://comp-rob2b.github.io/metamodels/", kOwnMetamodels);
  const app::LoadedModel model = app::load({kUr5eModel}, options);
  for (const auto& d : model.diagnostics().diagnostics()) ADD_FAILURE() << format(d);
  return chain_from_rdf(model.flattened(), kUr5eBase + "chain");
}

// The committed file is what `mospec import-urdf robots/ur5e.urdf --base
// https://mospec.example/robots/ur5e/` writes (the command's defaults: the
// URDF's root link to its only leaf).
TEST(RobotModelUr5e, CommittedFileIsTheGeneratorsOutput) {
  ChainJsonldOptions options;
  options.base = kUr5eBase;
  const std::string generated = chain_to_jsonld(chain_from_urdf_file(kUr5eUrdf, "", ""), options);
  // MOSPEC_REGENERATE_ROBOTS=1 rewrites the committed file instead of comparing.
  if (const char* regen = std::getenv("MOSPEC_REGENERATE_ROBOTS"); regen && *regen == '1') {
    write_output(kUr5eModel, generated);
  }
  EXPECT_EQ(read_file(kUr5eModel), generated)
      << "robots/ur5e.jsonld is stale: run this test with MOSPEC_REGENERATE_ROBOTS=1";
}

TEST(RobotModelUr5e, IsSixRevoluteJointsWithThePublishedMasses) {
  const Chain chain = ur5e_from_jsonld();
  const char* const joints[] = {"shoulder_pan_joint", "shoulder_lift_joint", "elbow_joint",
                                "wrist_1_joint",      "wrist_2_joint",       "wrist_3_joint"};
  const double masses[] = {3.761, 8.058, 2.846, 1.37, 1.3, 0.365};  // kg, UR's DH article
  ASSERT_EQ(chain.size(), 6);
  EXPECT_EQ(chain.root(), "base_link");
  EXPECT_EQ(chain.tip(), "wrist_3_link");
  for (int i = 0; i < 6; ++i) {
    EXPECT_EQ(chain.segment(i).joint, joints[i]);
    EXPECT_EQ(chain.segment(i).type, JointType::Revolute);
    EXPECT_NEAR(chain.segment(i).inertia.mass, masses[i], 1e-12);
  }
  expect_same_chain(chain, ur5e_from_urdf(), 1e-12);
}

// Universal Robots' standard DH chain, frame i = frame i-1 * Rz(q_i) Tz(d_i)
// Tx(a_i) Rx(alpha_i), written out independently of the URDF: frame 6 is the
// tool flange.
Pose ur5e_dh_flange(const Eigen::VectorXd& q) {
  const double pi = std::acos(-1.0);
  const double a[6] = {0, -0.425, -0.3922, 0, 0, 0};
  const double d[6] = {0.1625, 0, 0, 0.1333, 0.0997, 0.0996};
  const double alpha[6] = {pi / 2, 0, 0, pi / 2, -pi / 2, 0};
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  for (int i = 0; i < 6; ++i) {
    const double ct = std::cos(q[i]), st = std::sin(q[i]);
    const double ca = std::cos(alpha[i]), sa = std::sin(alpha[i]);
    Eigen::Matrix4d A;
    A << ct, -st * ca, st * sa, a[i] * ct,  //
        st, ct * ca, -ct * sa, a[i] * st,   //
        0, sa, ca, d[i],                    //
        0, 0, 0, 1;
    T = T * A;
  }
  Pose X;
  X.R = T.topLeftCorner<3, 3>();
  X.p = T.topRightCorner<3, 1>();
  return X;
}

// The chain's tip (the URDF's and the JSON-LD model's) is the DH chain's frame
// 6 at zero, at the scenario's initial configuration (models/ur5e.world.json)
// and at random configurations.
TEST(RobotModelUr5e, ForwardKinematicsIsThePublishedDhChain) {
  for (const Chain& chain : {ur5e_from_urdf(), ur5e_from_jsonld()}) {
    const AchdModel model(chain);
    AchdData data(model);
    std::vector<Eigen::VectorXd> configurations;
    configurations.push_back(Eigen::VectorXd::Zero(6));
    Eigen::VectorXd q0(6);
    q0 << 0, -1.4081, -2.0773, -2.7978, -1.5708, 0;
    configurations.push_back(q0);
    std::mt19937 rng(5);
    for (int trial = 0; trial < 10; ++trial)
      configurations.push_back(testing::random_state(rng, 6).q);
    for (const Eigen::VectorXd& q : configurations) {
      forward_kinematics(model, data, q);
      const Pose expected = ur5e_dh_flange(q);
      EXPECT_TRUE(near(data.X_BT.p, expected.p, 1e-9)) << "q = " << q.transpose();
      EXPECT_TRUE(near(data.X_BT.R, expected.R, 1e-9)) << "q = " << q.transpose();
    }
  }
}

// The published DH table at zero: the arm stretched along -x of the base, the
// flange at (-(0.425 + 0.3922), -(0.1333 + 0.0996), 0.1625 - 0.0997).
TEST(RobotModelUr5e, ZeroConfigurationIsTheStretchedArm) {
  const AchdModel model(ur5e_from_jsonld());
  AchdData data(model);
  forward_kinematics(model, data, Eigen::VectorXd::Zero(6));
  EXPECT_TRUE(near(data.X_BT.p, Vec3(-0.8172, -0.2329, 0.0628), 1e-12));
}

}  // namespace
}  // namespace mospec::runtime
