// What the closed-loop scenario tests share: the run's CSV log, read with the
// project's own parser (src/plot/csv.hpp: a malformed log is a located error,
// not zeros) into rows; quoting for the shell command that runs `mospec run`;
// reading a whole file.
#pragma once

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "plot/csv.hpp"

namespace mospec::testing {

struct Csv {
  std::vector<std::string> header;
  std::vector<std::vector<double>> rows;  // rows[row][column]
  int column(const std::string& name) const {
    for (size_t i = 0; i < header.size(); ++i)
      if (header[i] == name) return static_cast<int>(i);
    return -1;
  }
};

inline Csv read_csv(const std::filesystem::path& path) {
  const plot::Table table = plot::read_csv(path.string());
  Csv csv;
  csv.header = table.columns;
  csv.rows.assign(table.rows(), std::vector<double>(table.columns.size()));
  for (size_t c = 0; c < table.data.size(); ++c)
    for (size_t r = 0; r < table.rows(); ++r) csv.rows[r][c] = table.data[c][r];
  return csv;
}

inline std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

inline std::string shell_quote(const std::string& s) {
  std::string out = "'";
  for (char c : s) {
    if (c == '\'')
      out += "'\\''";
    else
      out += c;
  }
  return out + "'";
}

}  // namespace mospec::testing
