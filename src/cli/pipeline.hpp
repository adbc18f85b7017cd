// The front half every code-producing command shares: load the app, validate
// it (the verdict gates everything after it), lower it to the IR.
#pragma once

#include <functional>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "cli/commands.hpp"
#include "ir/ir.hpp"
#include "ir/lower.hpp"
#include "sim/config.hpp"

namespace mospec::cli {

struct PipelineFlags {
  std::vector<std::string> inputs;
  std::vector<std::string> binds;  // CHAIN=ARM
  std::string world;               // --world FILE
  LoadFlags load;
  void add_to(CLI::App& cmd);
};

// An app named without its extension (`models/sc1`, as scenarios are named)
// is the JSON file next to it (`models/sc1.json`); other paths are unchanged.
std::string resolve_app(const std::string& path);

// APP's sibling "<name>.world.json" (empty when APP is not a .json file).
std::string default_world_file_name(const std::string& app);
// The world file a scenario runs in: `world_file`, else APP's sibling when it
// exists; empty: the default world.
std::string scenario_world_file(const std::string& app, const std::string& world_file);

// The scenario's world: `world_file`, else APP's sibling "<name>.world.json",
// else the default world (mospec's robot: two Gen3 arms on the KELO base).
// `check_files`: as sim::load_world_config.
sim::WorldConfig scenario_world(const std::string& app, const std::string& world_file,
                                bool check_files = true);

// Which arm each kinematic chain drives (ir::LowerOptions::ports): the world's
// arms' chains, then each --bind CHAIN=ARM (ARM a name or an index).
std::map<std::string, int> arm_ports(const sim::WorldConfig& world,
                                     const std::vector<std::string>& binds);

// Loads, validates and lowers (chains bound to the arms of the scenario's world). On failure prints
// every finding (located) to stderr and returns the exit code in `exit_code`: 1 when the model does
// not validate or lower, 2 on bad input. `files` receives the source files (for locations in the
// IR's JSON) when non-null. `after_pass`, when given, is called after each lowering pass with the
// program so far and the model's files (mospec ir --dump-after). `world`: the scenario's world when
// the caller has read it (`run`, which simulates it: the arms the program is bound to are then
// those of the very file it runs); otherwise it is read here for its arms.
using AfterPass =
    std::function<void(std::string_view pass, const ir::Program&, const SourceFiles&)>;
std::optional<ir::Program> load_validate_lower(const PipelineFlags& flags, int& exit_code,
                                               SourceFiles* files = nullptr,
                                               const AfterPass& after_pass = {},
                                               const sim::WorldConfig* world = nullptr);

}  // namespace mospec::cli
