// `mospec generate`: a validated, lowered app model -> the C++ project of its
// controller (src/codegen).
#include "cli/pipeline.hpp"
#include "codegen/codegen.hpp"

namespace mospec::cli {

Action add_generate_command(CLI::App& app) {
  struct Flags {
    PipelineFlags pipeline;
    std::string output;
  };
  auto flags = std::make_shared<Flags>();
  CLI::App* cmd = app.add_subcommand(
      "generate",
      "Validate an app model, lower it to the IR and generate its controller: a C++20 CMake "
      "project (CMakeLists.txt, controller.hpp, controller.cpp) whose shared library implements "
      "mospec's Controller interface; build it with `mospec build DIR`. The same model always "
      "gives byte-identical files. Exit 1 when the model does not validate or lower (each "
      "problem located; nothing is written), 2 on bad input.");
  flags->pipeline.add_to(*cmd);
  cmd->add_option("-o,--output", flags->output, "Directory of the generated project (created)")
      ->required()
      ->type_name("DIR");
  return [flags]() {
    int code = kExitOk;
    SourceFiles files;
    auto program = load_validate_lower(flags->pipeline, code, &files);
    if (!program) return code;
    ir::verify(*program);
    codegen::generate(*program, flags->output, &files);
    return kExitOk;
  };
}

}  // namespace mospec::cli
