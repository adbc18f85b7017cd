// Building and loading generated controllers: what `mospec build` runs, and
// what a control loop (e.g. `mospec run`) uses to turn a generated project into
// a robot::Controller.
#pragma once

#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "codegen/codegen.hpp"
#include "ir/ir.hpp"
#include "robot/controller.hpp"
#include "support/diagnostics.hpp"

namespace mospec::codegen {

// The runtime's CMake package directory (holding mospecConfig.cmake): an
// installed one next to the running executable (PREFIX/bin/x ->
// PREFIX/<libdir>/cmake/mospec) when present, else the build tree this library
// was built in.
std::string default_package_dir();

struct BuildResult {
  bool ok = false;
  std::string library;  // DIR/build/libmospec_controller.so (absolute) when ok
  std::string output;   // the failing step's output (configure or compile) when not
};

// Configures (cmake -S DIR -B DIR/build, Release, -Dmospec_DIR=package, the
// compiler mospec was built with) and builds the project in `dir`. The tools
// are run without a shell, so paths are passed as they are. `package` empty:
// default_package_dir(). Throws mospec::Error("usage") when `dir` holds no
// CMakeLists.txt.
BuildResult build_project(const std::string& dir, int jobs = 2, const std::string& package = {});

// A path that CMake writes into the files it generates (the project and
// build directories, the package, the compiler) must not hold what it cannot
// quote there: a line break or another control character, '"', '\\', '$'
// or ';'. Throws mospec::Error("unsafe-path") naming `what`, the path and
// the character otherwise.
void check_cmake_path(const std::string& path, const std::string& what);

// SHA-256 of bytes, and of everything an open file descriptor reads from
// its current offset to the end, as 64 lower-case hex digits (OpenSSL
// libcrypto). Throws mospec::Error("io") when the read fails.
std::string sha256_hex(std::string_view bytes);
std::string sha256_hex_of_fd(int fd, const std::string& name);

// The default cache directory (XDG Base Directory): $XDG_CACHE_HOME/mospec
// when XDG_CACHE_HOME is an absolute path, else $HOME/.cache/mospec when HOME
// is; a relative or empty XDG_CACHE_HOME is ignored, as the specification
// says. Neither: throws mospec::Error("usage") asking for --cache DIR. The
// overload reads the environment.
std::string default_cache_dir(const char* xdg_cache_home, const char* home);
std::string default_cache_dir();

// Makes `dir` a private directory of this user: missing components are
// created with mode 0700; an existing `dir` must be a directory owned by the
// effective user and writable by nobody else. Throws mospec::Error("unsafe-cache")
// naming the directory and the fix otherwise (or "io" when it cannot be made).
void ensure_private_dir(const std::string& dir);

// Everything besides the generated files that decides what a build produces.
struct BuildConfig {
  std::string version;             // mospec's version
  std::string runtime_id;          // content of the runtime's libraries and headers (build time)
  std::string package;             // the runtime's CMake package directory
  std::string package_content;     // SHA-256 of that directory's files
  std::string compiler;            // path of the C++ compiler
  std::string compiler_version;    // its --version output (and CMake's id at configure time)
  std::vector<std::string> flags;  // the configure arguments, CXXFLAGS & co, Eigen's version
};
// The configuration `cached_controller` builds with (`package` empty: default_package_dir()).
BuildConfig current_build_config(const std::string& package = {});

// The cache key: SHA-256 over the configuration and every generated file's
// name and content, each field length-prefixed (no two inputs share a key by
// concatenation).
std::string cache_key(const std::vector<GeneratedFile>& files, const BuildConfig& config);

// The generated and built controller of `program`, kept in
// cache_dir/<cache_key>/ with a manifest holding the built library's SHA-256:
// generated and built the first time (`built` is then true); later found by
// its key, and used only when the library's content still has the manifest's
// hash (otherwise the entry is removed and built again; `rebuilt_because`
// says why). `cache_dir` and the entry are private directories
// (ensure_private_dir). Runs started in parallel build an entry once (a file
// lock per key). Throws mospec::Error("build") with the compiler's output
// when the project does not build.
struct CachedController {
  std::string library;
  std::string sha256;           // the library's content hash, for load_controller
  std::string project;          // the generated project's directory
  bool built = false;           // generated and built now (not found in the cache)
  std::string rebuilt_because;  // an entry was found but not usable: why
};
CachedController cached_controller(const ir::Program& program, const std::string& cache_dir,
                                   const SourceFiles* files = nullptr, int jobs = 2);

// Loads a built controller library: opens it once (no symlink followed),
// hashes what that descriptor reads and, when `expected_sha256` is given,
// refuses a library whose content differs; then dlopens that same open file
// (/proc/self/fd/N, so what is loaded is what was hashed),
// mospec_create_controller(), and the ABI check. The returned controller
// keeps the library loaded for as long as it lives. Throws
// mospec::Error("load") naming the library and the reason.
std::unique_ptr<robot::Controller> load_controller(const std::string& library,
                                                   const std::string& expected_sha256 = {});

}  // namespace mospec::codegen
