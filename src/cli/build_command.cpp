// `mospec build`: configure and build a project `mospec generate` wrote against
// mospec's runtime package (runs in mospec-full: it hashes with libcrypto).
#include <iostream>

#include "cli/commands.hpp"
#include "codegen/build.hpp"

namespace mospec::cli {

Action add_build_command(CLI::App& app) {
  struct Flags {
    std::string dir;
    int jobs = 2;
    std::string package;
  };
  auto flags = std::make_shared<Flags>();
  CLI::App* cmd = app.add_subcommand("build", kBuildSummary);
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
