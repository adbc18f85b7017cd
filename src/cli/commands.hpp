// mospec's subcommands. Each registers its options on the CLI11 app and returns
// the action to run after parsing; the action returns the process exit code:
// 0 all is well, 1 the models have findings (under --strict) or fail
// verification, 2 bad input, usage or environment errors, 3 an internal error
// (a bug in mospec, whatever the input).
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <string>
#include <vector>

#include "app/app.hpp"

namespace mospec::cli {

inline constexpr int kExitOk = 0;
inline constexpr int kExitFindings = 1;
inline constexpr int kExitBadInput = 2;
inline constexpr int kExitInternal = 3;

using Action = std::function<int()>;

// Runs a command's action and returns its exit code; what it throws becomes
// one line on stderr and the exit code: mospec::Error (bad input) 2, out of
// memory 2, anything else 3, an internal error.
int run_guarded(const Action& action);

// Options every command that loads models shares.
struct LoadFlags {
  std::vector<std::string> maps;  // IRI=DIR
  std::string root;
  bool strict = false;
  bool listed_shapes_only = false;  // no shapes for the vocabulary, only the listed ones
  // The SPARQL budget of the command's validation (sparql::Limits).
  double sparql_seconds = 60;
  uint64_t sparql_steps = uint64_t{1} << 32;
  // --map, --root, and the flags that act on what the command does with the
  // model: --strict (`strict`: it reports the loader's warnings) and
  // --listed-shapes-only (`validates`: it runs SHACL). A command lists only
  // flags that act.
  void add_to(CLI::App& cmd, bool strict = true, bool validates = true);
  void add_budget_to(CLI::App& cmd);    // --sparql-seconds, --sparql-steps (commands that validate)
  app::LoadOptions to_options() const;  // throws mospec::Error on a malformed --map
};

// Prints diagnostics to stderr; returns how many are warnings or errors (the
// notes among them explain those, or say what was done).
size_t print_diagnostics(const DiagnosticSink& sink);

// Throws a usage error naming the app beside it when `path` is a world file
// (NAME.world.json) given where a model goes (pipeline.cpp).
void refuse_world_file_as_model(const std::string& path);

// The commands that run in mospec-full, the build of this CLI that links the
// simulator (MuJoCo), the URDF reader and libcrypto: the `mospec` users call
// lists them under these summaries and execs mospec-full, installed beside
// it, for them (main.cpp), so the model-side commands never load those
// libraries.
inline constexpr const char* kSimSummary =
    "Run the simulated robot (two Gen3 arms on a KELO base, in front of a table) headless with "
    "a zero-torque or gravity-compensation controller, and write a CSV log. The world is "
    "generated from the robot description; WORLD is a JSON file of initial conditions (see "
    "docs/simulation.md), the default world if omitted.";
inline constexpr const char* kRunSummary =
    "Validate an app model, lower it and run its controller against the simulated robot; "
    "write a CSV log (every constraint's value, error and satisfaction, every monitor, motion "
    "and controller output, and the world's ground truth) and a JSON summary. The world is "
    "--world, else APP's sibling <name>.world.json, else the default world; the run names it "
    "first.";
inline constexpr const char* kImportUrdfSummary =
    "Convert the serial chain of a URDF (root link to tip link; fixed joints folded into "
    "the previous segment) into a kinematic-chain JSON-LD model with units, keeping the "
    "joints' position, velocity and effort limits (the published kc-ext:JointLimit)";
inline constexpr const char* kBuildSummary =
    "Configure and build a project `mospec generate` wrote (in DIR/build, Release, with "
    "-Werror) against mospec's runtime package, and print the path of the built controller "
    "library. Exit 2 with the compiler's output when it fails.";

Action add_rdf_command(CLI::App& app);
Action add_validate_command(CLI::App& app);
Action add_stats_command(CLI::App& app);
Action add_sim_command(CLI::App& app);
Action add_import_urdf_command(CLI::App& app);
Action add_generate_command(CLI::App& app);
Action add_build_command(CLI::App& app);
Action add_ir_command(CLI::App& app);
Action add_run_command(CLI::App& app);
Action add_plot_command(CLI::App& app);
Action add_trials_command(CLI::App& app);
Action add_new_command(CLI::App& app);
Action add_report_command(CLI::App& app);
Action add_explain_command(CLI::App& app);

}  // namespace mospec::cli
