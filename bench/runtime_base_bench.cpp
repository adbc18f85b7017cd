// Base-side tick timings: the KELO force distribution (G, weighted
// pseudo-inverse, alignment reference, Eq. 3, hub torques), the velocity
// composition, one PID step (decaying integral, clamped), and the whole
// composed base cycle of tests/runtime/base_cycle.hpp (two arms' operators,
// evaluators, monitors, PIDs, wrench algebra, then the KELO force path).
// Each benchmark repeats 10 times and reports mean/median/stddev; compare medians.
#include <benchmark/benchmark.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "base_cycle.hpp"
#include "description/urdf_import.hpp"
#include "kelo_base.hpp"
#include "runtime/controllers.hpp"
#include "runtime/kelo.hpp"
#include "two_arm_base_cycle.hpp"

namespace {

using namespace mospec::runtime;

// Pivot angles and platform wrenches that change every iteration, so nothing
// is hoisted out of the loop.
void BM_KeloDistribution(benchmark::State& state) {
  const KeloModel model(mospec::testing::paper_base());
  KeloData data(model);
  double t = 0.0;
  for (auto _ : state) {
    t += 1e-3;
    KeloPivotVector q(4);
    q << t, -t, 0.5 * t, 1.0 - t;
    const Vec3 F_p(100.0 * std::cos(t), 50.0, 10.0 * std::sin(t));
    benchmark::DoNotOptimize(kelo_force_step(model, data, q, F_p).data());
  }
}

void BM_KeloPlatformTwist(benchmark::State& state) {
  const KeloModel model(mospec::testing::paper_base());
  KeloData data(model);
  KeloDriveVector w = KeloDriveVector::Constant(8, 3.0);
  KeloPivotVector q(4);
  double t = 0.0;
  for (auto _ : state) {
    t += 1e-3;
    w[0] = t;
    q << t, -t, 0.5 * t, 1.0 - t;
    kelo_set_pivots(model, data, q);
    benchmark::DoNotOptimize(kelo_platform_twist(model, data, w).data());
  }
}

void BM_ControllerStep(benchmark::State& state) {
  const Pid pid({.kp = 450.0,
                 .ki = 65.5,
                 .kd = 80.0,
                 .decay_rate = 0.99,
                 .output_min = -150.0,
                 .output_max = 150.0});
  PidState s;
  double e = 0.0;
  for (auto _ : state) {
    e += 1e-4;
    benchmark::DoNotOptimize(pid.step(s, std::sin(e), 1e-3));
    benchmark::DoNotOptimize(s.output);
  }
}

void BM_BaseCycle(benchmark::State& state) {
  mospec::runtime::testing::BaseCycle cycle;
  double t = 0.0;
  for (auto _ : state) {
    t += 1e-3;
    benchmark::DoNotOptimize(cycle.tick(t, 1e-3).data());
  }
}

// The whole controller tick: both Gen3 arms' ACHD (nc = 5 each) and the base
// cycle. Target: <= 10 µs per tick.
void BM_TwoArmBaseTick(benchmark::State& state) {
  const std::string urdf = std::string(MOSPEC_SHARED_DIR) + "/upstream/kinova/GEN3_URDF_V12.urdf";
  if (!std::filesystem::exists(urdf)) {
    state.SkipWithError("needs the Kinova Gen3 URDF in ../shared/upstream/kinova");
    return;
  }
  const auto arm = mospec::description::chain_from_urdf_file(urdf, "base_link", "EndEffector_Link");
  mospec::runtime::testing::TwoArmBaseCycle cycle(arm);
  double t = 0.0;
  for (auto _ : state) {
    t += 1e-3;
    benchmark::DoNotOptimize(cycle.tick(t, 1e-3).data());
  }
}

}  // namespace

BENCHMARK(BM_TwoArmBaseTick)
    ->Repetitions(10)
    ->ReportAggregatesOnly(true)
    ->Unit(benchmark::kNanosecond);
BENCHMARK(BM_KeloDistribution)
    ->Repetitions(10)
    ->ReportAggregatesOnly(true)
    ->Unit(benchmark::kNanosecond);
BENCHMARK(BM_KeloPlatformTwist)
    ->Repetitions(10)
    ->ReportAggregatesOnly(true)
    ->Unit(benchmark::kNanosecond);
BENCHMARK(BM_ControllerStep)
    ->Repetitions(10)
    ->ReportAggregatesOnly(true)
    ->Unit(benchmark::kNanosecond);
BENCHMARK(BM_BaseCycle)->Repetitions(10)->ReportAggregatesOnly(true)->Unit(benchmark::kNanosecond);

BENCHMARK_MAIN();
