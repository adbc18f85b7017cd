#include "support/paths.hpp"

#include <cstdlib>
#include <system_error>

namespace mospec {
namespace fs = std::filesystem;

fs::path canonical_path(const std::string& path) {
  std::error_code ec;
  fs::path abs = fs::absolute(path, ec);
  if (ec) return fs::path(path).lexically_normal();
  // An existing path: one realpath(3) call. weakly_canonical gives the same
  // answer but first stats every prefix of the path, which made path checks a
  // fifth of loading a model.
  if (char* resolved = ::realpath(abs.c_str(), nullptr)) {
    fs::path p(resolved);
    std::free(resolved);
    return p;
  }
  fs::path p = fs::weakly_canonical(abs, ec);
  return ec ? abs.lexically_normal() : p;
}

bool is_within(const fs::path& path, const fs::path& root) {
  auto p = path.begin();
  for (auto r = root.begin(); r != root.end(); ++r) {
    if (r->empty()) continue;  // a trailing '/'
    if (p == path.end() || *p != *r) return false;
    ++p;
  }
  return true;
}

std::string escaped_bytes(std::string_view s) {
  static constexpr char kHex[] = "0123456789ABCDEF";
  std::string out;
  for (char c : s) {
    const auto u = static_cast<unsigned char>(c);
    if (u < 0x20 || u >= 0x7f) {
      out += "\\x";
      out += kHex[u >> 4];
      out += kHex[u & 15];
    } else {
      out += c;
    }
  }
  return out;
}

}  // namespace mospec
