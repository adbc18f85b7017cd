// check_cmake_path (build.hpp), apart from build.cpp: `mospec generate` checks
// its output directory with it, and build.cpp's hashing would otherwise link
// libcrypto into the executable that only validates and generates.
#include <array>
#include <cstdio>

#include "codegen/build.hpp"
#include "codegen/codegen.hpp"
#include "support/diagnostics.hpp"

namespace mospec::codegen {

void check_cmake_path(const std::string& path, const std::string& what) {
  for (const char c : path) {
    const auto u = static_cast<unsigned char>(c);
    if (u >= 0x20 && u != 0x7f && c != '"' && c != '\\' && c != '$' && c != ';') continue;
    std::array<char, 8> code{};
    std::snprintf(code.data(), code.size(), "0x%02X", static_cast<unsigned>(u));
    std::string msg = what;
    msg.append(" '").append(comment_text(path)).append("' holds ");
    if (u < 0x20 || u == 0x7f) {
      msg.append("the control character ").append(code.data());
    } else {
      msg.append("'").append(1, c).append("'");
    }
    msg.append(
        ", which CMake cannot quote safely in the build files it generates; use a path "
        "without line breaks, control characters, '\"', '\\', '$' or ';'");
    throw Error("unsafe-path", msg);
  }
}

}  // namespace mospec::codegen
