// `mospec report RUN_OR_TRIALS -o report.html`: a run's summary and log (or a
// directory of them: one run, or `mospec trials`' trial-<i>.json/.csv) and its
// model as one self-contained page (src/report/report.hpp).
#include <algorithm>
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>

#include "cli/commands.hpp"
#include "cli/log_info.hpp"
#include "cli/pipeline.hpp"
#include "report/report.hpp"
#include "support/io.hpp"
#include "support/paths.hpp"

namespace mospec::cli {
namespace {

namespace fs = std::filesystem;

struct ReportFlags {
  std::string input, output, title;
  bool absolute_links = false, no_video = false;
  LoadFlags load;
};

// A run's files: SUMMARY.json beside SUMMARY.csv and, when present,
// SUMMARY.mp4 or SUMMARY.gif.
report::Run run_of(const fs::path& summary, const fs::path& dir, bool video) {
  report::Run r;
  r.name = summary.stem().string();
  r.dir = dir.string();
  r.summary_path = summary.string();
  fs::path log = summary;
  log.replace_extension(".csv");
  if (!fs::is_regular_file(log)) {
    throw Error("report", "mospec report: " + escaped_bytes(summary.string()) +
                              " has no log beside it (" + escaped_bytes(log.string()) +
                              "): run with --log " + escaped_bytes(log.string()) + " --summary " +
                              escaped_bytes(summary.string()));
  }
  r.log_path = log.string();
  for (const char* ext : {".mp4", ".gif"}) {
    if (!video) break;
    fs::path video = summary;
    video.replace_extension(ext);
    if (fs::is_regular_file(video)) {
      r.video_path = video.string();
      break;
    }
  }
  return r;
}

// trial-2 before trial-10.
bool natural_less(const std::string& a, const std::string& b) {
  return a.size() != b.size() ? a.size() < b.size() : a < b;
}

std::vector<report::Run> runs_in(const std::string& input, bool video) {
  const fs::path p(input);
  if (fs::is_regular_file(p)) {
    const fs::path dir = p.parent_path().empty() ? fs::path(".") : p.parent_path();
    return {run_of(p, dir, video)};
  }
  if (!fs::is_directory(p)) {
    throw Error("report", "mospec report: " + escaped_bytes(input) +
                              " is neither a run's summary (FILE.json) nor a directory of runs");
  }
  std::vector<fs::path> summaries;
  for (const fs::directory_entry& e : fs::directory_iterator(p)) {
    if (e.is_regular_file() && e.path().extension() == ".json") {
      fs::path log = e.path();
      log.replace_extension(".csv");
      if (fs::is_regular_file(log)) summaries.push_back(e.path());
    }
  }
  std::sort(summaries.begin(), summaries.end(), [](const fs::path& a, const fs::path& b) {
    return natural_less(a.filename().string(), b.filename().string());
  });
  if (summaries.empty()) {
    throw Error("report", "mospec report: " + escaped_bytes(input) +
                              " holds no run (a NAME.json summary beside its NAME.csv log)");
  }
  std::vector<report::Run> runs;
  for (const fs::path& s : summaries) runs.push_back(run_of(s, p, video));
  return runs;
}

// The model entities the report lists: a step's role names what it is, or
// nullptr for a step that is no entity of the model (a view, the clock...).
const char* report_entity(ir::StepRole role) {
  switch (role) {
    case ir::StepRole::Constraint:
      return "constraint";
    case ir::StepRole::Monitor:
      return "monitor";
    case ir::StepRole::Controller:
      return "controller";
    case ir::StepRole::Motion:
      return "motion";
    case ir::StepRole::Clock:
    case ir::StepRole::Measurement:
    case ir::StepRole::Computation:
    case ir::StepRole::Solver:
      break;
  }
  return nullptr;
}

// The model the run came from, validated and lowered again: the page lists its
// constraints, monitors, controllers and motions where the files define them.
// The summary names the app; it is loaded only from inside the tree `report`
// runs in (--root, else the current directory), as an app's iri-map is: a
// shared summary must not make the page list a model of its reader's.
void describe_model(const std::string& app, const ReportFlags& flags, report::Input& in) {
  if (app.empty()) {
    in.model_verdict = "The run's summary names no app.";
    return;
  }
  const fs::path tree = canonical_path(flags.load.root.empty() ? "." : flags.load.root);
  const fs::path app_path = canonical_path(app);
  if (!is_within(app_path, tree)) {
    in.model_verdict = "The run's app (" + app + ") lies outside the tree mospec report runs in (" +
                       tree.string() +
                       "); it was not loaded (run mospec report where you ran the "
                       "run, or pass --root).";
    return;
  }
  if (!fs::is_regular_file(app_path)) {
    in.model_verdict = "The run's app (" + app +
                       ") is not found from here: run mospec report where you ran the run.";
    return;
  }
  PipelineFlags pipeline;
  pipeline.inputs = {app};
  pipeline.load = flags.load;
  int code = kExitOk;
  SourceFiles files;
  const auto program = load_validate_lower(pipeline, code, &files);
  if (!program) {
    in.model_verdict = app + " no longer validates and lowers (mospec exit status " +
                       std::to_string(code) + "; `mospec validate " + app + "` says why).";
    return;
  }
  in.model_ok = true;
  in.log_info = log_info(*program);
  in.model_verdict = app + " validates and lowers today: " + std::to_string(program->steps.size()) +
                     " steps, " + std::to_string(program->arms.size()) + " arm solver(s).";
  for (const ir::Step& s : program->steps) {
    const char* kind = report_entity(ir::role(s));
    if (!kind) continue;
    std::string iri = s.iri;
    if (ir::role(s) == ir::StepRole::Constraint && !s.out.empty()) {
      // The constraint it evaluates ("<constraint>#satisfied"), located at
      // the evaluator.
      const std::string& flag = program->data[static_cast<size_t>(s.out[0])].iri;
      iri = flag.substr(0, flag.rfind('#')) + " (evaluated by " + s.iri + ")";
    }
    report::Entity e{kind, iri, "", s.where.line};
    if (s.where.known()) {
      e.file = files.path(s.where.file);
    }
    in.entities.push_back(std::move(e));
  }
}

int run_report(const ReportFlags& flags) {
  const std::vector<report::Run> runs = runs_in(flags.input, !flags.no_video);
  const report::Assets assets = report::load_assets();
  report::Input in;
  SourceFiles files;
  for (const report::Run& r : runs) in.runs.push_back(report::load_run(r, files));
  in.title = flags.title.empty() ? "mospec report: " + flags.input : flags.title;
  in.page = flags.output;
  in.absolute_links = flags.absolute_links;
  describe_model(in.runs.front().summary.scenario, flags, in);
  write_output(flags.output, report::render(in, assets));
  std::cerr << "mospec: wrote " << flags.output << " (" << in.runs.size() << " run"
            << (in.runs.size() == 1 ? "" : "s") << ")\n";
  return kExitOk;
}

}  // namespace

Action add_report_command(CLI::App& app) {
  auto flags = std::make_shared<ReportFlags>();
  CLI::App* cmd = app.add_subcommand(
      "report",
      "Write one self-contained HTML page about a run (its SUMMARY.json from `mospec run "
      "--summary`, with SUMMARY.csv and an optional SUMMARY.mp4|.gif beside it) or a directory "
      "of runs or trials: the verdicts and timeline, interactive time series of the log, the "
      "video, and the model's constraints, monitors and controllers with their file:line. "
      "Works offline: nothing is fetched when it is opened.");
  cmd->add_option("input", flags->input, "A run's summary, or a directory of runs or trials")
      ->required()
      ->type_name("RUN.json|DIR");
  cmd->add_option("-o,--output", flags->output, "The page")->required()->type_name("FILE.html");
  cmd->add_option("--title", flags->title, "The page's title (default: from the input)");
  cmd->add_flag("--absolute-links", flags->absolute_links,
                "Link the model's files by absolute file:// URLs (the default links them "
                "relative to the page, so a shared page does not carry your directory names)");
  cmd->add_flag("--no-video", flags->no_video, "Leave the run's video out of the page");
  flags->load.add_to(*cmd);
  return [flags]() { return run_report(*flags); };
}

}  // namespace mospec::cli
