#include "robot/limits.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <exception>
#include <limits>

#include "support/diagnostics.hpp"

namespace mospec::robot {
namespace {

void check_limit(const ClampRecord& r) {
  if (!std::isfinite(r.limit) || r.limit <= 0.0) {
    throw Error("invalid-limits", "the limit of " + r.quantity + " is " + exact_number(r.limit) +
                                      " " + r.unit + "; expected a finite number > 0");
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
  limits_.platform_force = limits_.platform_moment = kNone;
  try {
    records_.resize(2);
  } catch (...) {
    std::terminate();  // 2 records: only an exhausted heap gets here
  }
  for (ClampRecord& r : records_) r.limit = kNone;
}

CommandLimiter::CommandLimiter(const CommandLimits& limits) : limits_(limits) {
  if (limits.arm_names.size() != limits.arm_effort.size()) {
    throw Error("invalid-limits", "the limits name " + std::to_string(limits.arm_names.size()) +
                                      " arms but give efforts for " +
                                      std::to_string(limits.arm_effort.size()));
  }
  for (size_t k = 0; k < limits.arm_effort.size(); ++k) {
    for (size_t i = 0; i < limits.arm_effort[k].size(); ++i) {
      ClampRecord r;
      r.quantity = limits.arm_names[k] + "_arm.tau[" + std::to_string(i) + "]";
      r.limit = limits.arm_effort[k][i];
      if (k < limits.arm_prismatic.size() && i < limits.arm_prismatic[k].size() &&
          limits.arm_prismatic[k][i])
        r.unit = "N";
      records_.push_back(std::move(r));
    }
  }
  for (size_t w = 0; w < limits.wheel_torque.size(); ++w) {
    ClampRecord r;
    r.quantity = "wheel_tau[" + std::to_string(w) + "]";
    r.limit = limits.wheel_torque[w];
    records_.push_back(std::move(r));
  }
  ClampRecord force;
  force.quantity = "platform.force";
  force.unit = "N";
  force.limit = limits.platform_force;
  records_.push_back(std::move(force));
  ClampRecord moment;
  moment.quantity = "platform.moment";
  moment.limit = limits.platform_moment;
  records_.push_back(std::move(moment));
  for (const ClampRecord& r : records_) check_limit(r);
}

void CommandLimiter::saturate(Command& command, std::uint64_t tick) noexcept {
  auto clamp = [&](double& x, size_t index) {
    ClampRecord& r = records_[index];
    note(r, tick, std::abs(x));
    x = std::clamp(x, -r.limit, r.limit);
  };
  size_t index = 0;
  for (size_t k = 0; k < limits_.arm_effort.size(); ++k) {
    for (size_t i = 0; i < limits_.arm_effort[k].size(); ++i) clamp(command.arm_tau[k][i], index++);
  }
  for (size_t w = 0; w < limits_.wheel_torque.size(); ++w) clamp(command.wheel_tau[w], index++);
}

void CommandLimiter::limit_platform(Command& command, std::uint64_t tick,
                                    const PlatformWrench& requested,
                                    const PlatformWrench& saturated) noexcept {
  ClampRecord& force = records_[static_cast<size_t>(platform_force_index())];
  ClampRecord& moment = records_[static_cast<size_t>(platform_moment_index())];
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

std::string describe_clamps(std::span<const ClampRecord> records) {
  std::string out;
  for (const ClampRecord& r : records) {
    if (r.ticks == 0) continue;
    const std::string unit = r.unit;
    out += r.quantity + ": clamped in " + std::to_string(r.ticks) + " tick" +
           (r.ticks == 1 ? "" : "s") + " from tick " + std::to_string(r.first_tick) +
           ", requested up to " + shortest(r.max_requested) + " " + unit + ", limit " +
           shortest(r.limit) + " " + unit + "\n";
  }
  return out;
}

}  // namespace mospec::robot
