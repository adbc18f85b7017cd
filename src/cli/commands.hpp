// mospec's subcommands. Each registers its options on the CLI11 app and returns
// the action to run after parsing; the action returns the process exit code:
// 0 all is well, 1 the models have findings (under --strict) or fail
// verification, 2 bad input, usage or environment errors.
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

using Action = std::function<int()>;

// Options every command that loads models shares.
struct LoadFlags {
  std::vector<std::string> maps;  // IRI=DIR
  std::string root;
  bool strict = false;
  void add_to(CLI::App& cmd);
  app::LoadOptions to_options() const;  // throws mospec::Error on a malformed --map
};

// Prints the loader's warnings to stderr; returns how many there were.
size_t print_diagnostics(const DiagnosticSink& sink);

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

}  // namespace mospec::cli
