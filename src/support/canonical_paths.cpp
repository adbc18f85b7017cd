#include "support/canonical_paths.hpp"

#include <sys/stat.h>

#include <cstdlib>
#include <filesystem>
#include <system_error>

#include "support/paths.hpp"

namespace mospec {
namespace fs = std::filesystem;

std::string CanonicalPaths::canonical(std::string_view path) {
  if (path.empty() || path.find('\0') != std::string_view::npos) {
    return canonical_path(std::string(path)).string();
  }
  if (path[0] != '/' && cwd_.empty()) {
    std::error_code ec;
    cwd_ = fs::current_path(ec).string();
    if (ec || cwd_.empty() || cwd_[0] != '/') {
      cwd_.clear();
      return canonical_path(std::string(path)).string();
    }
  }
  // `resolved` stays canonical: every component appended to it was checked
  // not to be a link (or replaced by what the link resolves to), so `..` can
  // drop its last component by spelling.
  // (Both buffers are kept across calls: a path costs no allocation but its
  // answer and the components seen for the first time.)
  std::string& resolved = resolved_;
  std::string& candidate = candidate_;
  resolved.assign(path[0] == '/' || cwd_ == "/" ? std::string_view() : std::string_view(cwd_));
  size_t at = 0;
  while (at < path.size()) {
    size_t end = path.find('/', at);
    if (end == std::string_view::npos) end = path.size();
    const std::string_view part = path.substr(at, end - at);
    at = end + 1;
    if (part.empty() || part == ".") continue;
    if (part == "..") {
      resolved.resize(resolved.rfind('/') == std::string::npos ? 0 : resolved.rfind('/'));
      continue;
    }
    candidate.assign(resolved).append("/").append(part);
    auto it = known_.find(candidate);
    if (it == known_.end()) {
      struct stat st {};
      if (::lstat(candidate.c_str(), &st) != 0) {
        // Missing or unreadable: canonical_path resolves what exists of the
        // path and normalises the rest by spelling.
        return canonical_path(std::string(path)).string();
      }
      Known k{S_ISDIR(st.st_mode), S_ISLNK(st.st_mode), {}};
      if (k.link) {
        // A link is rare: realpath answers for it (and stat for its target).
        char* target = ::realpath(candidate.c_str(), nullptr);
        if (target == nullptr) return canonical_path(std::string(path)).string();
        k.target = std::string_view(target) == "/" ? std::string() : std::string(target);
        k.directory = ::stat(target, &st) == 0 && S_ISDIR(st.st_mode);
        std::free(target);
      }
      it = known_.emplace(candidate, std::move(k)).first;
    }
    // A file with more of the path after it is no directory to look in
    // (realpath fails): canonical_path says what such a path comes to.
    if (!it->second.directory && end < path.size()) {
      return canonical_path(std::string(path)).string();
    }
    if (it->second.link) {
      resolved = it->second.target;
    } else {
      resolved.swap(candidate);
    }
  }
  return resolved.empty() ? std::string("/") : resolved;
}

}  // namespace mospec
