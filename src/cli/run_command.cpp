// `mospec run APP --sim`: validate -> lower -> run the controller against the
// simulated robot -> log and summary. With --interpret the IR is executed
// directly; otherwise the generated controller is built (cached by content
// hash) and loaded. With --video the run is rendered (src/video).
#include <cmath>
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <sstream>

#include "cli/faults.hpp"
#include "cli/log_info.hpp"
#include "cli/loop_check.hpp"
#include "cli/numbers.hpp"
#include "cli/pipeline.hpp"
#include "cli/world_arms.hpp"
#include "codegen/build.hpp"
#include "codegen/codegen.hpp"
#include "description/base_rdf.hpp"
#include "description/robot_model.hpp"
#include "ir/interpreter.hpp"
#include "sim/config.hpp"
#include "sim/run.hpp"
#include "sim/world.hpp"
#include "support/io.hpp"
#include "verdict/verdict.hpp"
#include "video/recorder.hpp"

namespace mospec::cli {

using verdict::degraded_solves;
using verdict::judge;
using verdict::plan_verdict;
using verdict::Verdict;
using verdict::VerdictPlan;
using verdict::watch_for_verdict;

namespace {

// --video-size WxH: even sides in [16, 4096] (H.264 needs even sides).
CLI::Validator frame_size() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        const size_t x = text.find('x');
        auto side = [](const std::string& t) {
          if (t.empty() || t.size() > 4 || t.find_first_not_of("0123456789") != std::string::npos)
            return -1;
          return std::stoi(t);
        };
        const int w = x == std::string::npos ? -1 : side(text.substr(0, x));
        const int h = x == std::string::npos ? -1 : side(text.substr(x + 1));
        if (w < 0 || h < 0) return "'" + text + "' is not WIDTHxHEIGHT (e.g. 640x480)";
        if (w < 16 || h < 16 || w > 4096 || h > 4096 || w % 2 != 0 || h % 2 != 0) {
          return text + ": each side must be even and in [16, 4096] pixels";
        }
        return {};
      },
      "WxH");
}

video::FrameSize parse_frame_size(const std::string& text) {
  const size_t x = text.find('x');
  return {std::stoi(text.substr(0, x)), std::stoi(text.substr(x + 1))};
}

std::string describe_pose(const runtime::Pose& X) {
  std::ostringstream s;
  s.precision(9);
  s << "position (" << X.p.x() << ", " << X.p.y() << ", " << X.p.z() << ") m";
  return s.str();
}

// The arms' mounts come from the task models: a solver rooted elsewhere than
// its chain's root composes the models' constant pose X_RB into the chain,
// and the simulator mounts that arm's base at the same X_RB in the platform
// frame, so the IR and the simulated robot agree by construction. A world
// file may state the mount of an arm the models do not mount (or the same
// pose); anything else would leave the task and the simulated robot
// disagreeing about where the arm is.
void mount_arms(const ir::Program& program, const SourceFiles& files, sim::WorldConfig& config) {
  std::string root;  // the frame the mounted solvers share: the platform's
  for (const ir::ArmSolver& a : program.arms) {
    if (a.mount_pose_iri.empty()) continue;
    const std::string file = a.where.known() ? files.path(a.where.file) : std::string();
    if (root.empty()) {
      root = a.root_frame;
    } else if (a.root_frame != root) {
      throw Error("mount-mismatch",
                  "the arm solver '" + a.iri + "' is rooted at '" + a.root_frame +
                      "', another mounted arm's solver at '" + root +
                      "'; the simulator mounts every arm on one platform: root the solvers of "
                      "mounted arms at the platform's frame",
                  file, a.where.line, a.where.column);
    }
    if (a.port < 0 || static_cast<size_t>(a.port) >= config.arms.size()) continue;
    sim::ArmSetup& arm = config.arms[static_cast<size_t>(a.port)];
    const bool same = (arm.X_PB.R - a.X_RB.R).cwiseAbs().maxCoeff() <= 1e-9 &&
                      (arm.X_PB.p - a.X_RB.p).cwiseAbs().maxCoeff() <= 1e-9;
    if (!arm.mount_source.empty() && !same) {
      throw Error("mount-mismatch",
                  "the arm solver '" + a.iri + "' mounts its chain at '" + a.mount_pose_iri +
                      "' (" + describe_pose(a.X_RB) + "), but " + arm.mount_source + " puts the " +
                      arm.name + " arm elsewhere (" + describe_pose(arm.X_PB) +
                      "); state the mount once, in the task models, and drop it from the "
                      "world file",
                  file, a.where.line, a.where.column);
    }
    arm.X_PB = a.X_RB;
    arm.mount_source = "the task models' '" + a.mount_pose_iri + "'";
  }
}

// The generated controller for `program`, generated and built once into the
// cache (the user's cache directory unless --cache, keyed by SHA-256 of
// everything that affects the build, under a file lock so concurrent runs
// share one build), then loaded after checking its content against the hash
// recorded when it was built (src/codegen/build.hpp).
std::unique_ptr<robot::Controller> generated_controller(const ir::Program& program,
                                                        const SourceFiles& files,
                                                        const std::string& cache) {
  const codegen::CachedController c = codegen::cached_controller(
      program, cache.empty() ? codegen::default_cache_dir() : cache, &files);
  if (!c.rebuilt_because.empty()) {
    std::cerr << "mospec: warning: the cached controller in " << c.project
              << " was not used: " << c.rebuilt_because << "; built it again\n";
  }
  if (c.built) std::cerr << "mospec: generated and built the controller in " << c.project << '\n';
  return codegen::load_controller(c.library, c.sha256);
}

std::string summary_json(const std::string& app, const sim::RunResult& r, bool interpreted,
                         const Verdict& verdict, const plot::LogInfo& log) {
  nlohmann::ordered_json j;
  j["scenario"] = app;
  j["controller"] = interpreted ? "interpreted" : "generated";
  j["duration"] = r.simulated;
  j["ticks"] = r.ticks;
  j["wall_time"] = r.wall;
  j["non_finite"] = r.non_finite;
  j["non_finite_logged_rows"] = r.non_finite_values;
  j["max_torque_ratio"] = r.max_torque_ratio;
  j["torque_limit_exceeded"] = r.torque_limit_exceeded;
  j["joint_limit_exceeded"] = r.joint_limit_exceeded;
  j["instabilities"] = r.instabilities;
  // What the robot interface clamped to the actuation limits (robot/limits.hpp).
  j["command_clamped"] = r.clamped;
  nlohmann::ordered_json clamps = nlohmann::ordered_json::array();
  for (const robot::ClampRecord& c : r.clamps) {
    if (c.ticks == 0) continue;
    nlohmann::ordered_json e;
    e["actuator"] = c.quantity;
    e["ticks"] = c.ticks;
    e["first_tick"] = c.first_tick;
    e["max_requested"] = std::isfinite(c.max_requested) ? nlohmann::ordered_json(c.max_requested)
                                                        : nlohmann::ordered_json(nullptr);
    e["limit"] = c.limit;
    e["unit"] = c.unit;
    clamps.push_back(std::move(e));
  }
  j["clamped_actuators"] = std::move(clamps);
  // Every bilateral constraint (a tube, e.g. the shoulder–contact distances):
  // where it ended and whether that is inside.
  nlohmann::ordered_json tubes = nlohmann::ordered_json::array();
  for (const std::string& c : r.columns) {
    const std::string suffix = ".lower";
    if (c.size() <= suffix.size() ||
        c.compare(c.size() - suffix.size(), suffix.size(), suffix) != 0)
      continue;
    const std::string name = c.substr(0, c.size() - suffix.size());
    const double v = sim::last_value(r, name + ".value");
    const double lo = sim::last_value(r, name + ".lower");
    const double hi = sim::last_value(r, name + ".upper");
    nlohmann::ordered_json t;
    t["constraint"] = name;
    t["final"] = v;
    t["lower"] = lo;
    t["upper"] = hi;
    t["inside"] = v >= lo && v <= hi;
    tubes.push_back(std::move(t));
  }
  j["bilateral"] = std::move(tubes);
  // Every event, with its tick (sim::RunResult::events): monitors' edges and
  // how motions ended.
  nlohmann::ordered_json events = nlohmann::ordered_json::array();
  for (const sim::RunEvent& e : r.events) {
    const std::string& column = r.columns[e.column];
    const bool motion = column.ends_with(".ended");
    const char* what = e.code == 1   ? (motion ? "until" : "rising")
                       : e.code == 2 ? (motion ? "while-violated" : "falling")
                                     : "both";
    nlohmann::ordered_json x;
    x["tick"] = e.tick;
    x["time"] = e.time;
    x["event"] = column;
    x[motion ? "reason" : "edge"] = what;
    events.push_back(std::move(x));
  }
  j["events"] = std::move(events);
  j["events_not_listed"] = r.events_dropped;
  // Per arm solver, the ticks whose solve lost constraint directions.
  nlohmann::ordered_json degraded = nlohmann::ordered_json::object();
  for (const auto& [solver, ticks] : degraded_solves(r)) degraded[solver] = ticks;
  j["degraded_solves"] = std::move(degraded);
  // The table's edge runs along y of the world: the platform is aligned with
  // it at yaw 0.
  const double yaw = sim::last_value(r, "base_yaw");
  j["base_yaw_to_edge_deg"] = std::isfinite(yaw) ? yaw * 180.0 / std::numbers::pi : 0.0;
  nlohmann::ordered_json final_values;
  for (size_t i = 0; i < r.columns.size() && i < r.last_row.size(); ++i) {
    const double v = r.last_row[i];
    final_values[r.columns[i]] =
        std::isfinite(v) ? nlohmann::ordered_json(v) : nlohmann::ordered_json(nullptr);
  }
  j["final"] = std::move(final_values);
  // The log's units and the constraints' thresholds, for the figures and the
  // report page (plot/log_info.hpp).
  j["log"] = log_info_json(log);
  // What happened, in short (verdict/verdict.hpp).
  j["verdict"] = verdict.json;
  return j.dump(2) + "\n";
}

}  // namespace

Action add_run_command(CLI::App& app) {
  struct Flags {
    PipelineFlags pipeline;
    bool sim = false;
    bool interpret = false;
    double duration = 10.0;
    std::optional<std::uint64_t> seed;
    std::string base;
    std::string log;
    std::string summary;
    int log_every = 10;
    std::string cache;
    std::vector<std::string> faults;
    bool run_diverging = false;
    std::string video;
    std::string video_size = "640x480";
    std::string video_camera = "corner";
  };
  auto flags = std::make_shared<Flags>();
  CLI::App* cmd = app.add_subcommand("run", kRunSummary);
  flags->pipeline.add_to(*cmd);
  // The MuJoCo simulation is the only target, so it is the default; `--sim`
  // stays accepted (scripts and docs of earlier versions) but is not listed.
  cmd->add_flag("--sim", flags->sim, "Run against the MuJoCo simulation (the default)")->group("");
  cmd->add_flag("--interpret", flags->interpret,
                "Execute the IR directly instead of generating and building C++");
  cmd->add_option("--duration", flags->duration,
                  "Simulated time [s], in (0, 86400] and at most 10^7 control ticks")
      ->check(finite_number(0.0, 86400.0, true, "s"))
      ->capture_default_str();
  cmd->add_option("--seed", flags->seed, "Seed of the world's initial perturbations (0..2^53)")
      ->check(integer_in(0, kMaxSeed));
  cmd->add_option("--base", flags->base, "Base model (overrides the world)")
      ->check(CLI::IsMember({"wheeled", "planar", "fixed"}));
  cmd->add_option("--log", flags->log, "CSV log file ('-' = standard output)")
      ->type_name("FILE.csv");
  cmd->add_option("--log-every", flags->log_every, "Log every N-th control tick")
      ->check(CLI::Range(1, 1000000))
      ->capture_default_str();
  cmd->add_option("--summary", flags->summary, "JSON summary file ('-' = standard output)")
      ->type_name("FILE.json");
  cmd->add_option("--fault", flags->faults, kFaultHelp)->type_name("SPEC");
  cmd->add_flag("--run-diverging", flags->run_diverging,
                "Run even if the loop check finds a loop that would diverge (its findings become "
                "warnings): to watch it happen, or where the linearisation misjudges a loop");
  CLI::Option* video =
      cmd->add_option("--video", flags->video,
                      "Video of the run, rendered offscreen by MuJoCo at 30 frames per simulated "
                      "second and encoded by ffmpeg: .mp4 (H.264) or .gif")
          ->type_name("FILE.mp4|FILE.gif");
  // Without --video they would do nothing: refused instead.
  cmd->add_option("--video-size", flags->video_size, "The video's frame size in pixels")
      ->needs(video)
      ->check(frame_size())
      ->capture_default_str();
  cmd->add_option("--video-camera", flags->video_camera,
                  "Where the video's camera looks from: corner (behind the robot's right, 30 "
                  "degrees down) or top (straight down)")
      ->needs(video)
      ->check(CLI::IsMember({"corner", "top"}))
      ->capture_default_str();
  cmd->add_option("--cache", flags->cache,
                  "Directory of generated and built controllers, private to you (default: "
                  "$XDG_CACHE_HOME/mospec, else ~/.cache/mospec)")
      ->type_name("DIR");
  return [flags]() {
    int code = kExitOk;
    SourceFiles files;
    // The world is read once: the program's arms are bound to the arms of
    // the file that is simulated (a second read could see another file).
    const std::string app_path = resolve_app(flags->pipeline.inputs.front());
    const std::string world_file = scenario_world_file(app_path, flags->pipeline.world);
    // Which world the run is in: a world file found (or not) beside the app
    // changes the robot, so the run names it.
    const std::string sibling = default_world_file_name(app_path);
    std::cerr << "mospec: world: "
              << (!world_file.empty() ? world_file
                  : sibling.empty()   ? std::string("mospec's default world")
                                      : "mospec's default world (there is no " + sibling + ")")
              << '\n';
    sim::WorldConfig config = scenario_world(app_path, flags->pipeline.world);
    auto program = load_validate_lower(flags->pipeline, code, &files, {}, &config);
    if (!program) return code;
    if (!flags->base.empty()) config.base = *sim::parse_base_fidelity(flags->base);
    if (flags->seed) config.seed = *flags->seed;
    // Refuse a run too long to simulate before building anything.
    (void)sim::tick_count(flags->duration, config.control_period,
                          static_cast<std::uint64_t>(flags->log_every));
    mount_arms(*program, files, config);
    std::vector<runtime::Chain> arms = arm_chains(config, &*program);
    sim::actuation_from_chains(config, arms);
    // The simulated base is the program's (the numbers lowering read from the
    // configuration its platform solvers name); a program without a base
    // drives none, and the world's base is the default robot description's.
    config.drives = program->base ? ir::kelo_config(*program->base)
                                  : description::load_base(config.base_model.model,
                                                           config.base_model.configuration);
    sim::RunOptions options;
    options.duration = flags->duration;
    options.log_every = flags->log_every;
    options.idle.assign(config.arms.size(), true);
    for (const ir::ArmSolver& a : program->arms) options.idle[static_cast<size_t>(a.port)] = false;
    // Before anything runs: no loop whose gain drives its error away or
    // puts a pole outside the unit circle (unless the user asks to see it).
    if (std::vector<Diagnostic> loops = check_loops(*program, config, arms, files);
        !loops.empty()) {
      for (Diagnostic& d : loops) {
        if (flags->run_diverging) d.severity = Severity::Warning;
        std::cerr << format(d) << '\n';
      }
      if (!flags->run_diverging) {
        std::cerr << "mospec: " << loops.size()
                  << " controller loop(s) that would diverge; nothing was run (--run-diverging "
                     "runs it anyway)\n";
        return kExitFindings;
      }
    }
    const VerdictPlan plan = plan_verdict(*program);
    const plot::LogInfo log = log_info(*program);
    watch_for_verdict(plan, options);
    sim::World world(config, std::move(arms));
    for (const std::string& f : flags->faults) add_fault(world.faults(), f);
    // The video's encoder starts before the controller is built and the run
    // starts, so a bad path, format or a missing ffmpeg fails first.
    std::unique_ptr<video::Recorder> recorder;
    if (!flags->video.empty()) {
      video::VideoOptions v;
      v.size = parse_frame_size(flags->video_size);
      (void)video::parse_camera(flags->video_camera, v.camera);  // checked by CLI11
      recorder = std::make_unique<video::Recorder>(world, flags->video, v);
      options.observer = recorder.get();
    }
    std::unique_ptr<robot::Controller> controller;
    if (flags->interpret) {
      controller = std::make_unique<ir::Interpreter>(std::move(*program));
    } else {
      controller = generated_controller(*program, files, flags->cache);
    }
    const sim::RunResult r = sim::run(world, *controller, options);
    if (recorder) recorder->finish();
    const Verdict verdict = judge(plan, r);
    if (!flags->log.empty()) write_output(flags->log, r.csv);
    if (!flags->summary.empty()) {
      write_output(flags->summary, summary_json(app_path, r, flags->interpret, verdict, log));
    }
    std::cerr << "mospec: ran " << r.simulated << " s (" << r.ticks << " ticks, "
              << (flags->interpret ? "interpreted" : "generated") << " controller) in " << r.wall
              << " s\n";
    if (recorder) {
      std::cerr << "mospec: wrote " << recorder->frames() << " frames to " << flags->video
                << " (rendering and encoding took " << recorder->seconds() << " s)\n";
    }
    sim::report_clamps(std::cerr, r.clamps);  // a clamp is a limit breach: the verdict fails
    for (const auto& [solver, ticks] : degraded_solves(r)) {
      if (ticks == 0) continue;
      std::cerr << "mospec: warning: the solver '" << solver << "' lost constraint directions in "
                << ticks << " of " << r.ticks
                << " ticks (a singular configuration or conflicting constraints); its `.degraded` "
                   "log column says when\n";
    }
    if (r.instabilities > 0) {
      std::cerr << "mospec: error: MuJoCo reported " << r.instabilities
                << " instability warning(s); the log is not trustworthy\n";
    }
    if (r.non_finite) {
      std::cerr << "mospec: error: the controller commanded a value that is not finite\n";
    }
    // Exit 1 when a limit was breached, a command was not finite, a `while`
    // aborted a motion or MuJoCo was unstable.
    std::cerr << verdict.text;
    return verdict.failed ? kExitFindings : kExitOk;
  };
}

}  // namespace mospec::cli
