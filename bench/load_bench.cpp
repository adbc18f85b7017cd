// Loading the authors' SC1 app (28 files, 1334 triples): parse, expand, toRdf,
// compose. Target: <= 5 ms per load on the 2-core reference machine.
#include <benchmark/benchmark.h>

#include <filesystem>

#include "app/app.hpp"

namespace fs = std::filesystem;

static void BM_LoadApp(benchmark::State& state, const char* app_file) {
  const fs::path models = fs::path(MOSPEC_SHARED_DIR) / "upstream" / "motion-spec-ral";
  if (!fs::exists(models / "models" / app_file)) {
    state.SkipWithError("../shared/upstream is absent; nothing to load");
    return;
  }
  mospec::app::LoadOptions options;
  options.root = models.string();
  const std::string input = (models / "models" / app_file).string();
  size_t triples = 0;
  for (auto _ : state) {
    mospec::app::LoadedModel model = mospec::app::load({input}, options);
    triples = model.dataset().size();
    benchmark::DoNotOptimize(triples);
  }
  state.counters["quads"] = static_cast<double>(triples);
}
BENCHMARK_CAPTURE(BM_LoadApp, sc1, "sc1.json")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_LoadApp, sc0a, "sc0a-right-arm.json")->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
