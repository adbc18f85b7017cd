// What a run log's header does not say about its columns: each controller
// column's unit, and each evaluated constraint's relation and constant
// thresholds. `mospec run --summary` writes it into the summary ("log"), so a
// figure or a report page can put one unit on an axis and draw a constraint's
// thresholds as a band without loading the model again.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <string_view>

namespace mospec::plot {

struct ConstraintInfo {
  std::string relation;  // "equality", "less-than", "greater-than", "bilateral", "assignment"
  std::optional<double> reference;  // equality, assignment
  std::optional<double> lower;      // greater-than (its threshold), bilateral
  std::optional<double> upper;      // less-than (its threshold), bilateral
  std::optional<double> tolerance;
  // A motion's `when` or `until`: a condition it waits for, not a goal the
  // controllers pursue.
  bool guard = false;
};

struct LogInfo {
  // By log column: the QUDT local name of its unit ("M", "N-M"); "" for a
  // flag, an event or a dimensionless value.
  std::map<std::string, std::string> units;
  // By constraint (the prefix of its .value/.error columns).
  std::map<std::string, ConstraintInfo> constraints;
  bool empty() const { return units.empty() && constraints.empty(); }
};

// A QUDT unit's symbol for an axis ("M" -> "m", "N-M" -> "N·m",
// "RAD-PER-SEC" -> "rad/s"); a name it does not know is returned as it is.
std::string unit_symbol(std::string_view qudt);

// A log column's unit symbol: from `info` when it names the column, else
// from the column's name for the simulator's columns (unit_of()); "" when
// neither tells.
std::string column_unit(const LogInfo& info, const std::string& column);

}  // namespace mospec::plot
