// Simulation speed: one control tick (read, controllers, write, step) of the
// full world — both arms under gravity compensation pushing the table's edge
// with 10 N each, the base pushing towards the table with 20 N through the
// KELO solver. The "x_realtime" counter is simulated time per wall-clock time.
// Targets on the 2-core dev machine: >= 10x (wheeled), >= 30x (planar).
#include <benchmark/benchmark.h>
#include <mujoco/mujoco.h>

#include <filesystem>

#include "description/base_rdf.hpp"
#include "description/robot_model.hpp"
#include "sim/drivers.hpp"
#include "sim/world.hpp"

namespace {

using namespace mospec;

void BM_SimStep(benchmark::State& st, sim::BaseFidelity base) {
  sim::WorldConfig c = sim::default_world();
  for (const auto& [prefix, dir] : c.robot.maps) {
    if (!std::filesystem::exists(dir)) {
      st.SkipWithError("needs the published metamodels to load the robot model");
      return;
    }
  }
  c.base = base;
  const runtime::Chain arm =
      description::load_chain(c.robot.model, c.robot.chain_iri, c.robot.maps);
  c.drives = description::load_base(c.base_model.model, c.base_model.configuration);
  sim::World world(c, arm);
  sim::GravityCompensation arms(arm, std::vector<runtime::Pose>{c.arms[0].X_PB, c.arms[1].X_PB});
  arms.f_E_P = {runtime::Vec3(10, 0, 0), runtime::Vec3(10, 0, 0)};
  sim::PlatformWrenchDriver drives(c.drives);
  drives.F_p = runtime::Vec3(20, 0, 0);
  robot::MeasuredState s = robot::make_state(robot::gen3_pair_shape());
  robot::Command cmd = robot::make_command(robot::gen3_pair_shape());
  auto tick = [&] {
    world.read(s);
    arms.compute(s, cmd);
    drives.compute(s, cmd);
    world.write(cmd);
    world.step();
  };
  for (int k = 0; k < 500; ++k) tick();  // settle into contact
  for (auto _ : st) tick();
  const int contacts = world.contact(0).contacts + world.contact(1).contacts;
  st.counters["x_realtime"] = benchmark::Counter(
      static_cast<double>(st.iterations()) * c.control_period, benchmark::Counter::kIsRate);
  st.counters["ee_contacts"] = contacts;
  st.counters["nv"] = world.mj_model()->nv;
}

BENCHMARK_CAPTURE(BM_SimStep, wheeled, sim::BaseFidelity::Wheeled)->Unit(benchmark::kMicrosecond);
BENCHMARK_CAPTURE(BM_SimStep, planar, sim::BaseFidelity::Planar)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
