// robots/kinova-gen3.jsonld: it is exactly what the generator makes from
// Kinova's URDF, it loads through the project's JSON-LD loader with every term
// defined, and it reads back into the same chain (same kinematics and dynamics),
// both against the authors' metamodels (../shared) and against mospec's own
// (metamodels/, needing nothing from ../shared).
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
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
#include "vocab/metamodels.hpp"
#include "vocab/w3c.hpp"

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
  // The Gen3's description loads against the authors' metamodels, which have
  // no joint extension: its limits are the world's default actuation instead.
  options.limits = false;
  const std::string generated = chain_to_jsonld(gen3_from_urdf(), options);
  // MOSPEC_REGENERATE_ROBOTS=1 rewrites the committed file instead of comparing.
  if (const char* regen = std::getenv("MOSPEC_REGENERATE_ROBOTS"); regen && *regen == '1') {
    write_output(kModel, generated);
  }
  EXPECT_EQ(read_file(kModel), generated)
      << "robots/kinova-gen3.jsonld is stale: run this test with MOSPEC_REGENERATE_ROBOTS=1";
}

// mospec's own metamodels (metamodels/): the model needs nothing from ../shared.
const std::string kOwnMetamodels = std::string(MOSPEC_SOURCE_DIR) + "/metamodels";

// The committed model loaded against the given metamodels (default: the authors').
app::LoadedModel load_gen3(const std::string& metamodels = kMetamodels) {
  app::LoadOptions options;
  options.maps.emplace_back("https://comp-rob2b.github.io/metamodels/", metamodels);
  return app::load({kModel}, options);
}

// `text` written to a scratch file named after `tag` and loaded against
// `metamodels` (an edited robot description, for the reader's refusals).
app::LoadedModel load_text(const std::string& text, const std::string& tag,
                           const std::string& metamodels) {
  const std::string path =
      ::testing::TempDir() + "/mospec-" + tag + "-" + std::to_string(::getpid()) + ".jsonld";
  write_output(path, text);
  app::LoadOptions options;
  options.maps.emplace_back("https://comp-rob2b.github.io/metamodels/", metamodels);
  return app::load({path}, options);
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

// Prismatic joints (mospec/joints: PrismaticJoint). A vertical lift carrying a
// revolute wrist, written by the test: base -(lift, prismatic z)-> carriage
// -(wrist, revolute, offset and tilted)-> hand -(fixed)-> tool.
const std::string kLiftUrdf = R"(<robot name="lift">
  <link name="base"/>
  <link name="carriage"><inertial><origin xyz="0.02 0 0.05" rpy="0 0 0.3"/><mass value="4"/>
    <inertia ixx="0.04" ixy="0.002" ixz="0" iyy="0.03" iyz="0" izz="0.02"/></inertial></link>
  <joint name="lift" type="prismatic"><parent link="base"/><child link="carriage"/>
    <origin xyz="0 0 0.3"/><axis xyz="0 0 1"/>
    <limit lower="0" upper="0.5" effort="400" velocity="0.3"/></joint>
  <link name="hand"><inertial><origin xyz="0.1 0 0"/><mass value="1.2"/>
    <inertia ixx="0.002" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/></inertial></link>
  <joint name="wrist" type="revolute"><parent link="carriage"/><child link="hand"/>
    <origin xyz="0.15 0 0.1" rpy="0 0.2 0"/><axis xyz="0 0 1"/>
    <limit lower="-2" upper="2" effort="20" velocity="2"/></joint>
  <link name="tool"/>
  <joint name="tool_joint" type="fixed"><parent link="hand"/><child link="tool"/>
    <origin xyz="0.2 0 0"/></joint>
</robot>
)";
const std::string kLiftBase = "https://mospec.example/robots/lift/";

// `chain` written as JSON-LD (base kLiftBase), loaded against mospec's
// metamodels with every term defined, and read back.
Chain round_trip(const Chain& chain, std::string* document = nullptr) {
  ChainJsonldOptions options;
  options.base = kLiftBase;
  const std::string text = chain_to_jsonld(chain, options);
  if (document != nullptr) *document = text;
  const app::LoadedModel model = load_text(text, "prismatic", kOwnMetamodels);
  for (const auto& d : model.diagnostics().diagnostics()) ADD_FAILURE() << format(d);
  return chain_from_rdf(model.flattened(), kLiftBase + "chain");
}

// Joint types, axes, joint poses, inertias and the tip pose, to the 17
// significant digits the document carries.
void expect_same_segments(const Chain& loaded, const Chain& expected) {
  ASSERT_EQ(loaded.size(), expected.size());
  for (int i = 0; i < expected.size(); ++i) {
    const Segment &a = loaded.segment(i), &b = expected.segment(i);
    SCOPED_TRACE("segment " + b.link);
    EXPECT_EQ(a.type, b.type);
    EXPECT_TRUE(near(a.axis_J, b.axis_J, 1e-15));
    EXPECT_TRUE(near(a.X_PJ.R, b.X_PJ.R, 1e-15));
    EXPECT_TRUE(near(a.X_PJ.p, b.X_PJ.p, 1e-15));
    EXPECT_NEAR(a.inertia.mass, b.inertia.mass, 1e-15);
    EXPECT_TRUE(near(a.inertia.p_SoScm_S, b.inertia.p_SoScm_S, 1e-15));
    EXPECT_TRUE(near(a.inertia.I_Scm_S, b.inertia.I_Scm_S, 1e-15));
  }
  EXPECT_TRUE(near(loaded.X_NT().R, expected.X_NT().R, 1e-15));
  EXPECT_TRUE(near(loaded.X_NT().p, expected.X_NT().p, 1e-15));
}

TEST(RobotModelPrismatic, LiftReadsBackIntoTheSameChain) {
  const Chain urdf = chain_from_urdf(kLiftUrdf, "base", "tool");
  ASSERT_EQ(urdf.size(), 2);
  ASSERT_EQ(urdf.segment(0).type, JointType::Prismatic);
  std::string document;
  const Chain loaded = round_trip(urdf, &document);
  // The extension's context is listed, once, and the lift is a PrismaticJoint.
  const std::string context = "\"https://comp-rob2b.github.io/metamodels/mospec/joints.json\"";
  ASSERT_NE(document.find(context), std::string::npos);
  EXPECT_EQ(document.find(context, document.find(context) + 1), std::string::npos);
  EXPECT_NE(document.find("\"@type\": [ \"Joint\", \"PrismaticJoint\" ]"), std::string::npos);
  EXPECT_EQ(loaded.root(), "base");
  EXPECT_EQ(loaded.tip(), "tool");
  EXPECT_EQ(loaded.segment(0).joint, "lift");
  EXPECT_EQ(loaded.segment(1).joint, "wrist");
  EXPECT_EQ(loaded.segment(0).type, JointType::Prismatic);
  EXPECT_EQ(loaded.segment(1).type, JointType::Revolute);
  expect_same_segments(loaded, urdf);
  expect_same_chain(loaded, urdf, 1e-12);
  // The lift raises the tool: q = (0.25 m, 0) puts it 0.25 m higher.
  const AchdModel model(loaded);
  AchdData data(model);
  Eigen::VectorXd q = Eigen::VectorXd::Zero(2);
  tip_jacobian(model, data, q);
  const Vec3 p0 = data.X_BT.p;
  q(0) = 0.25;
  tip_jacobian(model, data, q);
  EXPECT_TRUE(near(data.X_BT.p - p0, Vec3(0, 0, 0.25), 1e-15));
}

// The toy arm: a prismatic joint between revolute ones, off-axis and behind
// folded fixed joints.
TEST(RobotModelPrismatic, ToyArmReadsBackIntoTheSameChain) {
  const Chain toy = chain_from_urdf(testing::kToyUrdf, "world", "tool");
  const Chain loaded = round_trip(toy);
  expect_same_segments(loaded, toy);
  expect_same_chain(loaded, toy, 1e-12);
}

// An all-revolute chain without joint limits uses the comp-rob2b vocabulary
// alone; its limits are the published secorolab extension's kc-ext:JointLimit
// (not mospec's joint extension), typed by kc-stat's quantity kinds.
TEST(RobotModelPrismatic, RevoluteChainsNeedNoExtension) {
  Chain chain = chain_from_urdf(kLiftUrdf, "base", "tool");
  Chain revolute("base"), limited("base");
  for (int i = 0; i < chain.size(); ++i) {
    Segment s = chain.segment(i);
    s.type = JointType::Revolute;
    limited.add_segment(s);
    s.limits = JointLimits{};
    revolute.add_segment(s);
  }
  EXPECT_EQ(chain_to_jsonld(revolute).find("mospec/joints"), std::string::npos);
  EXPECT_EQ(chain_to_jsonld(revolute).find("PrismaticJoint"), std::string::npos);
  const std::string text = chain_to_jsonld(limited);
  EXPECT_EQ(text.find("mospec/joints.json"), std::string::npos);
  EXPECT_NE(text.find("\"https://secorolab.github.io/metamodels/kinematic-chain/"
                      "structural-entities-extension.json\""),
            std::string::npos);
  EXPECT_NE(text.find("kinematic-chain/state.json"), std::string::npos);
  EXPECT_NE(text.find("\"@type\": [ \"JointLimit\", \"kc-stat:JointForce\" ]"), std::string::npos);
  EXPECT_EQ(text.find("JointEffortLimit"), std::string::npos);
}

// The limits read back as written: position lower..upper, velocity and effort
// as magnitudes (-limit..limit in the document).
TEST(RobotModelPrismatic, LimitsReadBackAsJointLimits) {
  const Chain urdf = chain_from_urdf(kLiftUrdf, "base", "tool");
  std::string document;
  const Chain loaded = round_trip(urdf, &document);
  EXPECT_NE(document.find("\"lower\": { \"@type\": \"Quantity\", \"quantity-kind\": "
                          "\"LinearVelocity\", \"unit\": \"M-PER-SEC\", \"value\": -0.3 }"),
            std::string::npos)
      << document;
  for (int i = 0; i < urdf.size(); ++i) {
    SCOPED_TRACE("segment " + urdf.segment(i).link);
    const JointLimits &a = loaded.segment(i).limits, &b = urdf.segment(i).limits;
    EXPECT_EQ(a.lower, b.lower);
    EXPECT_EQ(a.upper, b.upper);
    EXPECT_EQ(a.velocity, b.velocity);
    EXPECT_EQ(a.effort, b.effort);
  }
  EXPECT_EQ(loaded.segment(0).limits.upper, 0.5);
  EXPECT_EQ(loaded.segment(1).limits.effort, 20.0);
}

// Limits mospec would not honour as stated are refused, naming the limit.
TEST(RobotModelPrismatic, ReadingRefusesLimitsItCannotHonour) {
  ChainJsonldOptions options;
  options.base = kLiftBase;
  const std::string text = chain_to_jsonld(chain_from_urdf(kLiftUrdf, "base", "tool"), options);
  const std::string effort_lower =
      "\"lower\": { \"@type\": \"Quantity\", \"quantity-kind\": \"Torque\", \"unit\": "
      "\"N-M\", \"value\": -20 }";
  const std::string velocity_type = "[ \"JointLimit\", \"kc-stat:JointVelocity\" ]";
  const std::string position_type =
      "\"@id\": \"position-limit-wrist\",\n            "
      "\"@type\": [ \"JointLimit\", \"kc-stat:JointPosition\" ]";
  struct Case {
    std::string from, to, message;
  } cases[] = {
      {effort_lower,
       "\"lower\": { \"@type\": \"Quantity\", \"quantity-kind\": \"Torque\", "
       "\"unit\": \"N-M\", \"value\": -5 }",
       "effort-limit-wrist: mospec bounds a joint's effort by one magnitude (|x| <= upper), so "
       "its lower limit must be -upper"},
      {velocity_type, "[ \"JointLimit\", \"kc-stat:JointAcceleration\" ]",
       "velocity-limit-lift: mospec enforces no joint acceleration limit"},
      {velocity_type, "[ \"JointLimit\" ]",
       "velocity-limit-lift: a JointLimit is typed also by exactly one kind of quantity"},
      {effort_lower,
       "\"lower\": { \"@type\": \"Quantity\", \"quantity-kind\": \"Torque\", "
       "\"unit\": \"N\", \"value\": -20 }",
       "unit must be {http://qudt.org/vocab/unit/N-M}"},
      {position_type,
       "\"@id\": \"position-limit-wrist\",\n            \"@type\": [ "
       "\"JointPositionLimits\" ]",
       "position-limit-wrist: JointPositionLimits (mos-jnt) is retired; a joint limit is the "
       "published kc-ext:JointLimit"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.to);
    std::string edited = text;
    const size_t at = edited.find(c.from);
    ASSERT_NE(at, std::string::npos) << c.from;
    edited.replace(at, c.from.size(), c.to);
    // The retired class needs mospec's joint extension, which names it.
    const std::string ctx = "\"https://comp-rob2b.github.io/metamodels/qudt.json\",";
    edited.replace(edited.find(ctx), ctx.size(),
                   ctx + "\"https://comp-rob2b.github.io/metamodels/mospec/joints.json\",");
    const rdf::Dataset graph = load_text(edited, "lift-limit", kOwnMetamodels).flattened();
    try {
      chain_from_rdf(graph, kLiftBase + "chain");
      ADD_FAILURE() << "no error";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(c.message), std::string::npos) << e.what();
    }
  }
}

// A joint of the chain that is neither or both kinds is refused, by name.
TEST(RobotModelPrismatic, ReadingNamesAJointOfNeitherOrBothKinds) {
  ChainJsonldOptions options;
  options.base = kLiftBase;
  const std::string text = chain_to_jsonld(chain_from_urdf(kLiftUrdf, "base", "tool"), options);
  const std::string lift = "\"Joint\", \"PrismaticJoint\" ]";
  const std::string cases[][2] = {
      {"\"Joint\" ]", "only RevoluteJoint and PrismaticJoint (mospec/joints) are supported"},
      {"\"Joint\", \"PrismaticJoint\", \"RevoluteJoint\" ]",
       "is both a RevoluteJoint and a PrismaticJoint"}};
  for (const auto& [type, message] : cases) {
    std::string edited = text;
    edited.replace(edited.find(lift), lift.size(), type);
    const rdf::Dataset graph = load_text(edited, "lift-bad", kOwnMetamodels).flattened();
    try {
      chain_from_rdf(graph, kLiftBase + "chain");
      ADD_FAILURE() << "no error for " << type;
    } catch (const Error& e) {
      EXPECT_EQ(std::string(e.what()), "mospec: error: " + kLiftBase + "joint-lift: " + message +
                                           "; state exactly one of them");
    }
  }
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
  const rdf::Dataset graph = load_text(text, "gen3-grams", kMetamodels).flattened();
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
// Lowering reads a chain in place from some graphs of the dataset
// (describe_chain with graphs): a triple stated in two of the graphs read
// counts once there, while reading the whole dataset counts every statement
// (the errors below). Each case restates the statements of one property of
// the UR5e in a second graph; `via` first follows a property to a list node.
TEST(RobotModelUr5e, RestatedPropertiesCountOnceAmongTheGraphsRead) {
  app::LoadOptions options;
  options.maps.emplace_back("https://comp-rob2b.github.io/metamodels/", kOwnMetamodels);
  using vocab::term;
  const std::string z = term(vocab::geom_coord::ns, "z"), x = term(vocab::geom_coord::ns, "x");
  const std::string unit = term(vocab::qudt::ns, "unit"), u = "http://qudt.org/vocab/unit/";
  const std::string dcx = term(vocab::geom_coord::ns, "direction-cosine-x");
  struct Case {
    std::string subject, via, predicate, unfiltered_error;  // error empty: reads the same
  };
  const Case cases[] = {
      {"axis-shoulder_pan_joint", "", z,
       "axis-shoulder_pan_joint: expected exactly one <" + z + ">, found 2"},
      {"pose-shoulder_pan_joint", "", x,
       "pose-shoulder_pan_joint: expected exactly one <" + x + ">, found 2"},
      {"pose-shoulder_pan_joint", "", unit,
       "pose-shoulder_pan_joint: unit must be {" + u + "M, " + u + "UNITLESS}, got {" + u + "M, " +
           u + "M, " + u + "UNITLESS, " + u + "UNITLESS}"},
      {"pose-shoulder_pan_joint", dcx, std::string(vocab::rdf::first),
       ": expected exactly one <" + std::string(vocab::rdf::first) + ">, found 2"},
      {"inertia-shoulder_link", "", term(vocab::dyn_coord::ns, "ixx"),
       "inertia-shoulder_link: expected exactly one <" + term(vocab::dyn_coord::ns, "ixx") +
           ">, found 2"},
      {"mass-shoulder_link", "", unit,
       "mass-shoulder_link: unit must be {" + u + "KiloGM}, got {" + u + "KiloGM, " + u +
           "KiloGM}"},
      {"joint-shoulder_pan_joint", "", term(vocab::kc_ent::ns, "common-axis"),
       "joint-shoulder_pan_joint: expected exactly one <" + term(vocab::kc_ent::ns, "common-axis") +
           ">, found 2"},
      {"frame-shoulder_link", "", term(vocab::geom_ent::ns, "origin"), ""},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.subject + " " + c.via + " " + c.predicate);
    app::LoadedModel model = app::load({kUr5eModel}, options);
    rdf::Dataset& ds = model.dataset();
    std::vector<rdf::TermId> graphs;
    for (const rdf::Quad& q : ds.quads()) {
      if (std::find(graphs.begin(), graphs.end(), q.graph) == graphs.end())
        graphs.push_back(q.graph);
    }
    const ChainDescription before = describe_chain(ds, graphs, kUr5eBase + "chain");
    rdf::TermId s = ds.terms().find_iri(kUr5eBase + c.subject);
    if (!c.via.empty()) {
      const auto head = ds.match(s, ds.terms().find_iri(c.via), rdf::TermId::any());
      ASSERT_FALSE(head.empty());
      s = ds.quads()[head[0]].object;
    }
    std::vector<rdf::Quad> restated;
    for (uint32_t i : ds.match(s, ds.terms().find_iri(c.predicate), rdf::TermId::any())) {
      restated.push_back(ds.quads()[i]);
    }
    ASSERT_FALSE(restated.empty());
    const rdf::TermId again = ds.terms().iri("https://mospec.example/restated");
    for (rdf::Quad q : restated) {
      q.graph = again;
      ASSERT_TRUE(ds.add(q));
    }
    graphs.push_back(again);
    const ChainDescription after = describe_chain(ds, graphs, kUr5eBase + "chain");
    expect_same_chain(after.chain, before.chain, 0.0);
    EXPECT_EQ(after.frames.root.origin, before.frames.root.origin);
    ASSERT_EQ(after.frames.segments.size(), before.frames.segments.size());
    for (size_t i = 0; i < before.frames.segments.size(); ++i) {
      EXPECT_EQ(after.frames.segments[i].origin, before.frames.segments[i].origin);
      EXPECT_EQ(after.frames.segments[i].body, before.frames.segments[i].body);
    }
    if (c.unfiltered_error.empty()) {
      const ChainDescription all = describe_chain(ds, kUr5eBase + "chain");
      expect_same_chain(all.chain, before.chain, 0.0);
      EXPECT_EQ(all.frames.segments[0].origin, before.frames.segments[0].origin);
      continue;
    }
    try {
      describe_chain(ds, kUr5eBase + "chain");
      ADD_FAILURE() << "no error";
    } catch (const Error& e) {
      EXPECT_EQ(e.code(), "invalid-robot-model");
      const std::string what = e.what();
      if (c.via.empty()) {
        EXPECT_EQ(what, "mospec: error: " + kUr5eBase + c.unfiltered_error);
      } else {  // the list node is a blank node
        EXPECT_NE(what.find(c.unfiltered_error), std::string::npos) << what;
      }
    }
  }
}

// A property with two different values is an error however the chain is read.
TEST(RobotModelUr5e, APropertyGivenTwiceIsNamedWithItsCount) {
  app::LoadOptions options;
  options.maps.emplace_back("https://comp-rob2b.github.io/metamodels/", kOwnMetamodels);
  app::LoadedModel model = app::load({kUr5eModel}, options);
  rdf::Dataset& ds = model.dataset();
  const std::string z = vocab::term(vocab::geom_coord::ns, "z");
  const rdf::TermId axis = ds.terms().find_iri(kUr5eBase + "axis-elbow_joint");
  const auto stated = ds.match(axis, ds.terms().find_iri(z), rdf::TermId::any());
  ASSERT_EQ(stated.size(), 1u);
  rdf::Quad q = ds.quads()[stated[0]];
  const rdf::TermId graph = q.graph;
  q.object = ds.terms().literal("2", "http://www.w3.org/2001/XMLSchema#integer");
  ASSERT_TRUE(ds.add(q));
  const std::string message =
      "mospec: error: " + kUr5eBase + "axis-elbow_joint: expected exactly one <" + z + ">, found 2";
  for (bool whole : {true, false}) {
    try {
      whole ? describe_chain(ds, kUr5eBase + "chain")
            : describe_chain(ds, std::span(&graph, 1), kUr5eBase + "chain");
      ADD_FAILURE() << "no error";
    } catch (const Error& e) {
      EXPECT_EQ(std::string(e.what()), message);
    }
  }
}

TEST(RobotModelUr5e, ZeroConfigurationIsTheStretchedArm) {
  const AchdModel model(ur5e_from_jsonld());
  AchdData data(model);
  forward_kinematics(model, data, Eigen::VectorXd::Zero(6));
  EXPECT_TRUE(near(data.X_BT.p, Vec3(-0.8172, -0.2329, 0.0628), 1e-12));
}

// robots/lift.jsonld: a prismatic lift carrying two revolute joints, the
// robot of models/examples/lift; written by mospec, needs nothing from ../shared.
const std::string kLiftRobotUrdf = std::string(MOSPEC_SOURCE_DIR) + "/robots/lift.urdf";
const std::string kLiftRobotModel = std::string(MOSPEC_SOURCE_DIR) + "/robots/lift.jsonld";

TEST(RobotModelLift, CommittedFileIsTheGeneratorsOutput) {
  ChainJsonldOptions options;
  options.base = kLiftBase;
  const std::string generated =
      chain_to_jsonld(chain_from_urdf_file(kLiftRobotUrdf, "", ""), options);
  // MOSPEC_REGENERATE_ROBOTS=1 rewrites the committed file instead of comparing.
  if (const char* regen = std::getenv("MOSPEC_REGENERATE_ROBOTS"); regen && *regen == '1') {
    write_output(kLiftRobotModel, generated);
  }
  EXPECT_EQ(read_file(kLiftRobotModel), generated)
      << "robots/lift.jsonld is stale: run this test with MOSPEC_REGENERATE_ROBOTS=1";
}

TEST(RobotModelLift, ReadsBackAsALiftAndTwoHinges) {
  app::LoadOptions options;
  options.maps.emplace_back("https://comp-rob2b.github.io/metamodels/", kOwnMetamodels);
  const app::LoadedModel model = app::load({kLiftRobotModel}, options);
  for (const auto& d : model.diagnostics().diagnostics()) ADD_FAILURE() << format(d);
  const Chain loaded = chain_from_rdf(model.flattened(), kLiftBase + "chain");
  ASSERT_EQ(loaded.size(), 3);
  EXPECT_EQ(loaded.segment(0).type, JointType::Prismatic);
  EXPECT_EQ(loaded.segment(1).type, JointType::Revolute);
  EXPECT_EQ(loaded.segment(2).type, JointType::Revolute);
  expect_same_segments(loaded, chain_from_urdf_file(kLiftRobotUrdf, "", ""));
}

}  // namespace
}  // namespace mospec::runtime
