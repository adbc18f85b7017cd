// `mospec validate` in-process: the authors' SC1 app (load 28 files, read and
// compile their 9 shape files, validate), and validation time against data
// size on generated graphs (target: linear in triples).
//
// Targets: BM_Validate/sc1 (the whole pipeline) <= 20 ms; the scaling runs'
// s_per_triple stays flat from 5k to 100k triples; BM_ValidateProcess/sc1, the
// whole `mospec validate models/sc1.json` process as users run it (start-up,
// dynamic loading, validation, report), <= 15 ms wall. BM_HelpProcess is
// `mospec --help`: the start-up alone. BM_SparqlBudgetOverrun: a query
// stopped by its time budget ends at most 10 % past it (counter `overrun`);
// BM_RegexScan is the RE2 rate the budget's estimate must stay above.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "app/app.hpp"
#include "rdf/turtle.hpp"
#include "shacl/shapes.hpp"
#include "shacl/validate.hpp"
#include "sparql/query.hpp"
#include "sparql/regex.hpp"
#include "spawn.hpp"
#include "support/io.hpp"
#include "validation/model_validation.hpp"

extern char** environ;

namespace fs = std::filesystem;
using namespace mospec;

namespace {

const fs::path kUpstream = fs::path(MOSPEC_SHARED_DIR) / "upstream" / "motion-spec-ral";

// Load + shapes + compile + validate, as `mospec validate APP` runs it.
void BM_Validate(benchmark::State& state, const char* app_file) {
  if (!fs::exists(kUpstream / "models" / app_file)) {
    state.SkipWithError("../shared/upstream is absent; nothing to validate");
    return;
  }
  app::LoadOptions options;
  options.root = kUpstream.string();
  const std::string input = (kUpstream / "models" / app_file).string();
  size_t results = 0, quads = 0;
  for (auto _ : state) {
    app::LoadedModel model = app::load({input}, options);
    validation::ModelValidation v = validation::validate_model(model, {});
    results = v.report.results.size();
    quads = model.dataset().size();
    benchmark::DoNotOptimize(results);
  }
  state.counters["results"] = static_cast<double>(results);
  state.counters["quads"] = static_cast<double>(quads);
}
BENCHMARK_CAPTURE(BM_Validate, sc1, "sc1.json")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Validate, sc0a, "sc0a-right-arm.json")->Unit(benchmark::kMillisecond);

// The pieces of BM_Validate/sc1: shapes read + compiled, and validation alone.
void BM_ValidateStages(benchmark::State& state, int stage) {
  if (!fs::exists(kUpstream / "models" / "sc1.json")) {
    state.SkipWithError("../shared/upstream is absent; nothing to validate");
    return;
  }
  app::LoadOptions options;
  options.root = kUpstream.string();
  app::LoadedModel model = app::load({(kUpstream / "models" / "sc1.json").string()}, options);
  std::vector<validation::ShapeFile> files = validation::shape_files(model, {});
  auto read_shapes = [&] {
    auto graph = std::make_unique<rdf::Dataset>();
    for (const validation::ShapeFile& f : files)
      validation::read_shape_file(f, model.loader(), *graph);
    return graph;
  };
  if (stage == 0) {
    for (auto _ : state) {
      auto graph = read_shapes();
      shacl::Shapes shapes = shacl::Shapes::compile(*graph, &model.files());
      benchmark::DoNotOptimize(shapes.shapes().size());
    }
    return;
  }
  auto graph = read_shapes();
  shacl::Shapes shapes = shacl::Shapes::compile(*graph, &model.files());
  for (auto _ : state) {
    shacl::Report report = shacl::validate(shapes, model.dataset());
    benchmark::DoNotOptimize(report.results.size());
  }
}
BENCHMARK_CAPTURE(BM_ValidateStages, sc1_read_compile_shapes, 0)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_ValidateStages, sc1_validate_only, 1)->Unit(benchmark::kMillisecond);

// Runs the built mospec with `args` in `cwd`, output discarded; its exit status.
int run_mospec(const std::vector<std::string>& args, const fs::path& cwd) {
  std::vector<std::string> all{MOSPEC_BINARY};
  all.insert(all.end(), args.begin(), args.end());
  return mospec::bench::spawn(all, cwd.string());
}

// `mospec validate models/sc1.json` in the authors' tree: exit 1 (their SC1
// has two violations, tests/cli/validate_test.sh).
void BM_ValidateProcess(benchmark::State& state) {
  if (!fs::exists(kUpstream / "models" / "sc1.json")) {
    state.SkipWithError("../shared/upstream is absent; nothing to validate");
    return;
  }
  for (auto _ : state) {
    if (run_mospec({"validate", "models/sc1.json"}, kUpstream) != 1) {
      state.SkipWithError("mospec validate models/sc1.json did not exit 1");
      break;
    }
  }
}
BENCHMARK(BM_ValidateProcess)
    ->Name("BM_ValidateProcess/sc1")
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

void BM_HelpProcess(benchmark::State& state) {
  for (auto _ : state) {
    if (run_mospec({"--help"}, fs::current_path()) != 0) {
      state.SkipWithError("mospec --help failed");
      break;
    }
  }
}
BENCHMARK(BM_HelpProcess)->Unit(benchmark::kMillisecond)->UseRealTime();

// ---- scaling ------------------------------------------------------------------

// One unit of a generated model (~65 triples), conforming to the authors'
// shapes: a pose chain composed by geom-op:ComposePose, a direction, three
// wrenches added by dyn-op:AddWrench, a wrench rotated to the distal side, a
// guarded motion with a handler and its evaluator, a solver.
std::string unit(size_t i) {
  const std::string n = std::to_string(i);
  auto id = [&](const char* name) {
    std::string s = "ex:";
    s.append(name).append("-").append(n);
    return s;
  };
  std::string out;
  auto line = [&](std::initializer_list<std::string_view> parts) {
    for (std::string_view p : parts) out.append(p).append(" ");
    out.append(".\n");
  };
  const std::string fA = id("fA"), fB = id("fB"), fC = id("fC"), p = id("p");
  line({fA, "a geom-ent:Frame"});
  line({fB, "a geom-ent:Frame"});
  line({fC, "a geom-ent:Frame"});
  line({p, "a geom-ent:Point"});
  auto pose = [&](const std::string& s, const std::string& of, const std::string& wrt) {
    line({s, "a geom-coord:PoseCoordinate ; geom-coord:as-seen-by", wrt, "; geom-rel:of", of,
          "; geom-rel:in", of, "; geom-rel:with-respect-to", wrt});
  };
  pose(id("in1"), fB, fA);
  pose(id("in2"), fC, fB);
  pose(id("comp"), fC, fA);
  line({id("compose"), "a geom-op:ComposePose ; geom-op:in1", id("in1"), "; geom-op:in2", id("in2"),
        "; geom-op:composite", id("comp")});
  line({id("dir"), "a geom-coord:DirectionCoordinate ; geom-coord:as-seen-by", fA});
  line({id("p2d"), "a geom-op:PoseToDirection ; geom-op:pose", id("in1"), "; geom-op:direction",
        id("dir")});
  auto wrench = [&](const std::string& s, const std::string& asb) {
    line({s, "a dyn-coord:WrenchCoordinate ; dyn-ent:reference-point", p, "; dyn-coord:as-seen-by",
          asb});
  };
  wrench(id("w1"), fA);
  wrench(id("w2"), fA);
  wrench(id("w3"), fA);
  wrench(id("w4"), fB);
  line({id("add"), "a dyn-op:AddWrench ; dyn-op:in1", id("w1"), "; dyn-op:in2", id("w2"),
        "; dyn-op:out", id("w3")});
  line({id("rot"), "a dyn-op:RotateWrenchToDistalWithPose ; dyn-op:pose", id("in1"),
        "; dyn-op:from", id("w1"), "; dyn-op:to", id("w4")});
  line({id("c"), "a cstr:Constraint ; cstr:quantity", id("q")});
  line({id("motion"), "a mot:GuardedMotion ; mot:while", id("c")});
  line({id("eval"), "a cstr_hdl:ConstraintEvaluator ; cstr_hdl:constraint", id("c")});
  line({id("handler"), "a cstr_hdl:ConstraintHandler ; cstr_hdl:motion", id("motion"),
        "; cstr_hdl:evaluators", id("eval")});
  line({id("g"), "a dyn-coord:UniformGravitationalFieldCoordinate ; dyn-coord:as-seen-by", fA});
  line({id("drivers"), "a slv:MotionDrivers"});
  line({id("solver"), "a slv:SolverWithInputAndOutput ; slv:motion-drivers", id("drivers"),
        "; slv:root", fA, "; slv:gravity", id("g"),
        "; slv:solver slv:AccelerationConstrainedHybridDynamicsAlgorithm"});
  return out;
}

const char* const kPrefixes =
    "@prefix ex: <http://example.org/> .\n"
    "@prefix geom-ent: <https://comp-rob2b.github.io/metamodels/geometry/structural-entities#> .\n"
    "@prefix geom-rel: <https://comp-rob2b.github.io/metamodels/geometry/spatial-relations#> .\n"
    "@prefix geom-coord: <https://comp-rob2b.github.io/metamodels/geometry/coordinates#> .\n"
    "@prefix geom-op: <https://comp-rob2b.github.io/metamodels/geometry/spatial-operators#> .\n"
    "@prefix dyn-ent: <https://comp-rob2b.github.io/metamodels/newtonian-rigid-body-dynamics/"
    "structural-entities#> .\n"
    "@prefix dyn-coord: <https://comp-rob2b.github.io/metamodels/newtonian-rigid-body-dynamics/"
    "coordinates#> .\n"
    "@prefix dyn-op: <https://comp-rob2b.github.io/metamodels/newtonian-rigid-body-dynamics/"
    "operators#> .\n"
    "@prefix cstr: <https://comp-rob2b.github.io/metamodels/task/constraint#> .\n"
    "@prefix cstr_hdl: <https://comp-rob2b.github.io/metamodels/task/constraint-handler#> .\n"
    "@prefix mot: <https://comp-rob2b.github.io/metamodels/task/motion-specification#> .\n"
    "@prefix slv: <https://comp-rob2b.github.io/metamodels/task/solver-specification#> .\n";

struct AuthorsShapes {
  SourceFiles files;
  rdf::Dataset graph;
  std::unique_ptr<shacl::Shapes> shapes;
};

// The shape files sc1 names, compiled once per process.
const AuthorsShapes* authors_shapes() {
  static std::unique_ptr<AuthorsShapes> cached = [] {
    auto s = std::make_unique<AuthorsShapes>();
    const fs::path root = kUpstream / "comp-rob2b" / "metamodels";
    for (const char* rel :
         {"geometry/spatial-relations.ttl", "geometry/coordinates.ttl",
          "geometry/spatial-operators.ttl", "newtonian-rigid-body-dynamics/operators.ttl",
          "task/map.ttl", "task/constraint.ttl", "task/motion-specification.ttl",
          "task/constraint-handler.ttl", "task/solver-specification.ttl"}) {
      const std::string path = (root / rel).string();
      std::string iri = "https://comp-rob2b.github.io/metamodels/";
      iri.append(rel);
      rdf::read_turtle(read_file(path), iri, s->graph, s->files.add(path), path);
    }
    s->shapes = std::make_unique<shacl::Shapes>(shacl::Shapes::compile(s->graph, &s->files));
    return s;
  }();
  return cached.get();
}

// Validation of N generated units (time per triple should not grow with N).
void BM_ValidateScaling(benchmark::State& state) {
  if (!fs::exists(kUpstream / "comp-rob2b" / "metamodels")) {
    state.SkipWithError("../shared/upstream is absent; no shapes");
    return;
  }
  const AuthorsShapes* shapes = authors_shapes();
  std::string text = kPrefixes;
  for (size_t i = 0; i < static_cast<size_t>(state.range(0)); ++i) text += unit(i);
  rdf::Dataset data;
  rdf::read_turtle(text, "http://example.org/", data, 0, "generated.ttl");
  size_t results = 0;
  for (auto _ : state) {
    shacl::Report report = shacl::validate(*shapes->shapes, data);
    results = report.results.size();
    benchmark::DoNotOptimize(results);
  }
  if (results != 0) state.SkipWithError("the generated model should conform");
  state.counters["triples"] = static_cast<double>(data.size());
  state.counters["s_per_triple"] = benchmark::Counter(
      static_cast<double>(data.size()),
      benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_ValidateScaling)
    ->Arg(100)
    ->Arg(200)
    ->Arg(400)
    ->Arg(800)
    ->Arg(1750)
    ->Unit(benchmark::kMillisecond);

// ---- the SPARQL budget --------------------------------------------------------

// `n` subjects with a literal of `bytes` bytes each, and 64 ex:k triples.
std::string long_texts(size_t n, size_t bytes) {
  std::string out = "@prefix ex: <http://example.org/> .\n";
  const std::string body(bytes, 'a');
  for (size_t i = 0; i < n; ++i)
    out += "ex:s" + std::to_string(i) + " ex:text \"" + body + std::to_string(i) + "\" .\n";
  for (size_t i = 0; i < 64; ++i)
    out += "ex:k" + std::to_string(i) + " ex:k " + std::to_string(i) + " .\n";
  return out;
}

// How fast RE2 scans a 1 MiB text for a pattern that does not match and that
// it cannot skip through with memchr or a reverse scan from `$` (the cost
// Budget::kRegexSecondsPerStep estimates conservatively): bytes/s.
void BM_RegexScan(benchmark::State& state) {
  const std::string text(size_t{1} << 20, 'a');
  const sparql::Regex re("(a|b)c", "");
  for (auto _ : state) benchmark::DoNotOptimize(re.search(text));
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations()) *
                          static_cast<int64_t>(text.size()));
}
BENCHMARK(BM_RegexScan)->Unit(benchmark::kMicrosecond);

// A query that runs REGEX over 1 MiB for each of 16 x 64 solutions (about a
// second of work) under a time budget of state.range(0) ms: how far past the
// budget it stops. Target (issue #32): overrun <= 10 % of the budget.
void BM_SparqlBudgetOverrun(benchmark::State& state) {
  rdf::Dataset data;
  rdf::read_turtle(long_texts(16, size_t{1} << 20), "http://example.org/", data);
  const sparql::Query query = sparql::parse_query(
      "PREFIX ex: <http://example.org/>\n"
      "SELECT ?s { ?s ex:text ?t . ?k ex:k ?i FILTER(REGEX(CONCAT(?t, STR(?i)), '(a|b)c')) }");
  const double budget_s = static_cast<double>(state.range(0)) / 1000;
  double worst = 0;
  for (auto _ : state) {
    sparql::Evaluator eval(data);
    sparql::Budget budget(sparql::Limits{budget_s, 0, 0});
    eval.set_budget(&budget);
    sparql::ResultSet rows;
    const auto start = std::chrono::steady_clock::now();
    try {
      eval.select(query, {}, rows);
      state.SkipWithError("the query ended within its budget");
      break;
    } catch (const Error&) {
    }
    const std::chrono::duration<double> spent = std::chrono::steady_clock::now() - start;
    worst = std::max(worst, spent.count() / budget_s - 1);
  }
  state.counters["overrun"] = worst;  // worst (elapsed - budget) / budget
}
BENCHMARK(BM_SparqlBudgetOverrun)->Arg(20)->Arg(100)->Arg(500)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
