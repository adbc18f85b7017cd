// The base's tick path allocates nothing: 10 000 ticks of the composed cycle
// (operators -> evaluators -> monitors -> PID -> KELO distribution, see
// base_cycle.hpp) under a counting global allocator leave the counter at zero.
// Own executable because it replaces the global allocator.
#include <gtest/gtest.h>

#include <cstdlib>
#include <vector>

#include "base_cycle.hpp"
#include "kelo_base.hpp"
// Defines the replacement allocator: this translation unit only, and last.
#include "alloc_counter.hpp"  // NOLINT(llvm-include-order)

namespace mospec::runtime {
namespace {

class BaseNoAllocation : public ::testing::Test {
 protected:
  void SetUp() override {
#ifdef MOSPEC_NO_ALLOC_COUNTING
    GTEST_SKIP() << "allocation counting is off under AddressSanitizer";
#endif
  }
};

TEST_F(BaseNoAllocation, TheCounterSeesEveryKindOfAllocation) {
  EXPECT_EQ(alloc_counter::during([] { std::vector<int> v(10); }), 1);
  EXPECT_EQ(alloc_counter::during([] { Eigen::VectorXd v(10); }), 1);
  EXPECT_EQ(alloc_counter::during([] { std::free(std::malloc(8)); }), 1);
  EXPECT_EQ(alloc_counter::during([] {}), 0);
}

TEST_F(BaseNoAllocation, ComposedCycleOf10000Ticks) {
  testing::BaseCycle cycle;  // setup allocates (names in AddWrench): outside the count
  double checksum = 0.0;
  int events = 0;
  const long n = alloc_counter::during([&] {
    double t = 0.0;
    for (int k = 0; k < 10000; ++k) {
      const double dt = (k % 7 == 0) ? 1.5e-3 : 1e-3;  // jittery ticks
      t += dt;
      checksum += cycle.tick(t, dt).sum();
      events += cycle.events();
    }
  });
  EXPECT_EQ(n, 0);
  EXPECT_TRUE(std::isfinite(checksum));
  EXPECT_TRUE(cycle.kelo_data().xd_platform.allFinite());
  EXPECT_GT(events, 0);  // the monitors did fire: the cycle exercised every branch kind
}

TEST_F(BaseNoAllocation, EveryBlockOnItsOwn) {
  const KeloModel model(::mospec::testing::paper_base());
  KeloData data(model);
  const Pid pid({.kp = 1, .ki = 1, .kd = 1, .decay_rate = 0.5, .output_min = -1, .output_max = 1});
  PidState s;
  const EdgeMonitor monitor({.enter = 0.1, .leave = 0.2}, Edges::Both);
  MonitorState ms;
  const ConstraintEvaluator tube({.kind = ConstraintKind::Bilateral, .lower = 0, .upper = 1});
  double sink = 0;
  EXPECT_EQ(alloc_counter::during([&] {
              for (int k = 0; k < 10000; ++k) {
                const double x = 0.001 * k;
                const Vec4 q = Vec4::Constant(x);
                kelo_force_step(model, data, q, Vec3(x, 1 - x, 0.5));
                kelo_platform_twist(model, data, data.tau_wheel);
                kelo_wheel_rates(model, data, Vec3(x, 0, 1));
                sink += kelo_nullspace_projector(data).trace();
                pid.step(s, tube.evaluate(std::sin(x)).error, 1e-3);
                sink += static_cast<int>(monitor.update(ms, std::cos(x)));
                Vec3 d;
                const Pose X{Eigen::AngleAxisd(x, Vec3::UnitY()).toRotationMatrix(), Vec3(x, 1, 2)};
                pose_to_direction(X, d);
                double a = 0;
                planar_angle_from_directions(d, Vec3::UnitX(), Vec3::UnitY(), a);
                sink += a + view(X, {Part::Angular, Axis::Y}) + line_line_distance({}, {}) +
                        transform_wrench_to_distal(X, Vec6::Ones()).sum();
              }
            }),
            0);
  EXPECT_TRUE(std::isfinite(sink));
}

}  // namespace
}  // namespace mospec::runtime
