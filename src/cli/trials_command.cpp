// `mospec trials APP -n N -o DIR`: N seeded runs of one app, each a child
// process `mospec run APP --seed K+i --log DIR/trial-<i>.csv --summary
// DIR/trial-<i>.json` (its messages in DIR/trial-<i>.log), J at a time. The
// manifest DIR/trials.json is written last and atomically, so a directory
// without it is an unfinished (or interrupted) set of trials.
#include <algorithm>
#include <chrono>
#include <filesystem>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>

#include "cli/commands.hpp"
#include "cli/numbers.hpp"
#include "plot/process.hpp"
#include "support/diagnostics.hpp"
#include "support/io.hpp"

namespace mospec::cli {

namespace {

namespace fs = std::filesystem;

struct Trial {
  unsigned index = 0;
  std::uint64_t seed = 0;
  plot::ChildExit exit;
  double wall = 0.0;  // [s]
};

std::string trial_file(unsigned index, const char* extension) {
  std::string name = "trial-";
  name.append(std::to_string(index)).append(extension);
  return name;
}

// Removes what an earlier `mospec trials` left in `dir` (the manifest first, so
// the directory never looks complete with stale trials): trials.json and
// trial-<digits>.{csv,json,log}. Nothing else is touched.
void clear_previous(const fs::path& dir) {
  std::error_code ec;
  fs::remove(dir / "trials.json", ec);
  for (const fs::directory_entry& e : fs::directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    if (name.rfind("trial-", 0) != 0 || !e.is_regular_file()) continue;
    const size_t dot = name.find('.');
    const std::string digits =
        name.substr(6, dot == std::string::npos ? std::string::npos : dot - 6);
    const std::string ext = dot == std::string::npos ? "" : name.substr(dot);
    if (!digits.empty() &&
        std::all_of(digits.begin(), digits.end(),
                    [](unsigned char c) { return c >= '0' && c <= '9'; }) &&
        (ext == ".csv" || ext == ".json" || ext == ".log")) {
      fs::remove(e.path(), ec);
    }
  }
}

// The last lines of a trial's log, for the message about a failed trial.
std::string tail(const fs::path& log, size_t lines) {
  std::string text;
  if (!read_file_reason(log.string(), text).empty()) return {};  // no log: nothing to quote
  std::vector<std::string> all;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) all.push_back(line);
  std::string out;
  for (size_t i = all.size() > lines ? all.size() - lines : 0; i < all.size(); ++i) {
    out.append("  ").append(all[i]).append("\n");
  }
  return out;
}

}  // namespace

Action add_trials_command(CLI::App& app) {
  struct Flags {
    std::string app;
    bool sim = false;
    unsigned n = 0;
    unsigned jobs = 0;
    std::optional<double> duration;
    bool interpret = false;
    std::uint64_t seed_base = 0;
    std::string out;
    // Passed through to every `mospec run`.
    std::vector<std::string> maps, binds;
    std::string root, world, base, cache;
    std::optional<int> log_every;
    bool strict = false;
  };
  auto flags = std::make_shared<Flags>();
  CLI::App* cmd =
      app.add_subcommand("trials",
                         "Run N seeded simulations of an app (each `mospec run APP --seed "
                         "K+i`, in parallel child "
                         "processes) into DIR: trial-<i>.csv (log), trial-<i>.json (summary), "
                         "trial-<i>.log (messages), "
                         "then DIR/trials.json (per trial: seed, exit code, files; totals). Exit 0 "
                         "only if every trial "
                         "exited 0. `mospec plot DIR` draws the trials' mean and spread.");
  cmd->add_option("app", flags->app, "App model")->required()->type_name("APP");
  // As `mospec run`'s: the simulation is the only target, so the default;
  // `--sim` stays accepted but is not listed.
  cmd->add_flag("--sim", flags->sim, "Run against the MuJoCo simulation (the default)")->group("");
  cmd->add_option("-n", flags->n, "Number of trials")->required()->check(CLI::Range(1u, 100000u));
  cmd->add_option("--jobs,-j", flags->jobs, "Trials run at a time (default: the number of cores)")
      ->check(CLI::Range(1u, 4096u));
  cmd->add_option("--duration", flags->duration,
                  "Simulated time per trial [s], in (0, 86400] (default: `mospec run`'s)")
      ->check(finite_number(0.0, 86400.0, true, "s"));
  cmd->add_flag("--interpret", flags->interpret,
                "Execute the IR directly instead of generated C++");
  cmd->add_option("--seed-base", flags->seed_base, "Trial i runs with seed K+i (K+N-1 <= 2^53)")
      ->check(integer_in(0, kMaxSeed))
      ->type_name("K")
      ->capture_default_str();
  cmd->add_option("-o,--output", flags->out, "Directory of the trials (created)")
      ->required()
      ->type_name("DIR");
  cmd->add_option("--map", flags->maps, "Passed to `mospec run` (IRI=DIR); repeatable")
      ->type_name("IRI=DIR");
  cmd->add_option("--bind", flags->binds, "Passed to `mospec run` (CHAIN=right|left); repeatable")
      ->type_name("CHAIN=ARM");
  cmd->add_option("--root", flags->root,
                  "Passed to `mospec run`: resolve the app's iri-map against DIR")
      ->type_name("DIR");
  cmd->add_flag("--strict", flags->strict, "Passed to `mospec run`");
  cmd->add_option("--world", flags->world, "Passed to `mospec run`: world file")->type_name("FILE");
  cmd->add_option("--base", flags->base, "Passed to `mospec run`: base model")
      ->check(CLI::IsMember({"wheeled", "planar", "fixed"}));
  cmd->add_option("--log-every", flags->log_every, "Passed to `mospec run`: log every N-th tick")
      ->check(CLI::Range(1, 1000000));
  cmd->add_option("--cache", flags->cache, "Passed to `mospec run`: controller cache")
      ->type_name("DIR");
  return [flags]() {
    if (flags->seed_base > kMaxSeed - (flags->n - 1)) {
      throw Error("usage", "--seed-base " + std::to_string(flags->seed_base) + " with -n " +
                               std::to_string(flags->n) +
                               ": the last trial's seed would exceed "
                               "2^53 (seeds are integers 0..2^53)");
    }
    const fs::path dir(flags->out);
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec || !fs::is_directory(dir)) {
      std::string message = "cannot create the trials directory '";
      message.append(flags->out).append("': ").append(ec ? ec.message() : "not a directory");
      throw Error("io", message);
    }
    clear_previous(dir);
    const std::string self = plot::self_executable();
    const unsigned jobs =
        flags->jobs > 0 ? flags->jobs : std::max(1u, std::thread::hardware_concurrency());

    auto argv_of = [&](const Trial& t) {
      std::vector<std::string> argv = {self,
                                       "run",
                                       flags->app,
                                       "--seed",
                                       std::to_string(t.seed),
                                       "--log",
                                       (dir / trial_file(t.index, ".csv")).string(),
                                       "--summary",
                                       (dir / trial_file(t.index, ".json")).string()};
      if (flags->interpret) argv.emplace_back("--interpret");
      if (flags->duration) argv.insert(argv.end(), {"--duration", exact_number(*flags->duration)});
      for (const std::string& m : flags->maps) argv.insert(argv.end(), {"--map", m});
      for (const std::string& b : flags->binds) argv.insert(argv.end(), {"--bind", b});
      if (!flags->root.empty()) argv.insert(argv.end(), {"--root", flags->root});
      if (flags->strict) argv.emplace_back("--strict");
      if (!flags->world.empty()) argv.insert(argv.end(), {"--world", flags->world});
      if (!flags->base.empty()) argv.insert(argv.end(), {"--base", flags->base});
      if (flags->log_every)
        argv.insert(argv.end(), {"--log-every", std::to_string(*flags->log_every)});
      if (!flags->cache.empty()) argv.insert(argv.end(), {"--cache", flags->cache});
      return argv;
    };

    using Clock = std::chrono::steady_clock;
    const auto start = Clock::now();
    std::vector<Trial> trials(flags->n);
    std::map<pid_t, std::pair<unsigned, Clock::time_point>> running;
    unsigned next = 0;
    // A generated controller is built into the cache by the first run that
    // needs it, and concurrent runs would race to build the same one: without
    // --interpret, trial 0 runs alone and the others find it built.
    bool warming = !flags->interpret;
    auto reap = [&]() {
      const plot::ChildExit e = plot::wait_any_child();
      auto it = running.find(e.pid);
      if (it == running.end()) return;  // not one of ours
      Trial& t = trials[it->second.first];
      t.exit = e;
      t.wall = std::chrono::duration<double>(Clock::now() - it->second.second).count();
      if (t.index == 0) warming = false;
      running.erase(it);
    };
    try {
      while (next < flags->n || !running.empty()) {
        while (next < flags->n && running.size() < (warming ? 1u : jobs)) {
          Trial& t = trials[next];
          t.index = next;
          t.seed = flags->seed_base + next;
          const pid_t pid =
              plot::spawn_logged(argv_of(t), (dir / trial_file(t.index, ".log")).string());
          running.emplace(pid, std::make_pair(next, Clock::now()));
          ++next;
        }
        reap();
      }
    } catch (...) {
      while (!running.empty()) reap();  // never leave children behind
      throw;
    }
    const double wall = std::chrono::duration<double>(Clock::now() - start).count();

    nlohmann::ordered_json j;
    j["app"] = flags->app;
    j["controller"] = flags->interpret ? "interpreted" : "generated";
    j["seed_base"] = flags->seed_base;
    if (flags->duration) j["duration"] = *flags->duration;
    j["jobs"] = jobs;
    unsigned passed = 0;
    const Trial* first_failed = nullptr;
    int worst = kExitOk;
    nlohmann::ordered_json list = nlohmann::ordered_json::array();
    for (const Trial& t : trials) {
      nlohmann::ordered_json e;
      e["index"] = t.index;
      e["seed"] = t.seed;
      e["exit_code"] = t.exit.exit_code >= 0 ? nlohmann::ordered_json(t.exit.exit_code)
                                             : nlohmann::ordered_json(nullptr);
      if (t.exit.signal) e["signal"] = t.exit.signal;
      const std::string csv = trial_file(t.index, ".csv"), summary = trial_file(t.index, ".json");
      e["csv"] =
          fs::exists(dir / csv) ? nlohmann::ordered_json(csv) : nlohmann::ordered_json(nullptr);
      e["summary"] = fs::exists(dir / summary) ? nlohmann::ordered_json(summary)
                                               : nlohmann::ordered_json(nullptr);
      e["log"] = trial_file(t.index, ".log");
      e["wall_time"] = t.wall;
      list.push_back(std::move(e));
      if (t.exit.ok()) {
        ++passed;
      } else {
        if (first_failed == nullptr) first_failed = &t;
        // A crash or bad input outranks a model finding.
        worst = std::max(worst, t.exit.exit_code == kExitFindings ? kExitFindings : kExitBadInput);
      }
    }
    j["trials"] = std::move(list);
    j["totals"] = {{"trials", flags->n},
                   {"passed", passed},
                   {"failed", flags->n - passed},
                   {"wall_time", wall}};
    const fs::path manifest = dir / "trials.json";
    write_output(manifest.string(), j.dump(2) + "\n");
    if (first_failed != nullptr) {
      const fs::path log = dir / trial_file(first_failed->index, ".log");
      std::cerr << "mospec: trial " << first_failed->index << " (seed " << first_failed->seed
                << ") " << first_failed->exit.describe() << "; the end of " << log.string() << ":\n"
                << tail(log, 6);
    }
    std::cerr << "mospec: trials: " << passed << "/" << flags->n << " exited 0 (" << jobs
              << " at a time, " << wall << " s); " << manifest.string() << "\n";
    return worst;
  };
}

}  // namespace mospec::cli
