// The front half every code-producing command shares: load the app, validate
// it (the verdict gates everything after it), lower it to the IR.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "cli/commands.hpp"
#include "ir/ir.hpp"
#include "ir/lower.hpp"

namespace mospec::cli {

struct PipelineFlags {
  std::vector<std::string> inputs;
  std::vector<std::string> binds;  // CHAIN=right|left
  LoadFlags load;
  void add_to(CLI::App& cmd);
};

// An app named without its extension (`models/sc1`, as scenarios are named)
// is the JSON file next to it (`models/sc1.json`); other paths are unchanged.
std::string resolve_app(const std::string& path);

// Loads, validates and lowers. On failure prints every finding (located) to
// stderr and returns the exit code in `exit_code`: 1 when the model does not
// validate or lower, 2 on bad input. `files` receives the source files (for
// locations in the IR's JSON) when non-null.
// `after_pass`, when given, is called after each lowering pass with the
// program so far and the model's files (mospec ir --dump-after).
using AfterPass =
    std::function<void(std::string_view pass, const ir::Program&, const SourceFiles&)>;
std::optional<ir::Program> load_validate_lower(const PipelineFlags& flags, int& exit_code,
                                               SourceFiles* files = nullptr,
                                               const AfterPass& after_pass = {});

}  // namespace mospec::cli
