// `mospec ir`: the validated model lowered to the IR, as deterministic JSON.
#include <algorithm>
#include <iostream>
#include <optional>

#include "cli/pipeline.hpp"
#include "ir/lower.hpp"
#include "support/io.hpp"

namespace mospec::cli {

Action add_ir_command(CLI::App& app) {
  struct Flags {
    PipelineFlags pipeline;
    std::string output = "-";
    std::string dump_after;
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
  std::string passes;
  for (std::string_view p : ir::lowering_passes())
    passes.append(passes.empty() ? "" : ", ").append(p);
  cmd->add_option("--dump-after", flags->dump_after,
                  "Write the program as it is after this lowering pass instead of the finished "
                  "one (steps in declaration order until 'schedule'): " +
                      passes)
      ->type_name("PASS");
  return [flags]() {
    int code = kExitOk;
    SourceFiles files;
    if (!flags->dump_after.empty()) {
      const auto all = ir::lowering_passes();
      if (std::find(all.begin(), all.end(), flags->dump_after) == all.end()) {
        std::string names;
        for (std::string_view p : all) names.append(names.empty() ? "" : ", ").append(p);
        throw Error("usage", "--dump-after: no lowering pass '" + flags->dump_after +
                                 "'; the passes are " + names);
      }
    }
    std::optional<std::string> dumped;
    const AfterPass dump = [&](std::string_view pass, const ir::Program& p, const SourceFiles& f) {
      if (pass == flags->dump_after) dumped = ir::to_json(p, &f);
    };
    auto program = load_validate_lower(flags->pipeline, code, &files,
                                       flags->dump_after.empty() ? AfterPass{} : dump);
    if (dumped) {
      write_output(flags->output, *dumped);
      return program ? kExitOk : code;
    }
    if (!program) return code;
    write_output(flags->output, ir::to_json(*program, &files));
    return kExitOk;
  };
}

}  // namespace mospec::cli
