// `mospec plot INPUT -o FIG.svg|FIG.png`: the paper's Fig. 4 from one run log
// (`mospec run --log`), or its Fig. 6 (mean +- 1 std bands) from a directory of
// trials (`mospec trials`), rendered by gnuplot.
#include <algorithm>
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>

#include "cli/commands.hpp"
#include "json/json.hpp"
#include "plot/csv.hpp"
#include "plot/figure.hpp"
#include "plot/gnuplot.hpp"
#include "report/summary.hpp"
#include "support/diagnostics.hpp"
#include "support/io.hpp"

namespace mospec::cli {

namespace {

namespace fs = std::filesystem;

// trial-<i>.csv -> i; nullopt for any other name.
std::optional<unsigned long> trial_index(const std::string& name) {
  constexpr std::string_view prefix = "trial-", suffix = ".csv";
  if (name.size() <= prefix.size() + suffix.size() || name.compare(0, prefix.size(), prefix) != 0 ||
      name.compare(name.size() - suffix.size(), suffix.size(), suffix) != 0) {
    return std::nullopt;
  }
  const std::string digits =
      name.substr(prefix.size(), name.size() - prefix.size() - suffix.size());
  if (digits.empty() || digits.size() > 9 ||
      !std::all_of(digits.begin(), digits.end(),
                   [](unsigned char c) { return c >= '0' && c <= '9'; })) {
    return std::nullopt;
  }
  return std::stoul(digits);
}

// The trials' logs in index order. When `mospec trials` left a trials.json,
// trials that did not exit 0 are left out (their logs are not trustworthy),
// each with a warning.
std::vector<std::string> trial_logs(const std::string& dir) {
  std::vector<std::pair<unsigned long, std::string>> found;
  for (const fs::directory_entry& e : fs::directory_iterator(dir)) {
    if (!e.is_regular_file()) continue;
    if (auto i = trial_index(e.path().filename().string()))
      found.emplace_back(*i, e.path().string());
  }
  std::sort(found.begin(), found.end());
  const fs::path manifest = fs::path(dir) / "trials.json";
  std::vector<std::string> failed;
  if (fs::exists(manifest)) {
    // Read with locations: a manifest comes with a shared trials directory,
    // and a field of the wrong type is the file's fault, said where it is.
    SourceFiles files;
    const std::string path = manifest.string();
    const json::Value j = json::parse(read_file(path), files.add(path), path);
    const auto fail = [&](const json::Value& at, const std::string& what) {
      throw Error("trials",
                  "not a `mospec trials` manifest: " + what +
                      " (`mospec trials` writes it; delete it to plot the logs without it)",
                  path, at.location().line, at.location().column);
    };
    const json::Value* trials = j.get("trials");
    if (!trials || !trials->is_array()) fail(trials ? *trials : j, "\"trials\" is not an array");
    for (const json::Value& trial : trials->as_array()) {
      const json::Value* code = trial.get("exit_code");  // null: killed by a signal
      const json::Value* csv = trial.get("csv");         // null: never written
      if (!code || !(code->is_null() || code->is_number()))
        fail(code ? *code : trial, "a trial's \"exit_code\" is not a number or null");
      if (!csv || !(csv->is_null() || csv->is_string()))
        fail(csv ? *csv : trial, "a trial's \"csv\" is not a file name or null");
      if (csv->is_string() && !(code->is_number() && code->as_number() == 0))
        failed.emplace_back(csv->as_string());
    }
  }
  std::vector<std::string> logs;
  for (auto& [index, path] : found) {
    const std::string name = fs::path(path).filename().string();
    if (std::find(failed.begin(), failed.end(), name) != failed.end()) {
      std::cerr << "mospec: warning: leaving out " << path << ": its run did not exit 0 ("
                << manifest.string() << ")\n";
      continue;
    }
    logs.push_back(path);
  }
  if (logs.empty()) {
    std::string message = "no trial-<i>.csv logs to plot in '";
    message.append(dir).append("' (write them with `mospec trials`)");
    throw Error("io", message);
  }
  return logs;
}

// The scenario a run or trials came from, by the name of its app
// ("models/sc2.json" -> "sc2"): from a trials directory's trials.json ("app"),
// or from a run log's summary next to it (X.json or X-summary.json for X.csv,
// "scenario"). Empty when none says.
std::string scenario_name(const fs::path& json, const char* key) {
  std::error_code ec;
  if (!fs::is_regular_file(json, ec)) return "";
  try {
    const nlohmann::json j = nlohmann::json::parse(read_file(json.string()));
    const auto it = j.find(key);
    if (it == j.end() || !it->is_string()) return "";
    fs::path app = fs::path(it->get<std::string>()).lexically_normal();
    if (app.filename().empty()) app = app.parent_path();
    return app.stem().string();
  } catch (const std::exception&) {
    return "";  // not ours to judge here: the title falls back to the file's name
  }
}

std::string run_scenario(const std::string& csv) {
  const fs::path p(csv);
  fs::path stem = p;
  stem.replace_extension();
  for (const fs::path& json :
       {fs::path(stem.string() + ".json"), fs::path(stem.string() + "-summary.json")}) {
    std::string name = scenario_name(json, "scenario");
    if (!name.empty()) return name;
  }
  return "";
}

// The units and thresholds of a log's columns from the run's summary beside
// it (X.json or X-summary.json for X.csv; a trials directory: its
// trial-<i>.json), when there is one. A summary that does not read is said in
// a warning: the figure is drawn from the names then.
plot::LogInfo summary_log_info(const std::string& csv) {
  fs::path stem(csv);
  stem.replace_extension();
  for (const fs::path& json :
       {fs::path(stem.string() + ".json"), fs::path(stem.string() + "-summary.json")}) {
    std::error_code ec;
    if (!fs::is_regular_file(json, ec)) continue;
    try {
      SourceFiles files;
      return report::parse_summary(read_file(json.string()), json.string(), files).log;
    } catch (const Error& e) {
      Diagnostic d = e.diagnostic();
      d.severity = Severity::Warning;
      d.message += " (the figure takes the columns' units from their names)";
      std::cerr << format(d) << '\n';
      return {};
    }
  }
  return {};
}

}  // namespace

Action add_plot_command(CLI::App& app) {
  struct Flags {
    std::string input;
    std::string output;
    std::string title;
    plot::Selection selection;
  };
  auto flags = std::make_shared<Flags>();
  CLI::App* cmd = app.add_subcommand(
      "plot",
      "Render a run log (`mospec run --log`) as the paper's Fig. 4 - the shoulder-contact "
      "distances "
      "d_r, d_l [m] with their thresholds, and the platform wrench F_perp, F_par [N], tau [N m] "
      "(or, "
      "without one, each arm's distance-controller output [N]) - or a directory of trials (`mospec "
      "trials`) as Fig. 6: mean +- one standard deviation over the trials. A log of another app "
      "draws its constraints' values with their setpoints or thresholds dashed, and its "
      "controllers' outputs (else the constraints' errors), each panel in one unit (from the "
      "run's summary beside the log). Needs gnuplot.");
  cmd->add_option("input", flags->input, "A run's CSV log, or a directory of trial-<i>.csv logs")
      ->required()
      ->type_name("CSV|DIR");
  cmd->add_option("-o,--output", flags->output, "The figure; the format follows the extension")
      ->required()
      ->type_name("FIG.svg|FIG.png");
  cmd->add_option(
      "--title", flags->title,
      "Figure title (default: the scenario's name, from the trials' trials.json or "
      "the run's summary X.json / X-summary.json next to X.csv; else the input's name)");
  cmd->add_option(
         "--distance", flags->selection.distances,
         "A distance column [m] for the left panel instead of the shoulder-contact distances; "
         "repeatable. Its .lower/.upper columns, when present, are drawn as thresholds.")
      ->type_name("COL");
  cmd->add_option(
         "--force", flags->selection.forces,
         "A force column [N] for the right panel instead of the defaults (a column ending in .mz "
         "goes on the right-hand torque scale); repeatable.")
      ->type_name("COL");
  return [flags]() {
    plot::format_of(flags->output);  // a bad extension fails before any reading
    std::error_code ec;
    plot::Figure figure;
    if (fs::is_directory(flags->input, ec)) {
      std::vector<plot::Table> trials;
      for (const std::string& log : trial_logs(flags->input)) trials.push_back(plot::read_csv(log));
      if (flags->selection.info.empty())
        flags->selection.info = summary_log_info(trials.front().path);
      std::string title = flags->title;
      if (title.empty()) {
        title = scenario_name(fs::path(flags->input) / "trials.json", "app");
        if (title.empty()) title = fs::path(flags->input).lexically_normal().filename().string();
        if (title.empty())
          title = fs::path(flags->input).lexically_normal().parent_path().filename().string();
        title.append(": mean ± 1 std over ")
            .append(std::to_string(trials.size()))
            .append(trials.size() == 1 ? " trial" : " trials");
      }
      figure = plot::trials_figure(trials, flags->selection, title);
      plot::render(figure, flags->output);
      std::cerr << "mospec: wrote " << flags->output << " (" << trials.size()
                << (trials.size() == 1 ? " trial)\n" : " trials)\n");
    } else {
      const plot::Table run = plot::read_csv(flags->input);
      if (flags->selection.info.empty()) flags->selection.info = summary_log_info(flags->input);
      std::string title = flags->title;
      if (title.empty()) title = run_scenario(flags->input);
      if (title.empty()) title = fs::path(flags->input).filename().string();
      figure = plot::run_figure(run, flags->selection, title);
      plot::render(figure, flags->output);
      std::cerr << "mospec: wrote " << flags->output << "\n";
    }
    return kExitOk;
  };
}

}  // namespace mospec::cli
