#include "robot/limits.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>

#include "support/diagnostics.hpp"

namespace mospec::robot {
namespace {

void check_limit(double limit, int index) {
  if (!std::isfinite(limit) || limit <= 0.0) {
    throw Error("invalid-limits", "the limit of " + limited_quantity_name(index) + " is " +
                                      exact_number(limit) + " " + limited_quantity_unit(index) +
                                      "; expected a finite number > 0");
  }
}

// Shortest round-trip form, for the report.
std::string shortest(double x) {
  char buffer[32];
  auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, x);
  return ec == std::errc() ? std::string(buffer, end) : exact_number(x);
}

void note(ClampRecord& r, std::uint64_t tick, double requested) noexcept {
  if (!(requested > r.limit)) return;
  if (r.ticks++ == 0) r.first_tick = tick;
  r.max_requested = std::max(r.max_requested, requested);
}

}  // namespace

CommandLimiter::CommandLimiter() noexcept {
  constexpr double kNone = std::numeric_limits<double>::infinity();
  for (auto& arm : limits_.arm_effort) arm.fill(kNone);
  limits_.wheel_torque.fill(kNone);
  limits_.platform_force = limits_.platform_moment = kNone;
  for (ClampRecord& r : records_) r.limit = kNone;
}

CommandLimiter::CommandLimiter(const CommandLimits& limits) : limits_(limits) {
  for (int k = 0; k < kArms; ++k) {
    for (int i = 0; i < kArmJoints; ++i) {
      const int index = k * kArmJoints + i;
      records_[static_cast<size_t>(index)].limit =
          limits.arm_effort[static_cast<size_t>(k)][static_cast<size_t>(i)];
    }
  }
  for (int w = 0; w < kWheels; ++w) {
    records_[static_cast<size_t>(kArmTorqueLimits + w)].limit =
        limits.wheel_torque[static_cast<size_t>(w)];
  }
  records_[kPlatformForceLimit].limit = limits.platform_force;
  records_[kPlatformMomentLimit].limit = limits.platform_moment;
  for (int q = 0; q < kLimitedQuantities; ++q)
    check_limit(records_[static_cast<size_t>(q)].limit, q);
}

void CommandLimiter::saturate(Command& command, std::uint64_t tick) noexcept {
  auto clamp = [&](double& x, int index) {
    ClampRecord& r = records_[static_cast<size_t>(index)];
    note(r, tick, std::abs(x));
    x = std::clamp(x, -r.limit, r.limit);
  };
  for (int k = 0; k < kArms; ++k) {
    for (int i = 0; i < kArmJoints; ++i) {
      clamp(command.arm_tau[static_cast<size_t>(k)][static_cast<size_t>(i)], k * kArmJoints + i);
    }
  }
  for (int w = 0; w < kWheels; ++w) {
    clamp(command.wheel_tau[static_cast<size_t>(w)], kArmTorqueLimits + w);
  }
}

void CommandLimiter::limit_platform(Command& command, std::uint64_t tick,
                                    const PlatformWrench& requested,
                                    const PlatformWrench& saturated) noexcept {
  ClampRecord& force = records_[kPlatformForceLimit];
  ClampRecord& moment = records_[kPlatformMomentLimit];
  note(force, tick, std::hypot(requested[0], requested[1]));
  note(moment, tick, std::abs(requested[2]));
  const double f = std::hypot(saturated[0], saturated[1]), m = std::abs(saturated[2]);
  double scale = 1.0;
  if (f > force.limit) scale = std::min(scale, force.limit / f);
  if (m > moment.limit) scale = std::min(scale, moment.limit / m);
  if (!(scale < 1.0)) return;
  for (double& t : command.wheel_tau) t *= scale;
}

bool CommandLimiter::any() const noexcept {
  return std::any_of(records_.begin(), records_.end(),
                     [](const ClampRecord& r) { return r.ticks > 0; });
}

void CommandLimiter::reset() noexcept {
  for (ClampRecord& r : records_) {
    r.ticks = 0;
    r.first_tick = 0;
    r.max_requested = 0.0;
  }
}

std::string limited_quantity_name(int index) {
  if (index < kArmTorqueLimits) {
    return std::string(index < kArmJoints ? "right_arm" : "left_arm") + ".tau[" +
           std::to_string(index % kArmJoints) + "]";
  }
  if (index < kPlatformForceLimit) {
    return "wheel_tau[" + std::to_string(index - kArmTorqueLimits) + "]";
  }
  return index == kPlatformForceLimit ? "platform.force" : "platform.moment";
}

const char* limited_quantity_unit(int index) {
  return index == kPlatformForceLimit ? "N" : "N·m";
}

std::string describe_clamps(std::span<const ClampRecord, kLimitedQuantities> records) {
  std::string out;
  for (int q = 0; q < kLimitedQuantities; ++q) {
    const ClampRecord& r = records[static_cast<size_t>(q)];
    if (r.ticks == 0) continue;
    const std::string unit = limited_quantity_unit(q);
    out += limited_quantity_name(q) + ": clamped in " + std::to_string(r.ticks) + " tick" +
           (r.ticks == 1 ? "" : "s") + " from tick " + std::to_string(r.first_tick) +
           ", requested up to " + shortest(r.max_requested) + " " + unit + ", limit " +
           shortest(r.limit) + " " + unit + "\n";
  }
  return out;
}

}  // namespace mospec::robot
