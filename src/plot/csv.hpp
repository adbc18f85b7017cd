// A numeric CSV table as `mospec run --log` writes it: one header line of
// column names, then rows of numbers (shortest round-trip form; "nan" and
// "inf" allowed). Read whole into columns, every error located "file:line".
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace mospec::plot {

struct Table {
  std::string path;                       // where it was read from (for messages)
  std::vector<std::string> columns;       // header names, in file order
  std::vector<uint32_t> column_at;        // where each name starts in the header (1-based)
  std::vector<std::vector<double>> data;  // data[column][row]

  size_t rows() const { return data.empty() ? 0 : data.front().size(); }
  // The index of a column by exact name.
  std::optional<size_t> find(std::string_view name) const;
  // Like find(), but throws mospec::Error (code "missing-column") naming the
  // column, the file and every available column.
  size_t require(std::string_view name, std::string_view role) const;
  const std::vector<double>& column(std::string_view name) const { return data[require(name, "")]; }
};

// Parses `text` (the content of `path`). Throws mospec::Error (code "csv")
// located at the offending line (and column for a bad field): an empty file, an
// empty or duplicate header name, a row with the wrong number of fields, a field
// that is not a number. A final newline and '\r' line ends are accepted.
Table parse_csv(std::string_view text, const std::string& path);

// Reads and parses a file; I/O errors are mospec::Error (code "io").
Table read_csv(const std::string& path);

// "a, b, c": a list of names for messages.
std::string join_names(const std::vector<std::string>& names);

}  // namespace mospec::plot
