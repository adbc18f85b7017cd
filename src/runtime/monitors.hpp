// Monitors (paper Sec. II-E): they signal a constraint's state to the
// time-discrete coordination (state machines, Petri nets).
//   - A level-triggered monitor raises a FLAG while the condition holds and
//     lowers it while it does not.
//   - An edge-triggered monitor emits an EVENT when the condition starts to hold
//     (rising edge), stops holding (falling edge), or either, as configured.
//
// The condition is on a scalar (an error magnitude, a distance, a force):
// "value below a threshold" or "value above a threshold", with optional
// hysteresis as two thresholds:
//   Below: becomes satisfied when value <= enter; stops when value > leave;
//          enter <= leave.
//   Above: becomes satisfied when value >= enter; stops when value < leave;
//          enter >= leave.
// enter == leave is a plain threshold (satisfied iff value <= / >= it). Between
// the two thresholds the previous state is kept, so a noisy signal near one
// threshold does not chatter. A monitor can also follow a boolean directly
// (e.g. Evaluation::satisfied), without hysteresis.
//
// A NaN value is "not satisfied" and sets MonitorState::fault for that sample.
// Model/Data: the monitor (thresholds, edges) is constant and built at setup;
// MonitorState is the per-monitor data the tick updates. Thresholds are in the
// monitored quantity's SI unit.
#pragma once

#include <cstdint>

namespace mospec::runtime {

enum class Sense : uint8_t { Below, Above };

struct MonitorThresholds {
  Sense sense = Sense::Below;
  double enter = 0.0;
  double leave = 0.0;  // = enter: no hysteresis
};

struct MonitorState {
  bool satisfied = false;    // the level before the first sample (default: not satisfied)
  bool fault = false;        // the last sample was NaN
  bool was_running = false;  // steps::monitor_reports: a motion it reports for ran last tick
};

// Which transitions an edge-triggered monitor reports.
enum class Edges : uint8_t { Rising = 1, Falling = 2, Both = 3 };
enum class Event : uint8_t { None = 0, Rising = 1, Falling = 2 };

// The shared hysteresis step: the new level for `value` given the old one.
class Condition {
 public:
  // Throws mospec::Error("invalid-monitor") naming `name` when a threshold is
  // NaN or the thresholds are the wrong way round (Below: enter > leave;
  // Above: enter < leave).
  explicit Condition(const MonitorThresholds& thresholds, const char* name = "monitor");

  const MonitorThresholds& thresholds() const { return t_; }

  // Updates state (level and fault) and returns the new level.
  bool update(MonitorState& state, double value) const noexcept {
    state.fault = value != value;
    if (state.fault) return state.satisfied = false;
    if (t_.sense == Sense::Below) {
      state.satisfied = state.satisfied ? !(value > t_.leave) : value <= t_.enter;
    } else {
      state.satisfied = state.satisfied ? !(value < t_.leave) : value >= t_.enter;
    }
    return state.satisfied;
  }

 private:
  MonitorThresholds t_;
};

class LevelMonitor {
 public:
  explicit LevelMonitor(const MonitorThresholds& thresholds, const char* name = "monitor")
      : condition_(thresholds, name) {}

  // The flag after this sample.
  bool update(MonitorState& state, double value) const noexcept {
    return condition_.update(state, value);
  }
  // Follows a boolean (no hysteresis).
  static bool update(MonitorState& state, bool satisfied) noexcept {
    state.fault = false;
    return state.satisfied = satisfied;
  }

 private:
  Condition condition_;
};

class EdgeMonitor {
 public:
  EdgeMonitor(const MonitorThresholds& thresholds, Edges edges, const char* name = "monitor")
      : condition_(thresholds, name), edges_(edges) {}

  Edges edges() const { return edges_; }

  // The event this sample produces (None when the level did not change, or the
  // change is of a kind this monitor does not report).
  Event update(MonitorState& state, double value) const noexcept {
    const bool before = state.satisfied;
    return filter(before, condition_.update(state, value));
  }
  Event update(MonitorState& state, bool satisfied) const noexcept {
    const bool before = state.satisfied;
    return filter(before, LevelMonitor::update(state, satisfied));
  }

 private:
  Event filter(bool before, bool after) const noexcept {
    if (before == after) return Event::None;
    const Event e = after ? Event::Rising : Event::Falling;
    return (static_cast<uint8_t>(edges_) & static_cast<uint8_t>(e)) != 0 ? e : Event::None;
  }

  Condition condition_;
  Edges edges_;
};

}  // namespace mospec::runtime
