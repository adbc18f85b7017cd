// `mospec generate`: a validated, lowered app model -> the C++ project of its
// controller (src/codegen); `mospec build`: configure and build such a project
// against mospec's runtime package.
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <iostream>

#include "cli/pipeline.hpp"
#include "codegen/codegen.hpp"

extern char** environ;

namespace mospec::cli {

namespace fs = std::filesystem;

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

namespace {

// The runtime's CMake package: an installed one next to this executable
// (PREFIX/bin/mospec -> PREFIX/<libdir>/cmake/mospec) when present, else the
// build tree this binary was built in.
std::string package_dir() {
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    const fs::path installed = exe.parent_path().parent_path() / MOSPEC_INSTALL_CMAKEDIR;
    if (fs::exists(installed / "mospecConfig.cmake", ec)) return installed.string();
  }
  return MOSPEC_BUILD_PACKAGE_DIR;
}

// Runs argv (no shell: paths are passed as they are), collecting its standard
// output and error into `output`. Returns the exit status, or -1 when it could
// not be started or was killed.
int run(const std::vector<std::string>& args, std::string& output) {
  std::vector<char*> argv;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  std::array<int, 2> pipe_fd{};
  if (pipe(pipe_fd.data()) != 0) {
    output = "mospec: pipe: ";
    output.append(std::strerror(errno));
    return -1;
  }
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addclose(&actions, pipe_fd[0]);
  posix_spawn_file_actions_adddup2(&actions, pipe_fd[1], STDOUT_FILENO);
  posix_spawn_file_actions_adddup2(&actions, pipe_fd[1], STDERR_FILENO);
  posix_spawn_file_actions_addclose(&actions, pipe_fd[1]);
  pid_t pid = 0;
  const int spawned = posix_spawnp(&pid, argv[0], &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  close(pipe_fd[1]);
  if (spawned != 0) {
    close(pipe_fd[0]);
    output = "mospec: cannot run '";
    output.append(args[0]).append("': ").append(std::strerror(spawned));
    return -1;
  }
  std::array<char, 4096> buf{};
  for (;;) {
    const ssize_t n = read(pipe_fd[0], buf.data(), buf.size());
    if (n > 0) {
      output.append(buf.data(), static_cast<std::size_t>(n));
    } else if (n == 0 || errno != EINTR) {
      break;
    }
  }
  close(pipe_fd[0]);
  int status = 0;
  while (waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) return -1;
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

}  // namespace

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
    std::error_code ec;
    const fs::path dir = fs::absolute(flags->dir, ec);
    if (ec || !fs::exists(dir / "CMakeLists.txt", ec)) {
      std::string msg = "mospec: '";
      msg.append(flags->dir).append("' holds no generated project (no CMakeLists.txt)");
      throw Error("usage", msg);
    }
    const std::string package = flags->package.empty() ? package_dir() : flags->package;
    const fs::path build = dir / "build";
    std::string cmake = MOSPEC_CMAKE_COMMAND;
    if (!fs::exists(cmake, ec)) cmake = "cmake";
    std::string out;
    // The compiler mospec was built with: the library is loaded into mospec's processes.
    int status = run({cmake, "-S", dir.string(), "-B", build.string(), "-DCMAKE_BUILD_TYPE=Release",
                      "-Dmospec_DIR=" + package, "-DCMAKE_CXX_COMPILER=" MOSPEC_CXX_COMPILER},
                     out);
    if (status == 0) {
      out.clear();
      status = run({cmake, "--build", build.string(), "--parallel", std::to_string(flags->jobs)}, out);
    }
    if (status != 0) {
      std::cerr << out;
      std::string msg = "mospec: building '";
      msg.append(dir.string()).append("' failed");
      std::cerr << msg << '\n';
      return kExitBadInput;
    }
    const fs::path library = build / "libmospec_controller.so";
    if (!fs::exists(library, ec)) {
      std::cerr << "mospec: the build left no " << library.string() << '\n';
      return kExitBadInput;
    }
    std::cout << library.string() << '\n';
    return kExitOk;
  };
}

}  // namespace mospec::cli
