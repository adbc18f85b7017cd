// The robot's actuation limits, enforced where every command passes before it
// reaches the hardware (or the simulator): RobotInterface::write.
//
// Limited quantities (the limiter's record order):
//   every arm joint, <arm>_arm.tau[i], arm by arm (on mospec's default robot
//             right_arm.tau[0..6] then left_arm.tau[0..6]) [N·m, or N for a
//             prismatic joint], each |τ| <= effort limit;
//   then the hub torques wheel_tau[0..2n-1] of the n drives [N·m], each |τ|
//             <= hub limit;
//   then platform.force: |(f_x, f_y)| of the platform wrench the hub
//             torques produce (kelo.hpp's G F_d) [N];
//   and platform.moment: its |m_z| about Po [N·m].
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
#include <vector>

#include "robot/interface.hpp"

namespace mospec::robot {

struct CommandLimits {
  // Per arm (the robot's shape: a name and one effort per joint), > 0 [N·m or N].
  std::vector<std::string> arm_names;
  std::vector<JointValues> arm_effort;
  // Per arm and joint: true for a prismatic joint (its limit is a force [N]);
  // empty: every joint revolute.
  std::vector<std::vector<bool>> arm_prismatic;
  JointValues wheel_torque;  // per hub motor [N·m], > 0
  double platform_force = 0.0;   // |(f_x, f_y)| [N], > 0
  double platform_moment = 0.0;  // |m_z| [N·m], > 0
};

// The platform wrench [f_x, f_y, m_z] (kelo.hpp's layout, seen by P) that a
// set of hub torques produces at the current pivot angles. Supplied by the
// robot, which knows its drive geometry.
using PlatformWrench = std::array<double, 3>;

struct ClampRecord {
  std::string quantity;  // "right_arm.tau[3]", "wheel_tau[5]", "platform.force"
  const char* unit = "N·m";
  std::uint64_t ticks = 0;       // ticks whose requested value exceeded the limit
  std::uint64_t first_tick = 0;  // the first of them (valid when ticks > 0)
  double max_requested = 0.0;    // the largest requested magnitude
  double limit = 0.0;
};

class CommandLimiter {
 public:
  // No arms and no limits: every limit is +infinity and nothing is ever clamped.
  CommandLimiter() noexcept;
  // Throws mospec::Error("invalid-limits") naming the first limit that is not
  // a finite number > 0.
  explicit CommandLimiter(const CommandLimits& limits);

  // The commands clamp() takes are made for the limits' arms (one torque per
  // effort limit).

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
  std::span<const ClampRecord> records() const noexcept { return records_; }
  // Indices into records().
  int platform_force_index() const noexcept { return static_cast<int>(records_.size()) - 2; }
  int platform_moment_index() const noexcept { return static_cast<int>(records_.size()) - 1; }
  // True when some requested value exceeded its limit.
  bool any() const noexcept;
  void reset() noexcept;

 private:
  void saturate(Command& command, std::uint64_t tick) noexcept;
  void limit_platform(Command& command, std::uint64_t tick, const PlatformWrench& requested,
                      const PlatformWrench& saturated) noexcept;

  CommandLimits limits_;
  std::vector<ClampRecord> records_;  // sized at construction
};

// One line per clamped quantity, e.g. "right_arm.tau[0]: clamped in 9999
// ticks from tick 1, requested up to 1.2e+297 N·m, limit 39 N·m"; empty when
// nothing was clamped.
std::string describe_clamps(std::span<const ClampRecord> records);

}  // namespace mospec::robot
