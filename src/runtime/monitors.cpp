#include "runtime/monitors.hpp"

#include <cstdio>
#include <string>

#include "support/diagnostics.hpp"

namespace mospec::runtime {

Condition::Condition(const MonitorThresholds& thresholds, const char* name) : t_(thresholds) {
  auto number = [](double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.17g", v);
    return std::string(buf);
  };
  if (t_.enter != t_.enter || t_.leave != t_.leave) {
    throw Error("invalid-monitor", std::string(name) + ": thresholds must not be NaN (enter " +
                                       number(t_.enter) + ", leave " + number(t_.leave) + ")");
  }
  const bool below = t_.sense == Sense::Below;
  if (below ? t_.enter > t_.leave : t_.enter < t_.leave) {
    throw Error("invalid-monitor", std::string(name) + ": a monitor satisfied " +
                                       (below ? "below" : "above") + " its threshold needs enter " +
                                       (below ? "<=" : ">=") + " leave for hysteresis, got enter " +
                                       number(t_.enter) + " and leave " + number(t_.leave));
  }
}

}  // namespace mospec::runtime
