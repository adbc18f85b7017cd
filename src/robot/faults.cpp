#include "robot/faults.hpp"

#include <limits>
#include <string>

#include "support/diagnostics.hpp"

namespace mospec::robot {

void FaultInjector::add(const Fault& fault) {
  if (count_ == kCapacity) {
    throw Error("too-many-faults", "at most " + std::to_string(kCapacity) +
                                       " faults can be injected at once; clear() first");
  }
  faults_[static_cast<std::size_t>(count_++)] = fault;
}

void FaultInjector::add_sensor_fault(FaultKind kind, std::string_view sensor_name,
                                     std::uint64_t from_tick, std::uint64_t ticks) {
  Fault f;
  f.kind = kind;
  f.sensor = sensor(shape_, sensor_name);
  f.from_tick = from_tick;
  f.ticks = ticks;
  add(f);
}

void FaultInjector::inject_nan(std::string_view sensor_name, std::uint64_t from_tick,
                               std::uint64_t ticks) {
  add_sensor_fault(FaultKind::Nan, sensor_name, from_tick, ticks);
}

void FaultInjector::inject_stale(std::string_view sensor_name, std::uint64_t from_tick,
                                 std::uint64_t ticks) {
  add_sensor_fault(FaultKind::Stale, sensor_name, from_tick, ticks);
}

void FaultInjector::drop_commands(std::uint64_t from_tick, std::uint64_t count) {
  Fault f;
  f.kind = FaultKind::DropCommand;
  f.from_tick = from_tick;
  f.ticks = count;
  add(f);
}

void FaultInjector::corrupt(MeasuredState& state) noexcept {
  const std::uint64_t tick = state.clock.tick;
  for (int i = 0; i < count_; ++i) {
    Fault& f = faults_[static_cast<std::size_t>(i)];
    if (f.kind == FaultKind::DropCommand) continue;
    double& value = sensor_value(state, f.sensor);
    if (!f.active(tick)) {
      // Before the fault: remember the last good value.
      if (f.kind == FaultKind::Stale && tick < f.from_tick) {
        f.held = value;
        f.captured = true;
      }
      continue;
    }
    if (f.kind == FaultKind::Nan) {
      value = std::numeric_limits<double>::quiet_NaN();
    } else {
      if (!f.captured) {
        f.held = value;
        f.captured = true;
      }
      value = f.held;
    }
  }
}

bool FaultInjector::drops(std::uint64_t tick) const noexcept {
  for (int i = 0; i < count_; ++i) {
    const Fault& f = faults_[static_cast<std::size_t>(i)];
    if (f.kind == FaultKind::DropCommand && f.active(tick)) return true;
  }
  return false;
}

}  // namespace mospec::robot
