// Tests that read the source tree (registries checked against metamodels/,
// templates, test data): a file's text, and the texts of the files below a
// folder whose names end with a suffix.
#pragma once

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace mospec::test {

inline std::string slurp(const std::filesystem::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// The text of every regular file under `dir` whose name ends with `suffix`.
inline std::vector<std::string> texts_of_files(const std::filesystem::path& dir,
                                               const std::string& suffix) {
  std::vector<std::string> out;
  for (const auto& e : std::filesystem::recursive_directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    if (e.is_regular_file() && name.size() >= suffix.size() &&
        name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0)
      out.push_back(slurp(e.path()));
  }
  return out;
}

}  // namespace mospec::test
