// A run summary (`mospec run --summary`) as the report reads it: only the
// fields the page shows, each checked for its JSON type and range where it is
// read. A summary comes with a shared run directory, so it is untrusted input:
// a field of the wrong type, a number out of range or nesting past the JSON
// reader's depth limit (512) is a located error (`FILE:LINE:COL`), never an
// internal error. Fields the page does not show are not looked at.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "plot/log_info.hpp"
#include "support/diagnostics.hpp"

namespace mospec::report {

struct MotionRow {
  std::string name;
  std::optional<double> started_time, ended_time;  // s; absent: never started / still running
  std::string ended_by;
};

struct EventRow {
  std::optional<double> tick;
  std::string column;  // the log column the event is on
  std::string what;    // a motion's reason, or a monitor's edge
};

struct ConstraintRow {
  std::string name, relation;
  bool guard = false;
  std::optional<double> final_value, final_error;
  bool judged = true, satisfied = false;
};

struct Summary {
  std::string status;  // "ok", "failed", or what the file says (shown, escaped)
  std::vector<std::string> why;
  std::string controller;
  double duration = 0;  // s, finite and >= 0
  std::optional<double> ticks, max_torque_ratio;
  std::vector<MotionRow> motions;
  std::vector<EventRow> events;
  std::vector<ConstraintRow> constraints;
  std::string scenario;  // the app the run came from, as `run` was given it
  // The log's units and the constraints' thresholds ("log"); empty in a
  // summary written before mospec recorded them.
  plot::LogInfo log;
};

// Parses `text`, the content of the file `path` (registered in `files` for
// locations). Throws mospec::Error (code "report") located at the offending
// value; a JSON syntax error keeps the reader's own location.
Summary parse_summary(std::string_view text, const std::string& path, SourceFiles& files);

}  // namespace mospec::report
