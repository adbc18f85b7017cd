// `mospec ir`: the validated model lowered to the IR, as deterministic JSON.
#include <iostream>

#include "cli/pipeline.hpp"
#include "support/io.hpp"

namespace mospec::cli {

Action add_ir_command(CLI::App& app) {
  struct Flags {
    PipelineFlags pipeline;
    std::string output = "-";
  };
  auto flags = std::make_shared<Flags>();
  CLI::App* cmd = app.add_subcommand(
      "ir",
      "Validate an app model and lower it to mospec's IR: every quantity with its frames and "
      "unit, every step the control tick runs in schedule order, the solvers. Written as "
      "deterministic JSON. Exit 1 when the model does not validate or lower (each problem "
      "located), 2 on bad input.");
  flags->pipeline.add_to(*cmd);
  cmd->add_option("-o,--output", flags->output, "Output file ('-' = standard output)")
      ->type_name("FILE");
  return [flags]() {
    int code = kExitOk;
    SourceFiles files;
    auto program = load_validate_lower(flags->pipeline, code, &files);
    if (!program) return code;
    write_output(flags->output, ir::to_json(*program, &files));
    return kExitOk;
  };
}

}  // namespace mospec::cli
