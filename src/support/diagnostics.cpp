#include "support/diagnostics.hpp"

#include <algorithm>
#include <bit>
#include <cstdio>
#include <cstdlib>
#include <mutex>
#include <unordered_map>

namespace mospec {

struct SourceFiles::Index {
  std::mutex mutex;
  std::unordered_map<std::string, uint32_t> ids;
};

SourceFiles::SourceFiles() : index_(std::make_unique<Index>()) {
  blocks_[0] = std::make_unique<std::string[]>(kFirstBlock);
  size_.store(1, std::memory_order_release);  // id 0, the empty path
}

SourceFiles::~SourceFiles() = default;

SourceFiles::SourceFiles(const SourceFiles& other) : SourceFiles() {
  const size_t n = other.size();
  for (size_t id = 1; id < n; ++id) add(other.path(static_cast<uint32_t>(id)));
}

SourceFiles& SourceFiles::operator=(const SourceFiles& other) {
  if (this != &other) *this = SourceFiles(other);
  return *this;
}

SourceFiles::SourceFiles(SourceFiles&& other) noexcept
    : blocks_(std::move(other.blocks_)),
      size_(other.size_.load(std::memory_order_acquire)),
      index_(std::move(other.index_)) {
  other.size_.store(0, std::memory_order_release);
}

SourceFiles& SourceFiles::operator=(SourceFiles&& other) noexcept {
  blocks_ = std::move(other.blocks_);
  size_.store(other.size_.load(std::memory_order_acquire), std::memory_order_release);
  index_ = std::move(other.index_);
  other.size_.store(0, std::memory_order_release);
  return *this;
}

// Block b holds kFirstBlock << b ids, from kFirstBlock * (2^b - 1) on.
std::string& SourceFiles::slot(uint32_t id) const {
  const size_t k = id / kFirstBlock + 1;
  const int b = std::bit_width(k) - 1;
  return blocks_[static_cast<size_t>(b)][id - kFirstBlock * ((size_t{1} << b) - 1)];
}

uint32_t SourceFiles::add(std::string path) {
  std::lock_guard lock(index_->mutex);
  auto [it, fresh] = index_->ids.try_emplace(path, 0);
  if (!fresh) return it->second;
  const size_t id = size_.load(std::memory_order_relaxed);
  const size_t k = id / kFirstBlock + 1;
  const auto b = static_cast<size_t>(std::bit_width(k) - 1);
  if (b >= kBlocks) {
    index_->ids.erase(it);
    throw std::length_error("more source files than one load can name");
  }
  if (!blocks_[b]) blocks_[b] = std::make_unique<std::string[]>(kFirstBlock << b);
  slot(static_cast<uint32_t>(id)) = std::move(path);
  it->second = static_cast<uint32_t>(id);
  size_.store(id + 1, std::memory_order_release);
  return static_cast<uint32_t>(id);
}

Diagnostic located(Severity severity, SourceLoc loc, const SourceFiles& files, DiagnosticCode code,
                   std::string message) {
  Diagnostic d;
  d.severity = severity;
  if (loc.known()) {
    d.file = files.path(loc.file);
    d.line = loc.line;
    d.column = loc.column;
  }
  d.code = code;
  d.message = std::move(message);
  return d;
}

const std::string& SourceFiles::path(uint32_t id) const {
  return id < size() ? slot(id) : slot(0);
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

std::string format_place(std::string_view file, uint32_t line, uint32_t column) {
  std::string out(file);
  out += ':' + std::to_string(line);
  if (column != 0) out += ':' + std::to_string(column);
  return out;
}

std::string format(std::string_view file, uint32_t line, uint32_t column, std::string_view severity,
                   std::string_view message) {
  // Two shapes only: FILE:LINE:COL when the diagnostic has a place in a file,
  // "mospec:" otherwise. A file with no place in it (one that cannot be read,
  // a log too short) is named in the message instead of posing as a place.
  const bool placed = !file.empty() && line != 0;
  std::string out = placed ? format_place(file, line, column) : std::string("mospec");
  out += ": ";
  out += severity;
  out += ": ";
  out += message;
  if (!placed && !file.empty() && message.find(file) == std::string_view::npos) {
    out += " (in ";
    out += file;
    out += ')';
  }
  return out;
}

// MOSPEC_DIAGNOSTIC_CODES=1 writes each diagnostic's code after its severity,
// "error[CODE]:", as tests/ir/diagnostics/ spells expectations: tests of the
// command line check the code, not only the message (docs/diagnostics.md).
static bool show_codes() {
  static const bool on = [] {
    const char* v = std::getenv("MOSPEC_DIAGNOSTIC_CODES");
    return v != nullptr && *v != '\0' && std::string_view(v) != "0";
  }();
  return on;
}

std::string format(const Diagnostic& d) {
  if (show_codes() && !d.code.empty()) {
    const std::string severity =
        std::string(to_string(d.severity)) + "[" + std::string(d.code.name()) + "]";
    return format(d.file, d.line, d.column, severity, d.message);
  }
  return format(d.file, d.line, d.column, to_string(d.severity), d.message);
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

static std::string what_of(DiagnosticCode code, const std::string& message, const std::string& file,
                           uint32_t line, uint32_t column) {
  Diagnostic d{Severity::Error, file, line, column, code, message};
  return format(d);
}

Error::Error(DiagnosticCode code, std::string message, std::string file, uint32_t line,
             uint32_t column)
    : std::runtime_error(what_of(code, message, file, line, column)),
      code_(code),
      diagnostic_{Severity::Error, std::move(file), line, column, code, std::move(message)} {}

}  // namespace mospec
