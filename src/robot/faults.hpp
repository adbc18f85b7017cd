// Fault injection between a robot and its controller: corrupt a named reading
// (NaN, or a stale value that stops updating) and drop commands, for a span of
// ticks. It works on the interface structs only, so the simulator applies it
// and a hardware adapter could apply it in the same place (after reading,
// before writing).
//
// Timing is by the sample's clock tick: a fault "from tick k for n ticks"
// affects the samples (or commands) of ticks k … k+n-1; n = 0 means until
// clear(). A stale reading holds the last value seen before the fault became
// active (or, when injected late, the value of its first affected sample).
// A dropped command never reaches the robot: the robot keeps applying the last
// command it accepted, as an EtherCAT slave keeps its last process data.
//
// Setup (inject_*) may throw; the per-tick calls are noexcept and allocation-free.
#pragma once

#include <array>
#include <cstdint>
#include <string_view>
#include <utility>

#include "robot/interface.hpp"
#include "robot/sensors.hpp"

namespace mospec::robot {

enum class FaultKind : unsigned char { Nan, Stale, DropCommand };

struct Fault {
  FaultKind kind = FaultKind::Nan;
  SensorId sensor;  // unused for DropCommand
  std::uint64_t from_tick = 0;
  std::uint64_t ticks = 0;  // 0: until cleared
  // Stale: the held value and whether it has been captured.
  double held = 0.0;
  bool captured = false;

  bool active(std::uint64_t tick) const noexcept {
    return tick >= from_tick && (ticks == 0 || tick - from_tick < ticks);
  }
};

class FaultInjector {
 public:
  static constexpr int kCapacity = 16;

  // Sensor names are resolved against the robot's shape (robot/sensors.hpp);
  // without one only the base's sensors have names.
  FaultInjector() = default;
  explicit FaultInjector(RobotShape shape) : shape_(std::move(shape)) {}

  // Each throws mospec::Error: "unknown-sensor" for a bad name (listing the
  // forms), "too-many-faults" beyond kCapacity.
  void inject_nan(std::string_view sensor_name, std::uint64_t from_tick, std::uint64_t ticks = 0);
  void inject_stale(std::string_view sensor_name, std::uint64_t from_tick, std::uint64_t ticks = 0);
  void drop_commands(std::uint64_t from_tick, std::uint64_t count = 1);
  void clear() noexcept { count_ = 0; }
  int size() const noexcept { return count_; }

  // Applies the sensor faults to a fresh sample (uses state.clock.tick).
  void corrupt(MeasuredState& state) noexcept;
  // True when the command written at `tick` must be dropped.
  bool drops(std::uint64_t tick) const noexcept;

 private:
  void add(const Fault& fault);
  void add_sensor_fault(FaultKind kind, std::string_view sensor_name, std::uint64_t from_tick,
                        std::uint64_t ticks);
  RobotShape shape_;
  std::array<Fault, kCapacity> faults_{};
  int count_ = 0;
};

}  // namespace mospec::robot
