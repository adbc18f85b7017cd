// Canonical paths for the many paths of one load. Apart from paths.hpp so that
// headers holding one do not pull in <filesystem>.
#pragma once

#include <string>
#include <string_view>
#include <unordered_map>

namespace mospec {

// canonical_path() for the many paths of one load, which share their
// directories: each path component is checked once (one lstat) and
// remembered, instead of realpath's getcwd and readlink per component of
// every path. A component that is a symbolic link, or a path that does not
// exist, is answered by canonical_path() itself, so the answers are the same.
// What it remembers is only as fresh as the instance: keep one per load.
class CanonicalPaths {
 public:
  std::string canonical(std::string_view path);

 private:
  std::string cwd_;
  // A canonical directory plus one more component -> whether it is a
  // directory, and for a symbolic link, the canonical form it resolves to.
  struct Known {
    bool directory = false;
    bool link = false;
    std::string target;  // a link's canonical target
  };
  std::unordered_map<std::string, Known> known_;
  std::string resolved_, candidate_;  // canonical()'s buffers
};

}  // namespace mospec
