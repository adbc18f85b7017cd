// One diagnostic shape for every stage: "file:line:col: severity: message".
//
// Stages report through a DiagnosticSink (the caller decides whether a finding is
// collected, printed or escalated); errors that stop a stage are thrown as
// mospec::Error, which carries the same location.
#pragma once

#include <array>
#include <atomic>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "support/diagnostic_codes.hpp"

namespace mospec {

// Files are named by a small integer so that every JSON value and every quad can
// carry its origin cheaply. Id 0 means "no file" (generated or unknown).
//
// The documents of one load are parsed on more than one thread, so add() may
// run beside other add() and path() calls. A path never moves once added
// (blocks that double in size, never reallocated), so path() reads without a
// lock: an id is only ever handed out by add(), after its path is in place.
class SourceFiles {
 public:
  SourceFiles();
  ~SourceFiles();
  SourceFiles(const SourceFiles&);
  SourceFiles& operator=(const SourceFiles&);
  SourceFiles(SourceFiles&&) noexcept;
  SourceFiles& operator=(SourceFiles&&) noexcept;
  uint32_t add(std::string path);  // returns the existing id if already present
  const std::string& path(uint32_t id) const;
  size_t size() const { return size_.load(std::memory_order_acquire); }

 private:
  struct Index;  // path -> id, and the lock add() takes
  static constexpr size_t kFirstBlock = 64;
  static constexpr size_t kBlocks = 26;  // 64 * (2^26 - 1) ids, far past any model
  std::string& slot(uint32_t id) const;
  std::array<std::unique_ptr<std::string[]>, kBlocks> blocks_;
  std::atomic<size_t> size_{0};
  std::unique_ptr<Index> index_;
};

// 1-based line and column (columns count bytes); 0 means unknown.
struct SourceLoc {
  uint32_t file = 0;
  uint32_t line = 0;
  uint32_t column = 0;
  bool known() const { return line != 0; }
  friend bool operator==(const SourceLoc&, const SourceLoc&) = default;
};

std::string_view to_string(Severity);

struct Diagnostic {
  Severity severity = Severity::Error;
  std::string file;  // empty: not located in a file
  uint32_t line = 0;
  uint32_t column = 0;
  DiagnosticCode code;  // stable machine-readable kind, e.g. "dropped-key"
  std::string message;
};

// A place in a file as values carry it outside a SourceFiles table (a world
// file's entry, a second definition named in a message).
struct Place {
  std::string file;
  uint32_t line = 0;
  uint32_t column = 0;
  bool known() const { return !file.empty() && line != 0; }
};

// "file:line:col" (or "file:line" when the column is unknown) for a message
// that names a second place; format() writes a diagnostic's own place. The
// one home of that spelling (tests/layering/diagnostic_shape.sh).
std::string format_place(std::string_view file, uint32_t line, uint32_t column);

// A diagnostic at `loc` (file, line and column when known; unlocated otherwise).
Diagnostic located(Severity severity, SourceLoc loc, const SourceFiles& files, DiagnosticCode code,
                   std::string message);

// "file:line:col: warning: message", or "mospec: warning: message" for a
// diagnostic with no place in a file (a file without a line is named in the
// message: "... (in FILE)" unless the message names it already). Every
// producer that knows a line knows its column too; tests/cli's `expect`
// fails on any "FILE:LINE: " without one.
std::string format(const Diagnostic&);

// The same two shapes for a severity that is not one of Severity's (a SHACL
// report's "info", or a shape's own severity IRI): `file` empty or `line` 0
// gives the "mospec:" shape.
std::string format(std::string_view file, uint32_t line, uint32_t column, std::string_view severity,
                   std::string_view message);

// A number as messages quote it: every digit needed to read the same double
// back ("%.17g"), so a message never hides the value that was rejected.
std::string exact_number(double value);

// Collects diagnostics; the caller inspects or prints them.
class DiagnosticSink {
 public:
  void report(Diagnostic d) { diagnostics_.push_back(std::move(d)); }
  const std::vector<Diagnostic>& diagnostics() const { return diagnostics_; }
  size_t count(Severity) const;
  void clear() { diagnostics_.clear(); }

 private:
  std::vector<Diagnostic> diagnostics_;
};

// A fatal error of a stage. `code` is a stable kind; for JSON-LD processing it is
// the spec's error code (e.g. "invalid context entry") so conformance tests can
// compare it.
class Error : public std::runtime_error {
 public:
  Error(DiagnosticCode code, std::string message, std::string file = {}, uint32_t line = 0,
        uint32_t column = 0);
  const std::string& code() const { return code_; }
  const Diagnostic& diagnostic() const { return diagnostic_; }

 private:
  std::string code_;
  Diagnostic diagnostic_;
};

}  // namespace mospec
