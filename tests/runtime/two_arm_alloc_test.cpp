// The whole control tick allocates nothing: 10 000 ticks of both Gen3 arms'
// ACHD solvers composed with the base cycle (two_arm_base_cycle.hpp) under a
// counting global allocator leave the counter at zero.
// Own executable because it replaces the global allocator.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "description/urdf_import.hpp"
#include "two_arm_base_cycle.hpp"
// Defines the replacement allocator: this translation unit only, and last.
#include "alloc_counter.hpp"  // NOLINT(llvm-include-order)

namespace mospec::runtime {
namespace {

using namespace mospec::description;  // the chain importers under test

const std::string kGen3Urdf =
    std::string(MOSPEC_SHARED_DIR) + "/upstream/kinova/GEN3_URDF_V12.urdf";

TEST(TwoArmBaseNoAllocation, ComposedCycleOf10000Ticks) {
#ifdef MOSPEC_NO_ALLOC_COUNTING
  GTEST_SKIP() << "allocation counting is off under AddressSanitizer";
#endif
  if (!std::filesystem::exists(kGen3Urdf)) {
    GTEST_SKIP() << "needs the Kinova Gen3 URDF at " << kGen3Urdf << " (../shared is absent)";
  }
  const Chain arm = chain_from_urdf_file(kGen3Urdf, "base_link", "EndEffector_Link");
  testing::TwoArmBaseCycle cycle(arm);  // setup allocates: outside the count
  double checksum = 0.0;
  const long n = alloc_counter::during([&] {
    double t = 0.0;
    for (int k = 0; k < 10000; ++k) {
      const double dt = (k % 7 == 0) ? 1.5e-3 : 1e-3;  // jittery ticks
      t += dt;
      checksum += cycle.tick(t, dt).sum();
    }
  });
  EXPECT_EQ(n, 0);
  EXPECT_TRUE(std::isfinite(checksum));
  EXPECT_TRUE(cycle.right_arm().qdd.allFinite());
  EXPECT_TRUE(cycle.left_arm().tau.allFinite());
  // The arms really moved the contact poses the base cycle read.
  EXPECT_GT((cycle.right_arm().X_BT.p - cycle.left_arm().X_BT.p).norm(), 1e-3);
}

}  // namespace
}  // namespace mospec::runtime
