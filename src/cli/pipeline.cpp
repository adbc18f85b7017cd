#include "cli/pipeline.hpp"

#include <filesystem>
#include <iostream>

#include "cli/commands.hpp"
#include "shacl/report.hpp"
#include "sim/config.hpp"
#include "support/diagnostics.hpp"
#include "validation/model_validation.hpp"

namespace mospec::cli {

void PipelineFlags::add_to(CLI::App& cmd) {
  cmd.add_option("app", inputs, "App model")->required()->type_name("APP");
  cmd.add_option("--bind", binds,
                 "Bind a kinematic chain to an arm of the robot (CHAIN=ARM, ARM an arm's name "
                 "in the world file or its index); the world file's arms bind their chains")
      ->type_name("CHAIN=ARM");
  cmd.add_option("--world", world,
                 "World file (JSON, docs/simulation.md): the robot, whose arms the chains drive, "
                 "and for `run` the simulated world (default: the app's sibling "
                 "NAME.world.json, else mospec's default robot and world)")
      ->type_name("FILE");
  load.add_to(cmd);
  load.add_budget_to(cmd);
}

void refuse_world_file_as_model(const std::string& path) {
  constexpr std::string_view kWorld = ".world.json";
  if (!path.ends_with(kWorld)) return;
  const std::string app = path.substr(0, path.size() - kWorld.size()) + ".json";
  std::error_code ec;
  throw Error("usage", "'" + path +
                           "' is a world file (the robot and the simulated world, "
                           "docs/simulation.md), not a model: give the app it goes with" +
                           (std::filesystem::is_regular_file(app, ec) ? ", '" + app + "'" : "") +
                           " (`mospec run APP` reads the world file beside it, or --world FILE)");
}

std::string resolve_app(const std::string& path) {
  refuse_world_file_as_model(path);
  std::error_code ec;
  if (std::filesystem::exists(path, ec)) {
    if (std::filesystem::is_directory(path, ec)) {
      std::string trimmed = path;
      while (trimmed.size() > 1 && trimmed.back() == '/') trimmed.pop_back();
      if (std::filesystem::is_regular_file(trimmed + ".json", ec)) return trimmed + ".json";
    }
    return path;
  }
  if (std::filesystem::is_regular_file(path + ".json", ec)) return path + ".json";
  return path;
}

std::string default_world_file_name(const std::string& app) {
  std::filesystem::path w(app);
  if (w.extension() != ".json") return "";
  w.replace_extension(".world.json");
  return w.string();
}

std::string scenario_world_file(const std::string& app, const std::string& world_file) {
  if (!world_file.empty()) return world_file;
  const std::string w = default_world_file_name(app);
  std::error_code ec;
  return !w.empty() && std::filesystem::exists(w, ec) ? w : "";
}

sim::WorldConfig scenario_world(const std::string& app, const std::string& world_file,
                                bool check_files) {
  const std::string w = scenario_world_file(app, world_file);
  return w.empty() ? sim::default_world() : sim::load_world_config(w, check_files);
}

std::map<std::string, int> arm_ports(const sim::WorldConfig& world,
                                     const std::vector<std::string>& binds) {
  std::map<std::string, int> ports;
  for (size_t k = 0; k < world.arms.size(); ++k) {
    ports[sim::arm_chain(world, k)] = static_cast<int>(k);
  }
  for (const std::string& b : binds) {
    const auto eq = b.find('=');
    const std::string arm = eq == std::string::npos ? "" : b.substr(eq + 1);
    int port = -1;
    for (size_t k = 0; k < world.arms.size(); ++k) {
      if (world.arms[k].name == arm || std::to_string(k) == arm) port = static_cast<int>(k);
    }
    if (eq == std::string::npos || eq == 0 || port < 0) {
      std::string names;
      for (const sim::ArmSetup& a : world.arms) names += (names.empty() ? "" : ", ") + a.name;
      throw Error("usage", "--bind expects CHAIN=ARM with ARM one of the robot's arms (" +
                               (names.empty() ? std::string("it has none") : names) +
                               ") or its index, got '" + b + "'");
    }
    ports[b.substr(0, eq)] = port;
  }
  return ports;
}

std::optional<ir::Program> load_validate_lower(const PipelineFlags& flags, int& exit_code,
                                               SourceFiles* files, const AfterPass& after_pass,
                                               const sim::WorldConfig* world) {
  ir::LowerOptions options;
  if (world != nullptr) {
    options.ports = arm_ports(*world, flags.binds);
  } else {
    // Only the arms' chains are read: the files the world names are checked
    // where they are loaded (`run`).
    options.ports = arm_ports(
        scenario_world(resolve_app(flags.inputs.front()), flags.world, /*check_files=*/false),
        flags.binds);
  }
  std::vector<std::string> inputs;
  for (const std::string& i : flags.inputs) inputs.push_back(resolve_app(i));
  app::LoadedModel model = app::load(inputs, flags.load.to_options());
  const size_t warnings = print_diagnostics(model.diagnostics());
  validation::ModelValidationOptions vopt;
  vopt.strict = flags.load.strict;
  vopt.vocabulary_shapes = !flags.load.listed_shapes_only;
  vopt.sparql_limits.seconds = flags.load.sparql_seconds;
  vopt.sparql_limits.steps = flags.load.sparql_steps;
  validation::ModelValidation v = validation::validate_model(model, vopt);
  print_diagnostics(v.shape_diagnostics);
  const size_t violations =
      v.report.count(shacl::Level::Violation) + v.report.count(shacl::Level::Other);
  const bool strict_fail =
      flags.load.strict && (warnings + v.strict_findings.size() + v.report.results.size() > 0);
  if (violations > 0 || strict_fail) {
    for (const Diagnostic& d : v.strict_findings) std::cerr << format(d) << '\n';
    std::cerr << shacl::to_text(v.report, &model.files(), &model.files());
    std::cerr << "mospec: the model does not validate; nothing was generated\n";
    exit_code = kExitFindings;
    return std::nullopt;
  }
  if (after_pass) {
    options.after_pass = [&](std::string_view pass, const ir::Program& p) {
      after_pass(pass, p, model.files());
    };
  }
  DiagnosticSink lower_warnings;
  options.warnings = &lower_warnings;
  try {
    ir::Program program = ir::lower(model, options);
    if (const size_t n = print_diagnostics(lower_warnings); n > 0 && flags.load.strict) {
      std::cerr << "mospec: " << n << " finding(s) under --strict; nothing was generated\n";
      exit_code = kExitFindings;
      return std::nullopt;
    }
    if (files) *files = model.files();
    exit_code = kExitOk;
    return program;
  } catch (const ir::LowerError& e) {
    // One located line per error, each starting with its file:line:col (an
    // editor's error parser reads it there; e.what() would put the first
    // behind "mospec: error: ").
    size_t errors = 0;  // the notes among them point at a second place of one
    for (const Diagnostic& d : e.diagnostics()) {
      std::cerr << format(d) << '\n';
      errors += d.severity == Severity::Error ? 1 : 0;
    }
    std::cerr << "mospec: the model cannot be lowered (" << errors
              << " error(s)); nothing was generated\n";
    exit_code = kExitFindings;
    return std::nullopt;
  } catch (const ir::VerifyError& e) {
    std::cerr << e.what() << '\n';
    std::cerr << "mospec: internal error: lowering made a program that does not verify (a bug in "
                 "mospec, not in the model; please report it with the model)\n";
    exit_code = kExitInternal;
    return std::nullopt;
  }
}

}  // namespace mospec::cli
