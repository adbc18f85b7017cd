// Code generation and the generated tick (issue #7's targets):
//   BM_GenerateProcess/sc1   `mospec generate models/sc1.json` as a whole
//                            process (target <= 30 ms wall; the authors'
//                            Python + JVM pipeline takes seconds);
//   BM_Lower/sc1             load + lower in-process (no validation; the
//                            imports prepared on two threads, the library's
//                            default; /sc1_one_thread on one, as the CLI);
//   BM_InterpretedTick/sc1   one tick of the IR interpreter;
//   BM_GeneratedTick/sc1     one tick of the generated controller (target
//                            <= 10 us), built once at start-up with
//                            `mospec build` and loaded with dlopen.
// Every tick runs against a robot standing in the default world's pose, with
// a slow joint motion so nothing is constant-folded.
#include <benchmark/benchmark.h>
#include <dlfcn.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "app/app.hpp"
#include "ir/interpreter.hpp"
#include "ir/lower.hpp"
#include "robot/controller.hpp"
#include "sim/config.hpp"
#include "spawn.hpp"

extern char** environ;

namespace {

namespace fs = std::filesystem;
using mospec::robot::Controller;

const std::string kSource = MOSPEC_SOURCE_DIR;
const std::string kMospec = MOSPEC_BINARY;

// Runs argv in the source tree with stdout to `out_file` (or discarded).
int spawn(const std::vector<std::string>& args, const std::string& out_file = "/dev/null") {
  return mospec::bench::spawn(args, kSource, out_file);
}

// The arms sc1's chains drive, as the CLI binds them: from its world file.
mospec::ir::LowerOptions sc1_lower_options() {
  const mospec::sim::WorldConfig world =
      mospec::sim::load_world_config(kSource + "/models/sc1.world.json", /*check_files=*/false);
  mospec::ir::LowerOptions options;
  for (std::size_t k = 0; k < world.arms.size(); ++k)
    options.ports[mospec::sim::arm_chain(world, k)] = static_cast<int>(k);
  return options;
}

// `threads`: LoadOptions::threads (0: as many as the machine offers, up to 2).
mospec::ir::Program lower_sc1(unsigned threads = 0) {
  static const mospec::ir::LowerOptions lower_options = sc1_lower_options();
  mospec::app::LoadOptions options;
  options.root = kSource;
  options.threads = threads;
  mospec::app::LoadedModel model = mospec::app::load({kSource + "/models/sc1.json"}, options);
  return mospec::ir::lower(model, lower_options);
}

void run_ticks(benchmark::State& state, Controller& controller) {
  const mospec::sim::WorldConfig world = mospec::sim::default_world();
  mospec::robot::MeasuredState s = mospec::robot::make_state(mospec::robot::gen3_pair_shape());
  for (size_t a = 0; a < s.arm.size(); ++a) s.arm[a].q = world.arms[a].q0;
  mospec::robot::Command command = mospec::robot::make_command(mospec::robot::gen3_pair_shape());
  std::uint64_t k = 0;
  for (auto _ : state) {
    s.clock.tick = k;
    s.clock.t = 0.001 * static_cast<double>(k);
    s.clock.dt = 0.001;
    s.arm[0].qd[1] = 0.05 * std::sin(0.001 * static_cast<double>(k));
    controller.tick(s, command);
    benchmark::DoNotOptimize(command);
    ++k;
  }
}

void BM_GenerateProcess(benchmark::State& state) {
  const fs::path out = fs::temp_directory_path() / ("mospec-bench-gen-" + std::to_string(getpid()));
  for (auto _ : state) {
    if (spawn({kMospec, "generate", "models/sc1.json", "-o", out.string()}) != 0) {
      state.SkipWithError("mospec generate failed");
      break;
    }
  }
  fs::remove_all(out);
}
BENCHMARK(BM_GenerateProcess)
    ->Name("BM_GenerateProcess/sc1")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// Wall time (UseRealTime): the load prepares documents on a second thread,
// whose work the benchmark thread's CPU time would not show.
void BM_Lower(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(lower_sc1());
}
BENCHMARK(BM_Lower)->Name("BM_Lower/sc1")->Unit(benchmark::kMillisecond)->UseRealTime();
// The baseline of the one above: every document on the benchmark thread.
void BM_LowerOneThread(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(lower_sc1(1));
}
BENCHMARK(BM_LowerOneThread)
    ->Name("BM_Lower/sc1_one_thread")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// The two halves of BM_Lower/sc1: loading the model files into one dataset,
// and lowering an already loaded model.
void BM_LowerStages(benchmark::State& state, int stage) {
  mospec::app::LoadOptions options;
  options.root = kSource;
  if (stage == 2) {
    options.threads = 1;
    stage = 0;
  }
  if (stage == 0) {
    for (auto _ : state)
      benchmark::DoNotOptimize(mospec::app::load({kSource + "/models/sc1.json"}, options));
    return;
  }
  const mospec::app::LoadedModel model = mospec::app::load({kSource + "/models/sc1.json"}, options);
  const mospec::ir::LowerOptions lower_options = sc1_lower_options();
  for (auto _ : state) benchmark::DoNotOptimize(mospec::ir::lower(model, lower_options));
}
BENCHMARK_CAPTURE(BM_LowerStages, sc1_load, 0)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_LowerStages, sc1_load_one_thread, 2)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK_CAPTURE(BM_LowerStages, sc1_lower_only, 1)->Unit(benchmark::kMillisecond);

void BM_InterpretedTick(benchmark::State& state) {
  mospec::ir::Interpreter interpreter(lower_sc1());
  run_ticks(state, interpreter);
}
BENCHMARK(BM_InterpretedTick)->Name("BM_InterpretedTick/sc1")->Unit(benchmark::kMicrosecond);

// The generated SC1 controller, built once per process.
std::unique_ptr<Controller> generated_sc1(std::string& why) {
  const fs::path dir = fs::temp_directory_path() / ("mospec-bench-sc1-" + std::to_string(getpid()));
  const fs::path lib_path_file = dir.string() + ".path";
  if (spawn({kMospec, "generate", "models/sc1.json", "-o", dir.string()}) != 0) {
    why = "mospec generate failed";
    return nullptr;
  }
  if (spawn({kMospec, "build", dir.string()}, lib_path_file.string()) != 0) {
    why = "mospec build failed";
    return nullptr;
  }
  std::string lib;
  if (FILE* f = std::fopen(lib_path_file.c_str(), "r")) {
    char buf[4096];
    if (std::fgets(buf, sizeof buf, f)) lib = buf;
    std::fclose(f);
  }
  while (!lib.empty() && (lib.back() == '\n' || lib.back() == '\r')) lib.pop_back();
  void* handle = dlopen(lib.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!handle) {
    why = dlerror();
    return nullptr;
  }
  auto factory = reinterpret_cast<mospec::robot::ControllerFactory>(
      dlsym(handle, mospec::robot::kControllerFactorySymbol));
  if (!factory) {
    why = "no controller factory in the library";
    return nullptr;
  }
  return std::unique_ptr<Controller>(factory());  // the library stays loaded
}

void BM_GeneratedTick(benchmark::State& state) {
  static std::string why;
  static std::unique_ptr<Controller> controller = generated_sc1(why);
  if (!controller) {
    state.SkipWithError(why.c_str());
    return;
  }
  run_ticks(state, *controller);
}
BENCHMARK(BM_GeneratedTick)->Name("BM_GeneratedTick/sc1")->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
