// models/left-arm/robot.jsonld: the second Gen3 of the dual-arm scenarios, made
// by the same generator as robots/kinova-gen3.jsonld from Kinova's URDF, with
// its own IRIs (https://mospec.example/robots/kinova-gen3-left/) so that both
// arms can be composed into one app. Skipped without ../shared (the URDF).
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>

#include "description/chain_jsonld.hpp"
#include "description/urdf_import.hpp"
#include "support/io.hpp"

namespace mospec::runtime {
namespace {

using namespace mospec::description;  // the chain importers under test

const std::string kModel = std::string(MOSPEC_SOURCE_DIR) + "/models/left-arm/robot.jsonld";
const std::string kUrdf = std::string(MOSPEC_SHARED_DIR) + "/upstream/kinova/GEN3_URDF_V12.urdf";

TEST(LeftArm, CommittedFileIsTheGeneratorsOutput) {
  if (!std::filesystem::exists(kUrdf)) GTEST_SKIP() << "needs " << kUrdf;
  ChainJsonldOptions options;
  options.base = "https://mospec.example/robots/kinova-gen3-left/";
  options.limits = false;  // as the Gen3's (robot_model_test.cpp): the published vocabulary
  const std::string generated =
      chain_to_jsonld(chain_from_urdf_file(kUrdf, "base_link", "EndEffector_Link"), options);
  // MOSPEC_REGENERATE_ROBOTS=1 rewrites the committed file instead of comparing.
  if (const char* regen = std::getenv("MOSPEC_REGENERATE_ROBOTS"); regen && *regen == '1') {
    write_output(kModel, generated);
  }
  EXPECT_EQ(read_file(kModel), generated)
      << "models/left-arm/robot.jsonld is stale: run this test with MOSPEC_REGENERATE_ROBOTS=1";
}

}  // namespace
}  // namespace mospec::runtime
