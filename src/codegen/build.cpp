#include "codegen/build.hpp"

#include <dlfcn.h>
#include <fcntl.h>
#include <spawn.h>
#include <sys/file.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <vector>

#include "codegen/codegen.hpp"
#include "ir/lower.hpp"
#include "support/diagnostics.hpp"

extern char** environ;

namespace mospec::codegen {

namespace fs = std::filesystem;

std::string default_package_dir() {
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    const fs::path installed = exe.parent_path().parent_path() / MOSPEC_INSTALL_CMAKEDIR;
    if (fs::exists(installed / "mospecConfig.cmake", ec)) return installed.string();
  }
  return MOSPEC_BUILD_PACKAGE_DIR;
}

namespace {

// Runs argv (no shell), collecting its standard output and error into
// `output`. Returns the exit status, or -1 when it could not be started or
// did not exit normally.
int run(const std::vector<std::string>& args, std::string& output) {
  std::vector<char*> argv;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  std::array<int, 2> fd{};
  if (pipe(fd.data()) != 0) {
    output.append("mospec: pipe: ").append(std::strerror(errno)).append("\n");
    return -1;
  }
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addclose(&actions, fd[0]);
  posix_spawn_file_actions_adddup2(&actions, fd[1], STDOUT_FILENO);
  posix_spawn_file_actions_adddup2(&actions, fd[1], STDERR_FILENO);
  posix_spawn_file_actions_addclose(&actions, fd[1]);
  pid_t pid = 0;
  const int spawned = posix_spawnp(&pid, argv[0], &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  close(fd[1]);
  if (spawned != 0) {
    close(fd[0]);
    output.append("mospec: cannot run '")
        .append(args[0])
        .append("': ")
        .append(std::strerror(spawned));
    output.append("\n");
    return -1;
  }
  std::array<char, 4096> buf{};
  for (;;) {
    const ssize_t n = read(fd[0], buf.data(), buf.size());
    if (n > 0) {
      output.append(buf.data(), static_cast<std::size_t>(n));
    } else if (n == 0 || errno != EINTR) {
      break;
    }
  }
  close(fd[0]);
  int status = 0;
  while (waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) return -1;
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// A loaded library's controller; destroys it before unloading its code.
class LibraryController final : public robot::Controller {
 public:
  LibraryController(void* handle, robot::Controller* inner) : handle_(handle), inner_(inner) {}
  LibraryController(const LibraryController&) = delete;
  LibraryController& operator=(const LibraryController&) = delete;
  ~LibraryController() override {
    delete inner_;
    dlclose(handle_);
  }
  int abi_version() const noexcept override { return inner_->abi_version(); }
  const char* app() const noexcept override { return inner_->app(); }
  void tick(const robot::MeasuredState& state, robot::Command& command) noexcept override {
    inner_->tick(state, command);
  }
  std::span<const robot::LogColumnInfo> log_columns() const noexcept override {
    return inner_->log_columns();
  }
  void log_values(std::span<double> out) const noexcept override { inner_->log_values(out); }

 private:
  void* handle_;
  robot::Controller* inner_;
};

// An exclusive lock on a file (flock), held for the object's lifetime: runs
// started in parallel (e.g. seeded trials) build a cached controller once.
class FileLock {
 public:
  explicit FileLock(const std::string& path)
      : fd_(open(path.c_str(), O_CREAT | O_RDWR | O_CLOEXEC, 0644)) {
    if (fd_ < 0) {
      std::string msg = "cannot open lock file '";
      msg.append(path).append("': ").append(std::strerror(errno));
      throw Error("io", msg);
    }
    while (flock(fd_, LOCK_EX) != 0 && errno == EINTR) {
    }
  }
  FileLock(const FileLock&) = delete;
  FileLock& operator=(const FileLock&) = delete;
  ~FileLock() {
    flock(fd_, LOCK_UN);
    close(fd_);
  }

 private:
  int fd_;
};

[[noreturn]] void load_error(const std::string& library, const std::string& why) {
  std::string msg = "cannot load controller '";
  msg.append(library).append("': ").append(why);
  throw Error("load", msg);
}

}  // namespace

BuildResult build_project(const std::string& dir_arg, int jobs, const std::string& package_arg) {
  std::error_code ec;
  const fs::path dir = fs::absolute(dir_arg, ec);
  if (ec || !fs::exists(dir / "CMakeLists.txt", ec)) {
    std::string msg = "'";
    msg.append(dir_arg).append("' holds no generated project (no CMakeLists.txt)");
    throw Error("usage", msg);
  }
  const std::string package = package_arg.empty() ? default_package_dir() : package_arg;
  const fs::path build = dir / "build";
  std::string cmake = MOSPEC_CMAKE_COMMAND;
  if (!fs::exists(cmake, ec)) cmake = "cmake";
  BuildResult r;
  // The compiler mospec was built with: the library is loaded into mospec's processes.
  int status = run({cmake, "-S", dir.string(), "-B", build.string(), "-DCMAKE_BUILD_TYPE=Release",
                    "-Dmospec_DIR=" + package, "-DCMAKE_CXX_COMPILER=" MOSPEC_CXX_COMPILER},
                   r.output);
  if (status == 0) {
    r.output.clear();
    status = run({cmake, "--build", build.string(), "--parallel", std::to_string(jobs)}, r.output);
  }
  const fs::path library = build / "libmospec_controller.so";
  if (status == 0 && !fs::exists(library, ec)) {
    r.output.append("mospec: the build left no ").append(library.string()).append("\n");
    status = -1;
  }
  r.ok = status == 0;
  if (r.ok) r.library = library.string();
  return r;
}

CachedController cached_controller(const ir::Program& program, const std::string& cache_dir,
                                   const SourceFiles* files, int jobs) {
  const std::vector<GeneratedFile> rendered = render(program, files);
  const std::string package = default_package_dir();
  std::string key_text = package;
  for (const GeneratedFile& f : rendered)
    key_text.append("\n").append(f.path).append("\n").append(f.content);
  const fs::path dir = fs::path(cache_dir) / ir::content_hash(key_text);
  const fs::path library = dir / "build" / "libmospec_controller.so";
  std::error_code ec;
  fs::create_directories(cache_dir, ec);
  if (ec) {
    std::string msg = "cannot create directory '";
    msg.append(cache_dir).append("': ").append(ec.message());
    throw Error("io", msg);
  }
  const FileLock lock(dir.string() + ".lock");
  CachedController c;
  c.project = dir.string();
  std::string output;
  int status = 0;
  if (fs::exists(library, ec)) {
    std::string cmake = MOSPEC_CMAKE_COMMAND;
    if (!fs::exists(cmake, ec)) cmake = "cmake";
    status = run({cmake, "--build", (dir / "build").string(), "--parallel", std::to_string(jobs)},
                 output);
  } else {
    generate(program, dir.string(), files);
    const BuildResult r = build_project(dir.string(), jobs, package);
    status = r.ok ? 0 : 1;
    output = r.output;
    c.built = true;
  }
  if (status != 0) {
    std::string msg = "building the generated controller in '";
    msg.append(dir.string()).append("' failed:\n").append(output);
    throw Error("build", msg);
  }
  c.library = library.string();
  return c;
}

std::unique_ptr<robot::Controller> load_controller(const std::string& library) {
  void* handle = dlopen(library.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (handle == nullptr) {
    const char* why = dlerror();
    load_error(library, why != nullptr ? why : "dlopen failed");
  }
  void* symbol = dlsym(handle, robot::kControllerFactorySymbol);
  if (symbol == nullptr) {
    dlclose(handle);
    load_error(library, "it exports no mospec_create_controller()");
  }
  robot::Controller* inner = reinterpret_cast<robot::ControllerFactory>(symbol)();
  if (inner == nullptr) {
    dlclose(handle);
    load_error(library, "mospec_create_controller() returned no controller");
  }
  if (inner->abi_version() != robot::kControllerAbiVersion) {
    const int got = inner->abi_version();
    delete inner;
    dlclose(handle);
    std::string why = "built against controller ABI ";
    why.append(std::to_string(got)).append(", this mospec has ");
    why.append(std::to_string(robot::kControllerAbiVersion)).append("; regenerate and rebuild it");
    load_error(library, why);
  }
  return std::make_unique<LibraryController>(handle, inner);
}

}  // namespace mospec::codegen
