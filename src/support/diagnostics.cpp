#include "support/diagnostics.hpp"

#include <algorithm>
#include <cstdio>

namespace mospec {

SourceFiles::SourceFiles() {
  paths_.emplace_back();
}

uint32_t SourceFiles::add(std::string path) {
  auto it = std::find(paths_.begin() + 1, paths_.end(), path);
  if (it != paths_.end()) return static_cast<uint32_t>(it - paths_.begin());
  paths_.push_back(std::move(path));
  return static_cast<uint32_t>(paths_.size() - 1);
}

Diagnostic located(Severity severity, SourceLoc loc, const SourceFiles& files, std::string code,
                   std::string message) {
  Diagnostic d;
  d.severity = severity;
  if (loc.known()) {
    d.file = files.path(loc.file);
    d.line = loc.line;
    d.column = loc.column;
  }
  d.code = std::move(code);
  d.message = std::move(message);
  return d;
}

const std::string& SourceFiles::path(uint32_t id) const {
  return id < paths_.size() ? paths_[id] : paths_[0];
}

std::string_view to_string(Severity s) {
  switch (s) {
    case Severity::Note:
      return "note";
    case Severity::Warning:
      return "warning";
    case Severity::Error:
      return "error";
  }
  return "error";
}

std::string format(const Diagnostic& d) {
  std::string out;
  if (d.file.empty()) {
    out = "mospec";
  } else {
    out = d.file;
    if (d.line != 0) {
      out += ':' + std::to_string(d.line);
      if (d.column != 0) out += ':' + std::to_string(d.column);
    }
  }
  out += ": ";
  out += to_string(d.severity);
  out += ": ";
  out += d.message;
  return out;
}

std::string exact_number(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.17g", value);
  return buffer;
}

size_t DiagnosticSink::count(Severity s) const {
  return static_cast<size_t>(std::count_if(diagnostics_.begin(), diagnostics_.end(),
                                           [s](const Diagnostic& d) { return d.severity == s; }));
}

static std::string what_of(const std::string& code, const std::string& message,
                           const std::string& file, uint32_t line, uint32_t column) {
  Diagnostic d{Severity::Error, file, line, column, code, message};
  return format(d);
}

Error::Error(std::string code, std::string message, std::string file, uint32_t line,
             uint32_t column)
    : std::runtime_error(what_of(code, message, file, line, column)),
      code_(code),
      diagnostic_{Severity::Error, std::move(file), line,
                  column,          std::move(code), std::move(message)} {}

}  // namespace mospec
