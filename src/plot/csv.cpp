#include "plot/csv.hpp"

#include <charconv>
#include <cmath>
#include <limits>
#include <unordered_set>

#include "support/diagnostics.hpp"
#include "support/io.hpp"
#include "support/paths.hpp"

namespace mospec::plot {

namespace {

// Splits one line (without its end) at commas; `starts` receives each field's
// 0-based byte offset in the line.
void split(std::string_view line, std::vector<std::string_view>& fields,
           std::vector<size_t>& starts) {
  fields.clear();
  starts.clear();
  size_t begin = 0;
  for (;;) {
    const size_t comma = line.find(',', begin);
    const size_t end = comma == std::string_view::npos ? line.size() : comma;
    fields.push_back(line.substr(begin, end - begin));
    starts.push_back(begin);
    if (comma == std::string_view::npos) break;
    begin = comma + 1;
  }
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

// A number as `mospec run` writes it, plus the spellings of non-finite values.
bool parse_number(std::string_view s, double& out) {
  if (s.empty()) return false;
  if (s.front() == '+') s.remove_prefix(1);
  const char* end = s.data() + s.size();
  auto [p, ec] = std::from_chars(s.data(), end, out);
  return ec == std::errc() && p == end;
}

}  // namespace

std::optional<size_t> Table::find(std::string_view name) const {
  for (size_t i = 0; i < columns.size(); ++i) {
    if (columns[i] == name) return i;
  }
  return std::nullopt;
}

size_t Table::require(std::string_view name, std::string_view role) const {
  if (auto i = find(name)) return *i;
  std::string message = "no column '";
  message.append(escaped_bytes(name)).append("'");
  if (!role.empty()) message.append(" (").append(role).append(")");
  message.append("; the columns are: ").append(join_names(columns));
  // At the header, which lists the columns there are.
  throw Error("missing-column", message, path, 1, 1);
}

std::string join_names(const std::vector<std::string>& names) {
  std::string out;
  for (size_t i = 0; i < names.size(); ++i) {
    if (i) out.append(", ");
    out.append(names[i]);
  }
  return out;
}

Table parse_csv(std::string_view text, const std::string& path) {
  Table table;
  table.path = path;
  std::vector<std::string_view> fields;
  std::vector<size_t> starts;
  uint32_t line_no = 0;
  size_t pos = 0;
  bool header = true;
  while (pos < text.size()) {
    const size_t nl = text.find('\n', pos);
    std::string_view line =
        text.substr(pos, nl == std::string_view::npos ? std::string_view::npos : nl - pos);
    pos = nl == std::string_view::npos ? text.size() : nl + 1;
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    if (header) {
      header = false;
      if (trim(line).empty())
        throw Error("csv", "the header line (column names) is empty", path, line_no, 1);
      split(line, fields, starts);
      std::unordered_set<std::string> seen;
      for (size_t i = 0; i < fields.size(); ++i) {
        std::string name(trim(fields[i]));
        const auto column = static_cast<uint32_t>(starts[i] + 1);
        if (name.empty()) {
          std::string message = "column ";
          message.append(std::to_string(i + 1)).append(" has an empty name");
          throw Error("csv", message, path, line_no, column);
        }
        if (!seen.insert(name).second) {
          std::string message = "column name '";
          message.append(escaped_bytes(name)).append("' appears twice");
          throw Error("csv", message, path, line_no, column);
        }
        table.columns.push_back(std::move(name));
        table.column_at.push_back(column);
      }
      table.data.resize(table.columns.size());
      continue;
    }
    if (trim(line).empty()) {
      // Only a trailing blank line is tolerated: a blank line between rows
      // would silently shift the time base.
      if (text.find_first_not_of(" \t\r\n", pos) == std::string_view::npos) break;
      throw Error("csv", "empty line between rows", path, line_no, 1);
    }
    split(line, fields, starts);
    if (fields.size() != table.columns.size()) {
      std::string message = "expected ";
      message.append(std::to_string(table.columns.size()))
          .append(" fields (as in the header), got ")
          .append(std::to_string(fields.size()));
      // At the first field too many, or at the line's end where the next
      // field is missing.
      const size_t at =
          fields.size() > table.columns.size() ? starts[table.columns.size()] : line.size();
      throw Error("csv", message, path, line_no, static_cast<uint32_t>(at + 1));
    }
    for (size_t i = 0; i < fields.size(); ++i) {
      double v = 0.0;
      if (!parse_number(trim(fields[i]), v)) {
        std::string message = "column '";
        message.append(escaped_bytes(table.columns[i]))
            .append("': '")
            .append(escaped_bytes(fields[i]))
            .append("' is not a number");
        throw Error("csv", message, path, line_no, static_cast<uint32_t>(starts[i] + 1));
      }
      table.data[i].push_back(v);
    }
  }
  if (header)
    throw Error("csv", "the file is empty (expected a header line of column names)", path, 1, 1);
  return table;
}

Table read_csv(const std::string& path) {
  return parse_csv(read_file(path), path);
}

}  // namespace mospec::plot
