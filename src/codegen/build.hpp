// Building and loading generated controllers: what `mospec build` runs, and
// what a control loop (e.g. `mospec run`) uses to turn a generated project into
// a robot::Controller.
#pragma once

#include <memory>
#include <string>

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

// The generated and built controller of `program`, kept in
// cache_dir/<hash of the generated files and the runtime package>/: generated
// and built the first time (`built` is then true), later only brought up to
// date by an incremental `cmake --build` (which relinks when the runtime's
// libraries changed). Throws mospec::Error("build") with the compiler's output
// when the project does not build.
struct CachedController {
  std::string library;
  std::string project;  // the generated project's directory
  bool built = false;   // generated and configured now (not found in the cache)
};
CachedController cached_controller(const ir::Program& program, const std::string& cache_dir,
                                   const SourceFiles* files = nullptr, int jobs = 2);

// Loads a built controller library: dlopen, mospec_create_controller(), and the
// ABI check. The returned controller keeps the library loaded for as long as it
// lives. Throws mospec::Error("load") naming the library and the reason.
std::unique_ptr<robot::Controller> load_controller(const std::string& library);

}  // namespace mospec::codegen
