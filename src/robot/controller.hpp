// What a control loop runs: one tick from the measured state to the command,
// plus the per-tick log of the task's quantities. Implemented by the IR
// interpreter (src/ir/interpreter.hpp) and by every generated controller
// (src/codegen), so one loop (src/sim/run.hpp) drives either and writes the
// same log.
//
// A generated controller is built as a shared library that exports
//   extern "C" mospec::robot::Controller* mospec_create_controller();
// (kControllerFactorySymbol); the caller owns the returned object. Both sides
// must be built against the same mospec headers: kControllerAbiVersion is
// checked on load.
#pragma once

#include <cstdint>
#include <span>
#include <string>

#include "robot/interface.hpp"

namespace mospec::robot {

// 2: LogColumnInfo::kind. 3: states and commands sized by the robot (any arms and joints).
inline constexpr int kControllerAbiVersion = 3;
inline constexpr const char* kControllerFactorySymbol = "mospec_create_controller";

// How a log that keeps only every N-th tick (sim::RunOptions::log_every)
// keeps a column, so that nothing a monitor or a motion signals is lost.
enum class LogColumnKind : std::uint8_t {
  Value,  // as it is at the logged tick
  Flag,   // a monitor's flag (0/1): 1 when it was raised at any tick since the previous row
  Event,  // an event code (0: none): the bitwise OR of its codes since the previous row;
          // every tick it fires at is also reported (sim::RunResult::events)
};

struct LogColumnInfo {
  const char* name;  // "cstr-dist-rightarm-shoulder-ee.error"
  const char* unit;  // QUDT local name; "" for flags and events
  LogColumnKind kind = LogColumnKind::Value;
};

class Controller {
 public:
  virtual ~Controller() = default;
  virtual int abi_version() const noexcept { return kControllerAbiVersion; }
  // The model this controller was generated from (the app's IRI) and the
  // content hash of its IR.
  virtual const char* app() const noexcept = 0;
  // One control tick: reads `state`, writes every field of `command`.
  // Allocation-free and noexcept.
  // `state` and `command` are made for a robot whose arms fit arm_joints().
  virtual void tick(const MeasuredState& state, Command& command) noexcept = 0;
  // The robot this controller was made for, per arm index (MeasuredState::arm):
  // the joint count of each arm it drives, 0 for an arm it does not. A loop
  // checks it against the robot once, before the first tick.
  virtual std::span<const int> arm_joints() const noexcept = 0;
  // The log's columns, fixed at construction.
  virtual std::span<const LogColumnInfo> log_columns() const noexcept = 0;
  // The values after the last tick, one per column (out.size() == columns).
  virtual void log_values(std::span<double> out) const noexcept = 0;
};

using ControllerFactory = Controller* (*)();

// Empty when `controller` fits a robot of `shape` (every arm it drives exists
// with that joint count), else why not, naming the arm.
std::string check_fits(const Controller& controller, const RobotShape& shape);

}  // namespace mospec::robot
