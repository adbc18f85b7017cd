// Code generation: an IR Program (src/ir/ir.hpp) -> a C++20 CMake project whose
// shared library implements robot::Controller (src/robot/controller.hpp).
//
// Every decision is made here, in C++, while building the template data: which
// runtime call each step becomes, which slot each operand lives in, how every
// constant is spelled. The Mustache templates (templates/*.mustache, embedded
// into this library at build time) only substitute and iterate. The generated
// tick makes the same runtime calls, in the same order, with the same
// arguments as the IR interpreter (src/ir/interpreter.cpp), so both log
// bit-identical values. See docs/codegen.md.
#pragma once

#include <string>
#include <vector>

#include "ir/ir.hpp"
#include "support/diagnostics.hpp"

namespace mospec::codegen {

// One file of the generated project, its path relative to the project root.
struct GeneratedFile {
  std::string path;
  std::string content;
};

// Renders the project: CMakeLists.txt, controller.hpp, controller.cpp.
// Deterministic: the same Program (and source files) gives byte-identical
// files; every number is printed with %.17g so constants round-trip exactly.
// `files` resolves the steps' SourceLoc into "file:line" comments (nullptr:
// line numbers only). Throws mospec::Error("codegen") for a Program the
// generator cannot express (e.g. a template that fails to render).
std::vector<GeneratedFile> render(const ir::Program& program, const SourceFiles* files = nullptr);

// render() written into `out_dir` (created if missing), each file atomically
// (temporary sibling + rename): a reader never sees half a file. Throws
// mospec::Error("io") naming the path on failure.
void generate(const ir::Program& program, const std::string& out_dir,
              const SourceFiles* files = nullptr);

// A double as C++ source that reads back as exactly the same value: %.17g with
// a decimal point added where needed ("1.0", "-0.0", "2.5e-07"), and the
// numeric_limits spelling of infinities and NaN.
std::string cpp_double(double value);

// A C++ string literal (quotes included) for arbitrary bytes.
std::string cpp_string(std::string_view text);

}  // namespace mospec::codegen
