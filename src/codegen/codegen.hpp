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
// mospec::Error("io") naming the path on failure, and
// mospec::Error("unsafe-path") before writing anything when `out_dir` holds
// a character CMake could not quote in a build of it (check_cmake_path).
void generate(const ir::Program& program, const std::string& out_dir,
              const SourceFiles* files = nullptr);

// A double as C++ source that reads back as exactly the same value: %.17g with
// a decimal point added where needed ("1.0", "-0.0", "2.5e-07"), and the
// numeric_limits spelling of infinities and NaN.
std::string cpp_double(double value);

// A C++ string literal (quotes included) for arbitrary bytes: printable ASCII
// as it is, everything else (control characters, bytes outside ASCII, '?')
// as octal escapes, so the literal holds exactly `text`'s bytes.
std::string cpp_string(std::string_view text);

// Model text for a // comment (or a CMake # comment): printable ASCII only.
// Control characters (line breaks), the backslash, '?' before '?' (a
// trigraph), '*' before '/' and '/' before '*' are written \xHH; characters
// outside ASCII (bidi controls among them) \uXXXX or \UXXXXXXXX, and bytes
// that are not UTF-8 \xHH. So the comment cannot end early, splice a line,
// or show a reader something the compiler does not see.
std::string comment_text(std::string_view text);

// The C++ identifier of a model-derived name in one role ("v" for a datum's
// slot, "arm", "eval", ...): role + '_' + the name, letters and digits as
// they are, every other byte as _xHH (xHH first, and a leading 'x' too); an
// underscore stays when a letter or digit other than 'x' follows it. Injective
// for a given role (the name can be read back), never holds "__" and, with a
// lower-case role, never starts with '_' or a capital: no keyword, no reserved
// name and no standard macro (errno, assert, NULL, unix, ...) can result.
std::string mangle(std::string_view role, std::string_view name);

}  // namespace mospec::codegen
