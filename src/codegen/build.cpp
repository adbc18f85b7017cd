#include "codegen/build.hpp"

#include <dlfcn.h>
#include <fcntl.h>
#include <link.h>
#include <openssl/evp.h>
#include <spawn.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <memory>
#include <vector>

#include "codegen/codegen.hpp"
#include "ir/lower.hpp"
#include "support/diagnostics.hpp"
#include "support/io.hpp"

extern char** environ;

namespace mospec::codegen {

namespace fs = std::filesystem;

// SHA-256 of the runtime's libraries and headers as this build made them
// (runtime_id.cpp, written by runtime_id.cmake when any of them changes).
const char* runtime_content_id();

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
  std::span<const int> arm_joints() const noexcept override { return inner_->arm_joints(); }

 private:
  void* handle_;
  robot::Controller* inner_;
};

// An exclusive lock on a file (flock), held for the object's lifetime: runs
// started in parallel (e.g. seeded trials) build a cached controller once.
class FileLock {
 public:
  explicit FileLock(const std::string& path)
      : fd_(open(path.c_str(), O_CREAT | O_RDWR | O_CLOEXEC | O_NOFOLLOW, 0600)) {
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

// An open file descriptor, closed with its owner.
class Fd {
 public:
  explicit Fd(int fd) : fd_(fd) {}
  Fd(const Fd&) = delete;
  Fd& operator=(const Fd&) = delete;
  ~Fd() {
    if (fd_ >= 0) close(fd_);
  }
  int get() const { return fd_; }

 private:
  int fd_;
};

class Sha256 {
 public:
  Sha256() : ctx_(EVP_MD_CTX_new()) {
    if (ctx_ == nullptr || EVP_DigestInit_ex(ctx_.get(), EVP_sha256(), nullptr) != 1)
      throw Error("internal", "OpenSSL cannot compute SHA-256");
  }
  void add(std::string_view bytes) {
    if (EVP_DigestUpdate(ctx_.get(), bytes.data(), bytes.size()) != 1)
      throw Error("internal", "OpenSSL cannot compute SHA-256");
  }
  // A field of a composite key: its length, then its bytes.
  void field(std::string_view bytes) {
    add(std::to_string(bytes.size()));
    add(":");
    add(bytes);
  }
  std::string hex() {
    std::array<unsigned char, EVP_MAX_MD_SIZE> md{};
    unsigned int n = 0;
    if (EVP_DigestFinal_ex(ctx_.get(), md.data(), &n) != 1)
      throw Error("internal", "OpenSSL cannot compute SHA-256");
    static constexpr char kDigits[] = "0123456789abcdef";
    std::string out;
    for (unsigned int i = 0; i < n; ++i) {
      out.push_back(kDigits[md[i] >> 4]);
      out.push_back(kDigits[md[i] & 0xF]);
    }
    return out;
  }

 private:
  struct Free {
    void operator()(EVP_MD_CTX* c) const { EVP_MD_CTX_free(c); }
  };
  std::unique_ptr<EVP_MD_CTX, Free> ctx_;
};

std::string cmake_command() {
  std::error_code ec;
  const std::string cmake = MOSPEC_CMAKE_COMMAND;
  return fs::exists(cmake, ec) ? cmake : std::string("cmake");
}

constexpr const char* kLibraryName = "libmospec_controller.so";
constexpr const char* kManifestName = "manifest";
constexpr const char* kManifestHeader = "mospec controller cache 1";

// The library's SHA-256 from an entry's manifest ("" when there is none or it
// is not ours).
std::string manifest_sha256(const fs::path& entry, const std::string& key) {
  std::string text;
  try {
    text = read_file((entry / kManifestName).string());
  } catch (const Error&) {
    return {};
  }
  std::string want = kManifestHeader;
  want.append("\nkey ").append(key).append("\nlibrary build/").append(kLibraryName);
  want.append("\nsha256 ");
  if (text.size() != want.size() + 65 || text.compare(0, want.size(), want) != 0 ||
      text.back() != '\n')
    return {};
  return text.substr(want.size(), 64);
}

// The SHA-256 of a library file opened without following a symlink ("" when
// it cannot be opened or is not a regular file).
std::string library_sha256(const fs::path& library) {
  const Fd fd(open(library.c_str(), O_RDONLY | O_NOFOLLOW | O_CLOEXEC));
  struct stat st {};
  if (fd.get() < 0 || fstat(fd.get(), &st) != 0 || !S_ISREG(st.st_mode)) return {};
  try {
    return sha256_hex_of_fd(fd.get(), library.string());
  } catch (const Error&) {
    return {};
  }
}

// Whether the dynamic loader holds an object loaded under `name`.
bool loaded_under(const std::string& name) {
  struct Search {
    const std::string* name;
    bool found;
  } search{&name, false};
  dl_iterate_phdr(
      [](dl_phdr_info* info, std::size_t, void* data) {
        auto* s = static_cast<Search*>(data);
        if (info->dlpi_name != nullptr && *s->name == info->dlpi_name) s->found = true;
        return 0;
      },
      &search);
  return search.found;
}

[[noreturn]] void unsafe_cache(const std::string& dir, const std::string& why,
                               const std::string& fix) {
  std::string msg = "refusing the controller cache directory '";
  msg.append(dir).append("': ").append(why).append("; ").append(fix);
  msg.append(" (or pass --cache DIR with a directory of your own)");
  throw Error("unsafe-cache", msg);
}

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
  check_cmake_path(dir.string(), "the generated project's directory");
  check_cmake_path(package, "mospec's CMake package directory");
  check_cmake_path(MOSPEC_CXX_COMPILER, "the C++ compiler");
  const std::string cmake = cmake_command();
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

std::string sha256_hex(std::string_view bytes) {
  Sha256 h;
  h.add(bytes);
  return h.hex();
}

std::string sha256_hex_of_fd(int fd, const std::string& name) {
  Sha256 h;
  std::array<char, 65536> buf{};
  for (;;) {
    const ssize_t n = read(fd, buf.data(), buf.size());
    if (n > 0) {
      h.add(std::string_view(buf.data(), static_cast<std::size_t>(n)));
    } else if (n == 0) {
      break;
    } else if (errno != EINTR) {
      std::string msg = "cannot read '";
      msg.append(name).append("': ").append(std::strerror(errno));
      throw Error("io", msg);
    }
  }
  return h.hex();
}

std::string default_cache_dir(const char* xdg_cache_home, const char* home) {
  // XDG Base Directory: "If an implementation encounters a relative path in
  // any of these variables it should consider the path invalid and ignore it."
  if (xdg_cache_home != nullptr && xdg_cache_home[0] == '/')
    return (fs::path(xdg_cache_home) / "mospec").string();
  if (home != nullptr && home[0] == '/') return (fs::path(home) / ".cache" / "mospec").string();
  throw Error("usage",
              "no cache directory for generated controllers: neither XDG_CACHE_HOME nor "
              "HOME is an absolute path; set one of them or pass --cache DIR (or run with "
              "--interpret)");
}

std::string default_cache_dir() {
  return default_cache_dir(std::getenv("XDG_CACHE_HOME"), std::getenv("HOME"));
}

void ensure_private_dir(const std::string& dir_arg) {
  std::error_code ec;
  const fs::path dir = fs::absolute(dir_arg, ec);
  if (ec) {
    std::string msg = "cannot resolve directory '";
    msg.append(dir_arg).append("': ").append(ec.message());
    throw Error("io", msg);
  }
  // Create what is missing, one component at a time, private from the start.
  fs::path at;
  for (const fs::path& part : dir) {
    at /= part;
    if (mkdir(at.c_str(), 0700) != 0 && errno != EEXIST) {
      std::string msg = "cannot create directory '";
      msg.append(at.string()).append("': ").append(std::strerror(errno));
      throw Error("io", msg);
    }
  }
  struct stat st {};
  if (lstat(dir.c_str(), &st) != 0) {
    std::string msg = "cannot inspect directory '";
    msg.append(dir.string()).append("': ").append(std::strerror(errno));
    throw Error("io", msg);
  }
  if (S_ISLNK(st.st_mode)) {
    unsafe_cache(dir.string(), "it is a symbolic link",
                 "replace it with a directory (mkdir -m 700)");
  }
  if (!S_ISDIR(st.st_mode)) {
    unsafe_cache(dir.string(), "it is not a directory", "remove it or choose another path");
  }
  if (st.st_uid != geteuid()) {
    unsafe_cache(dir.string(),
                 "it is owned by user id " + std::to_string(st.st_uid) + ", not by you (" +
                     std::to_string(geteuid()) + ")",
                 "remove it, or use a directory you own");
  }
  if ((st.st_mode & (S_IWGRP | S_IWOTH)) != 0) {
    unsafe_cache(dir.string(), "other users can write into it",
                 "make it private with `chmod go-w '" + dir.string() + "'` (or chmod 700)");
  }
}

BuildConfig current_build_config(const std::string& package_arg) {
  BuildConfig c;
  c.version = MOSPEC_VERSION;
  c.runtime_id = runtime_content_id();
  c.package = package_arg.empty() ? default_package_dir() : package_arg;
  // The package's own files (its targets carry the runtime's compile and link
  // options), by name and content.
  std::vector<fs::path> package_files;
  std::error_code ec;
  for (const fs::directory_entry& e : fs::directory_iterator(c.package, ec)) {
    if (e.is_regular_file(ec)) package_files.push_back(e.path());
  }
  std::sort(package_files.begin(), package_files.end());
  Sha256 package;
  for (const fs::path& f : package_files) {
    package.field(f.filename().string());
    std::string content;
    try {
      content = read_file(f.string());
    } catch (const Error&) {
      content = "<unreadable>";
    }
    package.field(content);
  }
  c.package_content = package.hex();
  c.compiler = MOSPEC_CXX_COMPILER;
  c.compiler_version = MOSPEC_CXX_COMPILER_ID " " MOSPEC_CXX_COMPILER_VERSION "\n";
  std::string output;
  const int status = run({c.compiler, "--version"}, output);
  c.compiler_version.append(status == 0 ? output : "<--version failed>");
  c.flags = {"-DCMAKE_BUILD_TYPE=Release", "-Dmospec_DIR=" + c.package,
             "-DCMAKE_CXX_COMPILER=" + c.compiler, "cmake=" + cmake_command()};
  // CMake takes the initial flags from the environment.
  for (const char* variable : {"CXXFLAGS", "CPPFLAGS", "LDFLAGS"}) {
    const char* v = std::getenv(variable);
    c.flags.push_back(std::string(variable) + "=" + (v != nullptr ? v : ""));
  }
  c.flags.push_back("Eigen " + std::to_string(EIGEN_WORLD_VERSION) + "." +
                    std::to_string(EIGEN_MAJOR_VERSION) + "." +
                    std::to_string(EIGEN_MINOR_VERSION));
  return c;
}

std::string cache_key(const std::vector<GeneratedFile>& files, const BuildConfig& config) {
  Sha256 h;
  h.field(kManifestHeader);
  h.field(config.version);
  h.field(config.runtime_id);
  h.field(config.package);
  h.field(config.package_content);
  h.field(config.compiler);
  h.field(config.compiler_version);
  h.field(std::to_string(config.flags.size()));
  for (const std::string& f : config.flags) h.field(f);
  h.field(std::to_string(files.size()));
  for (const GeneratedFile& f : files) {
    h.field(f.path);
    h.field(f.content);
  }
  return h.hex();
}

CachedController cached_controller(const ir::Program& program, const std::string& cache_dir,
                                   const SourceFiles* files, int jobs) {
  const std::vector<GeneratedFile> rendered = render(program, files);
  const BuildConfig config = current_build_config();
  const std::string key = cache_key(rendered, config);
  std::error_code ec;
  const fs::path root = fs::absolute(cache_dir, ec);
  check_cmake_path(root.string(), "the controller cache directory");
  ensure_private_dir(root.string());
  const fs::path entry = root / key;
  const fs::path library = entry / "build" / kLibraryName;
  const FileLock lock((root / (key + ".lock")).string());
  CachedController c;
  c.project = entry.string();
  c.library = library.string();
  struct stat st {};
  if (lstat(entry.c_str(), &st) == 0) {
    ensure_private_dir(entry.string());
    const std::string recorded = manifest_sha256(entry, key);
    const std::string actual = recorded.empty() ? std::string() : library_sha256(library);
    if (!recorded.empty() && actual == recorded) {
      c.sha256 = recorded;
      return c;
    }
    c.rebuilt_because = recorded.empty() ? "it has no complete manifest (an interrupted build?)"
                        : actual.empty() ? "its library is missing or not a regular file"
                                         : "its library's SHA-256 " + actual + " is not the " +
                                               recorded + " recorded when it was built";
    fs::remove_all(entry, ec);
    if (ec) {
      std::string msg = "cannot remove the stale cache entry '";
      msg.append(entry.string()).append("': ").append(ec.message());
      throw Error("io", msg);
    }
  }
  ensure_private_dir(entry.string());
  generate(program, entry.string(), files);
  const BuildResult r = build_project(entry.string(), jobs, config.package);
  if (!r.ok) {
    std::string msg = "building the generated controller in '";
    msg.append(entry.string()).append("' failed:\n").append(r.output);
    throw Error("build", msg);
  }
  c.sha256 = library_sha256(library);
  if (c.sha256.empty()) {
    std::string msg = "the build left no regular file '";
    msg.append(library.string()).append("'");
    throw Error("build", msg);
  }
  std::string manifest = kManifestHeader;
  manifest.append("\nkey ").append(key).append("\nlibrary build/").append(kLibraryName);
  manifest.append("\nsha256 ").append(c.sha256).append("\n");
  write_output((entry / kManifestName).string(), manifest);
  c.built = true;
  return c;
}

std::unique_ptr<robot::Controller> load_controller(const std::string& library,
                                                   const std::string& expected_sha256) {
  // One open file: what is hashed is what is loaded, whatever happens to the
  // path in between.
  const Fd fd(open(library.c_str(), O_RDONLY | O_NOFOLLOW | O_CLOEXEC));
  if (fd.get() < 0) load_error(library, std::strerror(errno));
  struct stat st {};
  if (fstat(fd.get(), &st) != 0 || !S_ISREG(st.st_mode)) load_error(library, "not a regular file");
  if (!expected_sha256.empty()) {
    const std::string actual = sha256_hex_of_fd(fd.get(), library);
    if (actual != expected_sha256) {
      load_error(library, "its SHA-256 " + actual + " is not the " + expected_sha256 +
                              " recorded when it was built; it was not loaded");
    }
  }
  // The dynamic loader matches a name it has loaded before, and a controller
  // library stays loaded for good (its unique symbols): a name like
  // /proc/self/fd/N that an earlier library was loaded under would return
  // that library. Use a descriptor number no loaded object is named after.
  int use = fd.get();
  std::vector<std::unique_ptr<Fd>> duplicates;
  std::string via = "/proc/self/fd/" + std::to_string(use);
  while (loaded_under(via)) {
    const int next = fcntl(use, F_DUPFD_CLOEXEC, use + 1);
    if (next < 0)
      load_error(library, std::string("cannot duplicate its descriptor: ") + std::strerror(errno));
    duplicates.push_back(std::make_unique<Fd>(next));
    use = next;
    via = "/proc/self/fd/" + std::to_string(use);
  }
  void* handle = dlopen(via.c_str(), RTLD_NOW | RTLD_LOCAL);
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
