// mospec: composable JSON-LD task models -> verified controllers.
//
// Built twice (src/cli/CMakeLists.txt). mospec-full registers every command.
// mospec, the executable users call (MOSPEC_FRONT_DOOR), runs the model-side
// commands itself and execs mospec-full, installed beside it, for the ones that
// need the simulator, the URDF reader or the build cache's hashing (sim, run,
// import-urdf, build) and for --help-all: validating a model then never pays
// for mapping and relocating MuJoCo and the libraries it pulls in.
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <string_view>

#include "cli/commands.hpp"
#include "support/diagnostics.hpp"
#include "support/paths.hpp"
#include "support/spelling.hpp"

namespace mospec::cli {

void LoadFlags::add_to(CLI::App& cmd, bool with_strict, bool validates) {
  cmd.add_option("--map", maps,
                 "Map an IRI prefix to a local directory (IRI=DIR); repeatable. Nothing is "
                 "ever fetched from the network.")
      ->type_name("IRI=DIR");
  cmd.add_option("--root", root,
                 "Resolve the app model's iri-map paths against DIR instead of the current "
                 "directory")
      ->type_name("DIR");
  if (with_strict) {
    cmd.add_flag("--strict", strict, "Treat warnings (dropped keys, undefined types) as findings");
  }
  if (validates) {
    cmd.add_flag("--listed-shapes-only", listed_shapes_only,
                 "Apply only the shape files the app lists (and --shapes), not mospec's shapes "
                 "for every term of mospec's vocabulary the model uses; to test shapes, or what "
                 "lowering refuses by itself, in isolation");
  }
}

void LoadFlags::add_budget_to(CLI::App& cmd) {
  cmd.add_option("--sparql-seconds", sparql_seconds,
                 "Wall-clock budget of all SPARQL work of this command (every SHACL-SPARQL "
                 "constraint and sh:path, for every shape and focus node, together); past it "
                 "validation stops with a sparql-limit error. 0: none")
      ->type_name("S")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  cmd.add_option("--sparql-steps", sparql_steps,
                 "Step budget of all SPARQL work of this command, together (a step is a "
                 "matched triple, a node reached by a path, a solution, or 64 bytes a string "
                 "function or REGEX reads). 0: none")
      ->type_name("N")
      ->capture_default_str();
}

app::LoadOptions LoadFlags::to_options() const {
  app::LoadOptions o;
  for (const std::string& m : maps) {
    auto eq = m.find('=');
    if (eq == std::string::npos || eq == 0 || eq + 1 == m.size()) {
      throw Error("usage", "--map expects IRI=DIR, got '" + m + "'");
    }
    o.maps.emplace_back(m.substr(0, eq), m.substr(eq + 1));
  }
  if (!root.empty()) o.root = root;
  // One load per process: a second thread does not pay for itself here. On
  // this project's 2-vCPU machines it starts 2.6-4 ms late in about a third
  // of fresh processes (the whole load takes about 3 ms) and its own heap
  // costs some 100 page faults; `mospec validate` of the authors' sc1 took
  // 8.25 ms with it against 8.08 ms without (medians of 150, docs/ir.md).
  o.threads = 1;
  return o;
}

size_t print_diagnostics(const DiagnosticSink& sink) {
  size_t findings = 0;  // a note says what was done, not what is wrong
  for (const Diagnostic& d : sink.diagnostics()) {
    std::cerr << format(d) << '\n';
    if (d.severity != Severity::Note) ++findings;
  }
  return findings;
}

#if MOSPEC_FRONT_DOOR
namespace {

constexpr std::array<std::string_view, 4> kForwarded{"sim", "run", "import-urdf", "build"};

// Whether mospec-full must run this command line: its subcommand (the first
// argument that is not an option) is one of kForwarded, or there is none and
// --help-all asks for every command's options.
bool forwarded(int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    const std::string_view arg = argv[i];
    if (arg == "--help-all") return true;
    if (arg.starts_with("-")) continue;
    for (std::string_view name : kForwarded)
      if (arg == name) return true;
    return false;
  }
  return false;
}

// Replaces this process by mospec-full with the same arguments; returns only
// when that fails.
int exec_full(char** argv) {
  std::error_code ec;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", ec);
  const std::string full = (self.parent_path() / "mospec-full").string();
  if (!ec) ::execv(full.c_str(), argv);
  std::cerr << "mospec: cannot run " << (ec ? std::string("mospec-full") : full) << ": "
            << std::strerror(ec ? ec.value() : errno)
            << " (the simulator commands and `build` run in mospec-full, which is built and "
               "installed beside mospec)\n";
  return kExitBadInput;
}

}  // namespace
#endif

}  // namespace mospec::cli

int main(int argc, char** argv) {
  using namespace mospec::cli;
#if MOSPEC_FRONT_DOOR
  if (forwarded(argc, argv)) return exec_full(argv);
#endif
  CLI::App app{
      "mospec: composable JSON-LD models of contact-rich robot tasks -> verified, "
      "generated controllers"};
  app.name("mospec");
  app.require_subcommand(1);
  app.set_version_flag("--version", "mospec " MOSPEC_VERSION);
  app.set_help_all_flag("--help-all", "Help for every command");
  std::vector<std::pair<CLI::App*, Action>> commands;
  Action rdf = add_rdf_command(app);
  commands.emplace_back(app.get_subcommand("rdf"), rdf);
  Action validate = add_validate_command(app);
  commands.emplace_back(app.get_subcommand("validate"), validate);
  Action stats = add_stats_command(app);
  commands.emplace_back(app.get_subcommand("stats"), stats);
#if MOSPEC_FRONT_DOOR
  app.add_subcommand("sim", kSimSummary);  // listed in --help; runs in mospec-full
  app.add_subcommand("import-urdf", kImportUrdfSummary);
#else
  Action sim = add_sim_command(app);
  commands.emplace_back(app.get_subcommand("sim"), sim);
  Action import_urdf = add_import_urdf_command(app);
  commands.emplace_back(app.get_subcommand("import-urdf"), import_urdf);
#endif
  Action generate = add_generate_command(app);
  commands.emplace_back(app.get_subcommand("generate"), generate);
#if MOSPEC_FRONT_DOOR
  app.add_subcommand("build", kBuildSummary);  // listed in --help; runs in mospec-full
#else
  Action build = add_build_command(app);
  commands.emplace_back(app.get_subcommand("build"), build);
#endif
  Action ir = add_ir_command(app);
  commands.emplace_back(app.get_subcommand("ir"), ir);
#if MOSPEC_FRONT_DOOR
  app.add_subcommand("run", kRunSummary);  // listed in --help; runs in mospec-full
#else
  Action run = add_run_command(app);
  commands.emplace_back(app.get_subcommand("run"), run);
#endif
  Action plot = add_plot_command(app);
  commands.emplace_back(app.get_subcommand("plot"), plot);
  Action trials = add_trials_command(app);
  commands.emplace_back(app.get_subcommand("trials"), trials);
  Action new_task = add_new_command(app);
  commands.emplace_back(app.get_subcommand("new"), new_task);
  Action report = add_report_command(app);
  commands.emplace_back(app.get_subcommand("report"), report);
  Action explain = add_explain_command(app);
  commands.emplace_back(app.get_subcommand("explain"), explain);

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    // A first word that is no command (`mospec valdate`): CLI11 would say only
    // that a command is required.
    const CLI::App& commands_app = app;
    const std::vector<const CLI::App*> known =
        commands_app.get_subcommands([](const CLI::App*) { return true; });
    const auto is_command = [&](std::string_view word) {
      return std::any_of(known.begin(), known.end(),
                         [&](const CLI::App* c) { return c->get_name() == word; });
    };
    if (argc > 1 && argv[1][0] != '-' && !is_command(argv[1])) {
      mospec::Nearest nearest(argv[1]);
      for (const CLI::App* c : known) nearest.offer(c->get_name());
      std::cerr << "mospec: error: no command '" << mospec::escaped_bytes(argv[1]) << "'"
                << (nearest.best().empty()
                        ? std::string()
                        : "; did you mean '" + std::string(nearest.best()) + "'?")
                << " (run 'mospec --help' for the commands)\n";
      return kExitBadInput;
    }
    std::cerr << "mospec: " << e.what() << "\n(run 'mospec --help' for usage)\n";
    return kExitBadInput;
  }
  for (auto& [cmd, action] : commands) {
    if (cmd->parsed()) return run_guarded(action);
  }
  return kExitBadInput;
}
