#include "cli/faults.hpp"

#include <cstdint>

#include "sim/run.hpp"
#include "support/diagnostics.hpp"

namespace mospec::cli {

// --fault KIND[:SENSOR]@TICK[+TICKS]: nan:right_arm.q[1]@500+100,
// stale:pivot_q[0]@100, drop@200+5 (TICKS omitted: until the end for sensors,
// one command for drop).
void add_fault(robot::FaultInjector& faults, const std::string& spec) {
  auto bad = [&spec](const std::string& why) {
    return Error("usage", "--fault '" + spec + "': " + why +
                              " (expected nan:SENSOR@TICK[+TICKS], stale:SENSOR@TICK[+TICKS] "
                              "or drop@TICK[+COUNT])");
  };
  const auto at = spec.rfind('@');
  if (at == std::string::npos) throw bad("no @TICK");
  const std::string what = spec.substr(0, at), when = spec.substr(at + 1);
  std::uint64_t from = 0, ticks = 0;
  bool has_ticks = false;
  {
    const auto plus = when.find('+');
    const std::string a = when.substr(0, plus);
    const std::string b = plus == std::string::npos ? "" : when.substr(plus + 1);
    auto number = [&](const std::string& text, std::uint64_t& out) {
      if (text.empty() || text.find_first_not_of("0123456789") != std::string::npos) {
        throw bad("'" + text + "' is not a tick count");
      }
      // A run has at most 10^7 ticks (sim::kMaxTicks): a later tick is a typo.
      if (text.size() > 8 || std::stoull(text) > sim::kMaxTicks) {
        throw bad("tick " + text + " is beyond 10^7, the most ticks a run has");
      }
      out = std::stoull(text);
    };
    number(a, from);
    if (plus != std::string::npos) {
      number(b, ticks);
      has_ticks = true;
    }
  }
  const auto colon = what.find(':');
  const std::string kind = what.substr(0, colon);
  const std::string sensor = colon == std::string::npos ? "" : what.substr(colon + 1);
  if (kind == "drop") {
    if (colon != std::string::npos) throw bad("drop takes no sensor");
    faults.drop_commands(from, has_ticks ? ticks : 1);
  } else if (kind == "nan" || kind == "stale") {
    if (sensor.empty()) throw bad(kind + " needs a sensor");
    if (kind == "nan") {
      faults.inject_nan(sensor, from, ticks);
    } else {
      faults.inject_stale(sensor, from, ticks);
    }
  } else {
    throw bad("unknown kind '" + kind + "'");
  }
}

}  // namespace mospec::cli
