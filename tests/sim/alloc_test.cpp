// The control tick through the simulator allocates nothing: read, the
// controllers, write (with commands beyond the limits on some ticks, so the
// clamp runs) and step (MuJoCo included) run 2000 ticks with every heap
// entry point of this executable counting. Own executable, because it replaces
// operator new/delete and glibc's malloc family; skipped under AddressSanitizer.
#include <gtest/gtest.h>

#include <cstdlib>

#include "sim_test_util.hpp"
// Defines the replacement allocator: this translation unit only, and last.
#include "alloc_counter.hpp"  // NOLINT(llvm-include-order)

namespace mospec::sim {
namespace {

TEST(Allocation, TheControlTickAllocatesNothing) {
#ifdef MOSPEC_NO_ALLOC_COUNTING
  GTEST_SKIP() << "AddressSanitizer owns the allocator";
#endif
  NEED_GEN3();
  for (BaseFidelity b : {BaseFidelity::Wheeled, BaseFidelity::Planar}) {
    WorldConfig c = testing::test_world();
    c.base = b;
    c.mount.active = b == BaseFidelity::Planar;
    World w(c, arm_chain);
    w.faults().inject_nan("right_arm.q[2]", 100, 10);
    w.faults().inject_stale("pivot_q[1]", 200, 10);
    w.faults().drop_commands(300, 5);
    GravityCompensation arms(arm_chain, testing::mounts(c));
    arms.f_E_P = {runtime::Vec3(10, 0, 0), runtime::Vec3(10, 0, 0)};
    PlatformWrenchDriver drives(c.drives);
    drives.F_p = runtime::Vec3(20, 0, 0.5);
    robot::MeasuredState s = robot::make_state(robot::gen3_pair_shape());
    robot::Command cmd = robot::make_command(robot::gen3_pair_shape());
    const long n = alloc_counter::during([&] {
      for (int k = 0; k < 2000; ++k) {
        w.read(s);
        arms.compute(s, cmd);
        drives.compute(s, cmd);
        // Some ticks ask for far more than the robot has: the write clamps.
        if (k % 100 < 10) {
          cmd.arm_tau[0][k % 7] = 1e300;
          cmd.wheel_tau[static_cast<size_t>(k % 8)] = -1e10;
        }
        w.write(cmd);
        w.step();
        (void)w.contact(k % 2);
        (void)w.ground_wrench_P();
      }
    });
    EXPECT_EQ(n, 0) << to_string(b);
    EXPECT_TRUE(w.limiter().any()) << "the clamp was exercised";
  }
  // The counter itself works (both C++ and C heaps).
  EXPECT_EQ(alloc_counter::during([] {
              delete new int(1);
              std::free(std::malloc(8));
            }),
            2);
}

}  // namespace
}  // namespace mospec::sim
