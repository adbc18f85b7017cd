// robots/kinova-gen3.jsonld: it is exactly what the generator makes from
// Kinova's URDF, it loads through the project's JSON-LD loader with every term
// defined, and it reads back into the same chain (same kinematics and dynamics).
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>

#include "app/app.hpp"
#include "runtime/chain_jsonld.hpp"
#include "runtime/chain_rdf.hpp"
#include "runtime/crba.hpp"
#include "runtime/kinematics.hpp"
#include "runtime/rne.hpp"
#include "runtime/urdf_import.hpp"
#include "support/diagnostics.hpp"
#include "support/io.hpp"
#include "test_robots.hpp"

namespace mospec::runtime {
namespace {

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

app::LoadedModel load_gen3() {
  app::LoadOptions options;
  options.maps.emplace_back("https://comp-rob2b.github.io/metamodels/", kMetamodels);
  return app::load({kModel}, options);
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
  ASSERT_EQ(loaded.size(), urdf.size());
  EXPECT_EQ(loaded.root(), "base_link");
  EXPECT_EQ(loaded.tip(), "EndEffector_Link");
  for (int i = 0; i < urdf.size(); ++i) {
    EXPECT_EQ(loaded.segment(i).link, urdf.segment(i).link);
    EXPECT_EQ(loaded.segment(i).joint, urdf.segment(i).joint);
  }
  const AchdModel a(loaded), b(urdf);
  AchdData da(a), db(b);
  std::mt19937 rng(17);
  for (int trial = 0; trial < 20; ++trial) {
    const auto s = testing::random_state(rng, a.nq);
    tip_jacobian(a, da, s.q);
    tip_jacobian(b, db, s.q);
    EXPECT_TRUE(near(da.X_BT.p, db.X_BT.p, 1e-12));
    EXPECT_TRUE(near(da.X_BT.R, db.X_BT.R, 1e-12));
    EXPECT_TRUE(near(Eigen::MatrixXd(da.J_To_B), Eigen::MatrixXd(db.J_To_B), 1e-12));
    mass_matrix(a, da, s.q);
    mass_matrix(b, db, s.q);
    EXPECT_TRUE(near(Eigen::MatrixXd(da.H), Eigen::MatrixXd(db.H), 1e-12));
    rne(a, da, s.q, s.qd, s.qdd, s.F_ext);
    rne(b, db, s.q, s.qd, s.qdd, s.F_ext);
    EXPECT_TRUE(near(Eigen::VectorXd(da.tau), Eigen::VectorXd(db.tau), 1e-12));
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
  const std::string path = ::testing::TempDir() + "/mospec-gen3-grams.jsonld";
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

}  // namespace
}  // namespace mospec::runtime
