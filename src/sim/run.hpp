// One loop for every controller: the simulated robot read -> controller tick
// -> write -> step, logging the controller's columns (its constraints,
// monitors, motions and PID outputs) next to the world's ground truth.
// The interpreter and generated controllers run through the same loop, so
// their logs compare byte for byte.
#pragma once

#include <array>
#include <cstdint>
#include <iosfwd>
#include <span>
#include <string>
#include <vector>

#include "robot/controller.hpp"
#include "runtime/chain.hpp"
#include "sim/world.hpp"

namespace mospec::sim {

// How long a run may be: at most 10^7 control ticks (2.8 h of simulated time
// at 1 ms), and at most 10^6 logged rows (the log is kept in memory until the
// run ends: about 2 GB at 10^6 rows of 100 columns).
inline constexpr std::uint64_t kMaxTicks = 10'000'000;
inline constexpr std::uint64_t kMaxLogRows = 1'000'000;

// The control ticks of `duration` [s] at `control_period` [s] (rounded to
// the nearest tick). Throws mospec::Error("invalid-duration") when the
// duration is not a finite number > 0, when the period is not finite and
// > 0, when the duration is shorter than one tick, or when the run would take
// more than kMaxTicks ticks or, logging every `log_every`-th tick (0: no log),
// more than kMaxLogRows rows; the message names --duration, the world's
// control_period and --log-every.
std::uint64_t tick_count(double duration, double control_period, std::uint64_t log_every);

// Sees the world between control ticks: once before the first tick and once
// after every step, never inside one (e.g. to render a video). What it does
// costs wall time only: it must not change the world, and the loop's per-tick
// path stays allocation-free without one.
class StepObserver {
 public:
  virtual ~StepObserver() = default;
  virtual void observe(const World& world) = 0;
};

struct RunOptions {
  double duration = 10.0;  // [s] simulated
  int log_every = 1;       // log every N-th tick (and the last)
  // Per arm of the world: an arm the controller does not drive (e.g. the left
  // arm in a right-arm task) is held by the robot side with gravity
  // compensation instead of being sent the controller's zeros. Empty: none.
  std::vector<bool> idle;
  // Controller log columns (indices into Controller::log_columns()) whose
  // every change is recorded, tick by tick (RunResult::changes): e.g. a
  // motion's running flag and its guards' satisfied flags.
  std::vector<std::size_t> watch;
  // Per arm of the world, controller log columns whose value, when not 0,
  // means the controller commands a force on that arm's end effector
  // (RunResult::contact). Empty, or shorter than the arms: none.
  std::vector<std::vector<std::size_t>> pushing;
  // Log columns kept as they were after the first tick in which the event
  // column `at` was not 0 (e.g. a motion's goals when it ended:
  // RunResult::snapshots, one per entry).
  struct Snapshot {
    std::size_t at = 0;
    std::vector<std::size_t> columns;
  };
  std::vector<Snapshot> snapshots;
  // Whether the flag column `flag` held in the ticks after which the flag
  // column `during` was set (a motion's `while` while the motion ran:
  // RunResult::held, one per entry).
  struct Held {
    std::size_t flag = 0, during = 0;
  };
  std::vector<Held> held;
  StepObserver* observer = nullptr;  // not owned; none when null
};

// RunOptions::snapshots' values.
struct Snapshot {
  bool taken = false;          // the event column was not 0 after some tick
  std::uint64_t tick = 0;      // the first such tick
  double time = 0.0;           // the controller's clock at that tick [s]
  std::vector<double> values;  // the columns' values after it, in RunOptions' order
};

// How a flag held while another was set (RunOptions::held). A lapse is a run
// of ticks in which it did not hold after it first held (within the ticks
// `during` was set).
struct HeldRecord {
  std::uint64_t during_ticks = 0;  // ticks with `during` set
  std::uint64_t held_ticks = 0;    // ... and the flag up
  bool ever_held = false;
  std::uint64_t first_held_tick = 0;
  std::uint64_t lapses = 0;        // lapses, as above
  std::uint64_t lapsed_ticks = 0;  // ticks within them
  std::uint64_t first_lapse_tick = 0;
  bool last = false;  // the flag in the last tick `during` was set
};

// One event a controller signalled: a column of kind robot::LogColumnKind::Event
// that was not 0 after a tick.
struct RunEvent {
  std::uint64_t tick = 0;  // the control tick (0-based)
  double time = 0.0;       // the controller's clock at that tick [s]
  std::size_t column = 0;  // index into RunResult::columns
  int code = 0;            // the column's value: an edge (1 rising, 2 falling) or how a
                           // motion ended (1 an `until` held, 2 a `while` was violated)
};
// A watched column's new value (RunOptions::watch).
struct RunChange {
  std::uint64_t tick = 0;  // the control tick (0-based) after which it had the value
  double time = 0.0;       // the controller's clock at that tick [s]
  std::size_t column = 0;  // index into RunResult::columns
  double value = 0.0;      // the value it changed to (every column starts at 0)
};

// Whether an arm's end effector kept its contact while the controller commanded
// a force on it (RunOptions::pushing). The end effector is in contact in a tick
// when it touches the table (ArmContact::contacts > 0) or the SC2 mount holds
// it. A force is commanded in a tick when one of the arm's pushing columns is
// not 0 after the controller's tick. A loss is a run of ticks, each with a
// commanded force and no contact, that follows a tick with both in the same
// stretch of commanded ticks (reaching for the contact first is not a loss).
struct ContactRecord {
  bool observed = false;              // the arm has pushing columns
  std::uint64_t commanded_ticks = 0;  // ticks with a commanded force
  std::uint64_t touching_ticks = 0;   // ... and contact
  std::uint64_t losses = 0;           // losses, as above
  std::uint64_t lost_ticks = 0;       // ticks within them
  std::uint64_t first_loss_tick = 0;  // the first tick of the first loss
  double first_loss_time = 0.0;       // its clock [s]
  std::uint64_t longest_loss = 0;     // the longest loss [ticks]
};

// How far a measured joint position went beyond its limits.
struct JointLimitRecord {
  std::uint64_t ticks = 0;       // ticks with some measured joint beyond its limits
  std::uint64_t first_tick = 0;  // the first of them
  int arm = 0, joint = 0;        // the joint furthest beyond (the world's arm index)
  double max_excess = 0.0;       // by how much [rad]
};

// At most this many events are kept (a monitor chattering every tick of a long
// run); RunResult::events_dropped counts the rest.
inline constexpr std::size_t kMaxRunEvents = 100'000;

struct RunResult {
  std::uint64_t ticks = 0;
  double simulated = 0.0;  // [s]
  double wall = 0.0;       // [s]
  std::string csv;         // header + rows; numbers in shortest round-trip form
  std::vector<std::string> columns;
  std::vector<double> last_row;  // the final logged values, by column
  // Every event, in tick order, then column order. In the log, a flag or event
  // column (robot::LogColumnKind) is latched: a row holds what was signalled at
  // any tick since the previous row, so decimation loses nothing.
  std::vector<RunEvent> events;
  std::uint64_t events_dropped = 0;
  // Every change of a watched column, in tick order, then column order; at
  // most kMaxRunEvents (changes_dropped counts the rest).
  std::vector<RunChange> changes;
  std::uint64_t changes_dropped = 0;
  // Per controller log column: in how many ticks a flag column was raised (0
  // for the other kinds); e.g. an arm solve's `.degraded`.
  std::vector<std::uint64_t> flag_ticks;
  // Safety summary over the whole run.
  bool non_finite = false;             // a command was NaN/inf (never sent: the world zeroes it)
  std::uint64_t non_finite_ticks = 0;  // ticks with such a command
  std::uint64_t first_non_finite_tick = 0;
  std::uint64_t non_finite_values = 0;  // logged rows with a NaN/inf value (e.g. from a NaN sensor)
  std::uint64_t dropped_commands = 0;   // ticks whose command the world rejected or dropped
  double max_torque_ratio = 0.0;        // max |tau_i| / effort_limit_i over arms and ticks,
                                        // as requested (before the clamp)
  bool torque_limit_exceeded = false;   // max_torque_ratio > 1
  // The world's arms (their names), and per arm the largest such ratio and its first tick.
  std::vector<std::string> arms;
  std::vector<double> peak_torque_ratio;
  std::vector<std::uint64_t> peak_torque_tick;
  // What the robot interface clamped (World::limiter()), per limited quantity
  // in robot/limits.hpp's order; `clamped` when any entry has ticks > 0.
  std::vector<robot::ClampRecord> clamps;
  bool clamped = false;
  bool joint_limit_exceeded = false;  // a measured joint position left its limits
  JointLimitRecord joint_limit;
  std::vector<ContactRecord> contact;  // per arm
  std::vector<Snapshot> snapshots;     // per RunOptions::snapshots entry
  std::vector<HeldRecord> held;        // per RunOptions::held entry
  int instabilities = 0;               // MuJoCo warnings (untrustworthy when > 0)
};

// Runs `controller` against `world` from its current state. The per-tick path
// allocates nothing except the log text and the events. Throws as tick_count() for a bad
// duration or log interval (before the first tick).
RunResult run(World& world, robot::Controller& controller, const RunOptions& options);

// Writes the console warning about clamped commands — "mospec: warning: ..."
// and one line per clamped quantity (robot::describe_clamps) — and returns
// true, or writes nothing and returns false when nothing was clamped.
bool report_clamps(std::ostream& out, std::span<const robot::ClampRecord> clamps);

// The value of a named column in the last row (NaN when absent).
double last_value(const RunResult& result, const std::string& column);

}  // namespace mospec::sim
