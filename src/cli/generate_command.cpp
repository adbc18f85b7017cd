// `mospec generate`: a validated, lowered app model -> the C++ project of its
// controller (src/codegen); `mospec build`: configure and build such a project
// against mospec's runtime package.
#include <iostream>

#include "cli/pipeline.hpp"
#include "codegen/build.hpp"
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

Action add_build_command(CLI::App& app) {
  struct Flags {
    std::string dir;
    int jobs = 2;
    std::string package;
  };
  auto flags = std::make_shared<Flags>();
  CLI::App* cmd = app.add_subcommand(
      "build",
      "Configure and build a project `mospec generate` wrote (in DIR/build, Release, with "
      "-Werror) against mospec's runtime package, and print the path of the built controller "
      "library. Exit 2 with the compiler's output when it fails.");
  cmd->add_option("dir", flags->dir, "The generated project")->required()->type_name("DIR");
  cmd->add_option("-j,--jobs", flags->jobs, "Parallel compile jobs")
      ->check(CLI::Range(1, 256))
      ->capture_default_str();
  cmd->add_option("--mospec-dir", flags->package,
                  "mospec's CMake package directory (default: the installed one next to this "
                  "executable, else the build tree it was built in)")
      ->type_name("DIR");
  return [flags]() {
    const codegen::BuildResult r = codegen::build_project(flags->dir, flags->jobs, flags->package);
    if (!r.ok) {
      std::cerr << r.output;
      std::string msg = "mospec: building '";
      msg.append(flags->dir).append("' failed");
      std::cerr << msg << '\n';
      return kExitBadInput;
    }
    std::cout << r.library << '\n';
    return kExitOk;
  };
}

}  // namespace mospec::cli
