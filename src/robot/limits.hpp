// The robot's actuation limits, enforced where every command passes before it
// reaches the hardware (or the simulator): RobotInterface::write.
//
// Limited quantities (the limiter's index order):
//   0 … 13    arm joint torques, right_arm.tau[0..6] then left_arm.tau[0..6]
//             [N·m], each |τ| <= effort limit;
//   14 … 21   hub torques wheel_tau[0..7] [N·m], each |τ| <= hub limit;
//   22        platform.force: |(f_x, f_y)| of the platform wrench the hub
//             torques produce (kelo.hpp's G F_d) [N];
//   23        platform.moment: its |m_z| about Po [N·m].
//
// Per tick: a joint or hub torque beyond its limit is saturated at the limit
// (sign kept), as the actuator's own current limit does; the platform wrench
// is bounded afterwards by scaling ALL hub torques by one factor, which keeps
// the wrench's direction (a per-wheel cut would turn it). Each quantity counts
// the ticks whose REQUESTED value exceeded its limit, the first such tick and
// the largest requested magnitude; the command that leaves the limiter is
// within every limit. Non-finite entries are the caller's business (the
// simulator zeroes them before limiting).
//
// Setup (the constructor) may throw; clamp() is noexcept and allocation-free.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string>

#include "robot/interface.hpp"

namespace mospec::robot {

inline constexpr int kArmTorqueLimits = kArms * kArmJoints;
inline constexpr int kPlatformForceLimit = kArmTorqueLimits + kWheels;
inline constexpr int kPlatformMomentLimit = kPlatformForceLimit + 1;
inline constexpr int kLimitedQuantities = kPlatformMomentLimit + 1;

struct CommandLimits {
  std::array<ArmVector, kArms> arm_effort{};  // per joint [N·m], > 0
  WheelVector wheel_torque{};                 // per hub motor [N·m], > 0
  double platform_force = 0.0;                // |(f_x, f_y)| [N], > 0
  double platform_moment = 0.0;               // |m_z| [N·m], > 0
};

// The platform wrench [f_x, f_y, m_z] (kelo.hpp's layout, seen by P) that a
// set of hub torques produces at the current pivot angles. Supplied by the
// robot, which knows its drive geometry.
using PlatformWrench = std::array<double, 3>;

struct ClampRecord {
  std::uint64_t ticks = 0;       // ticks whose requested value exceeded the limit
  std::uint64_t first_tick = 0;  // the first of them (valid when ticks > 0)
  double max_requested = 0.0;    // the largest requested magnitude
  double limit = 0.0;
};

class CommandLimiter {
 public:
  // No limits: every limit is +infinity and nothing is ever clamped.
  CommandLimiter() noexcept;
  // Throws mospec::Error("invalid-limits") naming the first limit that is not
  // a finite number > 0.
  explicit CommandLimiter(const CommandLimits& limits);

  // Clamps `command` in place for `tick`. `wrench(wheel_tau)` returns the
  // platform wrench of given hub torques; it is called twice (the requested
  // torques, then the saturated ones) and must be noexcept and allocation-free.
  template <class WrenchOf>
  void clamp(Command& command, std::uint64_t tick, WrenchOf&& wrench) noexcept {
    const PlatformWrench requested = wrench(command.wheel_tau);
    saturate(command, tick);
    limit_platform(command, tick, requested, wrench(command.wheel_tau));
  }

  const CommandLimits& limits() const noexcept { return limits_; }
  std::span<const ClampRecord, kLimitedQuantities> records() const noexcept { return records_; }
  // True when some requested value exceeded its limit.
  bool any() const noexcept;
  void reset() noexcept;

 private:
  void saturate(Command& command, std::uint64_t tick) noexcept;
  void limit_platform(Command& command, std::uint64_t tick, const PlatformWrench& requested,
                      const PlatformWrench& saturated) noexcept;

  CommandLimits limits_;
  std::array<ClampRecord, kLimitedQuantities> records_{};
};

// "right_arm.tau[3]", "wheel_tau[5]", "platform.force", "platform.moment".
std::string limited_quantity_name(int index);
// "N·m" or "N".
const char* limited_quantity_unit(int index);

// One line per clamped quantity, e.g. "right_arm.tau[0]: clamped in 9999
// ticks from tick 1, requested up to 1.2e+297 N·m, limit 39 N·m"; empty when
// nothing was clamped.
std::string describe_clamps(std::span<const ClampRecord, kLimitedQuantities> records);

}  // namespace mospec::robot
