#include "sim/run.hpp"

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <memory>
#include <ostream>

#include "sim/drivers.hpp"
#include "support/diagnostics.hpp"

namespace mospec::sim {

namespace {

void append_number(std::string& out, double x) {
  char buf[32];
  auto [p, ec] = std::to_chars(buf, buf + sizeof buf, x);
  if (ec != std::errc()) {
    out.append("nan");
    return;
  }
  out.append(buf, p);
}

// The world's columns: what the figures and the acceptance criteria read.
// base_x, base_y, base_yaw; per arm <arm>_ee_x/y/z, _fn, _fx/fy/fz;
// ground_fx/fy/mz, tau_ratio.
void append_world_columns(const robot::RobotShape& shape, std::vector<std::string>& columns) {
  for (const char* c : {"base_x", "base_y", "base_yaw"}) columns.emplace_back(c);
  for (const robot::ArmShape& arm : shape.arms) {
    for (const char* c : {"_ee_x", "_ee_y", "_ee_z", "_fn", "_fx", "_fy", "_fz"}) {
      columns.push_back(arm.name + c);
    }
  }
  for (const char* c : {"ground_fx", "ground_fy", "ground_mz", "tau_ratio"}) {
    columns.emplace_back(c);
  }
}

// Then each arm's joints (true state, no sensor faults), after the columns
// above so that their positions stay: <arm>_q0.. [rad], <arm>_qd0.. [rad/s],
// <arm>_tau0.. [N·m], the torque the actuator applied in the tick's last
// physics step (the command after the robot interface's clamp, as it acts
// after command_delay_ticks); prismatic joints in m, m/s, N.
void append_joint_columns(const robot::RobotShape& shape, std::vector<std::string>& columns) {
  for (const robot::ArmShape& arm : shape.arms) {
    for (const char* field : {"q", "qd", "tau"}) {
      for (int j = 0; j < arm.joints; ++j) {
        columns.push_back(arm.name + "_" + field + std::to_string(j));
      }
    }
  }
}

// A number as a message quotes it: the shortest form that reads back the same.
std::string shortest(double x) {
  char buffer[32];
  auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, x);
  return ec == std::errc() ? std::string(buffer, end) : exact_number(x);
}

}  // namespace

std::uint64_t tick_count(double duration, double control_period, std::uint64_t log_every) {
  auto fail = [](const std::string& message) { throw Error("invalid-duration", message); };
  if (!std::isfinite(duration) || duration <= 0) {
    fail("--duration " + shortest(duration) + ": expected a finite number of seconds > 0");
  }
  if (!std::isfinite(control_period) || control_period <= 0) {
    fail("control_period " + shortest(control_period) + ": expected a finite number > 0");
  }
  const double ticks = std::round(duration / control_period);
  if (ticks < 1) {
    fail("--duration " + shortest(duration) + " s is shorter than one control tick (" +
         shortest(control_period) + " s)");
  }
  if (ticks > static_cast<double>(kMaxTicks)) {
    fail("--duration " + shortest(duration) + " s at the world's control_period of " +
         shortest(control_period) + " s is " +
         (ticks < 1e18 ? std::to_string(static_cast<std::uint64_t>(ticks)) : shortest(ticks)) +
         " control ticks; at most 10^7 are simulated (shorten --duration or lengthen "
         "control_period)");
  }
  const auto n = static_cast<std::uint64_t>(ticks);
  if (log_every > 0 && (n + log_every - 1) / log_every > kMaxLogRows) {
    fail("--duration " + shortest(duration) + " s is " + std::to_string(n) +
         " control ticks; logging every " + std::to_string(log_every) + " would keep " +
         std::to_string((n + log_every - 1) / log_every) +
         " rows in memory, at most 10^6 are kept (raise --log-every)");
  }
  return n;
}

RunResult run(World& world, robot::Controller& controller, const RunOptions& options) {
  const WorldConfig& config = world.config();
  const auto every = static_cast<std::uint64_t>(options.log_every < 1 ? 1 : options.log_every);
  const std::uint64_t ticks = tick_count(options.duration, config.control_period, every);
  if (const std::string misfit = robot::check_fits(controller, world.shape()); !misfit.empty()) {
    throw Error("robot-mismatch", misfit + "; the controller was made for another robot");
  }
  RunResult r;
  const auto columns = controller.log_columns();
  r.columns.push_back("t");
  for (const robot::LogColumnInfo& c : columns) r.columns.emplace_back(c.name);
  const robot::RobotShape& shape = world.shape();
  const size_t arms = shape.arms.size();
  append_world_columns(shape, r.columns);
  append_joint_columns(shape, r.columns);
  for (size_t i = 0; i < r.columns.size(); ++i) {
    if (i) r.csv.push_back(',');
    r.csv.append(r.columns[i]);
  }
  r.csv.push_back('\n');
  std::vector<double> values(columns.size(), 0.0);
  std::vector<double> row(r.columns.size(), 0.0);
  // Latched columns (flags and events): what they signalled since the last row.
  std::vector<size_t> latched;
  for (size_t i = 0; i < columns.size(); ++i) {
    if (columns[i].kind != robot::LogColumnKind::Value) latched.push_back(i);
  }
  std::vector<unsigned> latch(columns.size(), 0);
  r.flag_ticks.assign(columns.size(), 0);
  robot::MeasuredState state = world.make_state(), truth = world.make_state();
  robot::Command command = world.make_command(), idle_command = world.make_command();
  std::unique_ptr<GravityCompensation> hold;
  std::vector<bool> idle(arms, false);
  for (size_t a = 0; a < arms && a < options.idle.size(); ++a) idle[a] = options.idle[a];
  const bool any_idle = std::find(idle.begin(), idle.end(), true) != idle.end();
  if (any_idle) {
    std::vector<runtime::Pose> X_PB;
    for (const ArmSetup& a : config.arms) X_PB.push_back(a.X_PB);
    hold = std::make_unique<GravityCompensation>(world.arms(), X_PB);
  }
  std::vector<std::vector<std::size_t>> pushing_columns(arms);
  for (size_t a = 0; a < arms && a < options.pushing.size(); ++a) {
    pushing_columns[a] = options.pushing[a];
  }
  if (options.pushing.size() > arms || options.idle.size() > arms) {
    throw Error("invalid-run-options", "the run options name more arms than the world has");
  }
  r.arms.reserve(arms);
  for (const robot::ArmShape& a : shape.arms) r.arms.push_back(a.name);
  r.peak_torque_ratio.assign(arms, 0.0);
  r.peak_torque_tick.assign(arms, 0);
  r.contact.assign(arms, ContactRecord{});
  for (const std::size_t i : options.watch) {
    if (i >= columns.size())
      throw Error("invalid-run-options", "a watched log column is out of range");
  }
  for (const auto& arm : pushing_columns) {
    for (const std::size_t i : arm) {
      if (i >= columns.size())
        throw Error("invalid-run-options", "a pushing log column is out of range");
    }
  }
  for (const RunOptions::Snapshot& s : options.snapshots) {
    bool fits = s.at < columns.size();
    for (const std::size_t i : s.columns) fits = fits && i < columns.size();
    if (!fits) throw Error("invalid-run-options", "a snapshot's log column is out of range");
    Snapshot taken;
    taken.values.assign(s.columns.size(), 0.0);
    r.snapshots.push_back(std::move(taken));
  }
  for (const RunOptions::Held& h : options.held) {
    if (h.flag >= columns.size() || h.during >= columns.size())
      throw Error("invalid-run-options", "a held log column is out of range");
  }
  r.held.assign(options.held.size(), HeldRecord{});
  std::vector<bool> lapsing(options.held.size(), false);
  std::vector<double> watched(options.watch.size(), 0.0);
  std::vector<bool> pushing(arms, false);
  std::vector<bool> touched(arms, false);    // contact since the force was last not commanded
  std::vector<std::uint64_t> loss(arms, 0);  // ticks of the current loss
  bool any_pushing = false;
  for (size_t a = 0; a < arms; ++a) {
    r.contact[a].observed = !pushing_columns[a].empty();
    any_pushing = any_pushing || r.contact[a].observed;
  }
  std::vector<const ArmActuation*> actuation;
  for (size_t a = 0; a < arms; ++a) actuation.push_back(&arm_actuation(config, a));
  const bool read_values = !latched.empty() || !options.watch.empty() || any_pushing ||
                           !options.snapshots.empty() || !options.held.empty();
  const auto start = std::chrono::steady_clock::now();
  if (options.observer) options.observer->observe(world);
  for (std::uint64_t k = 0; k < ticks; ++k) {
    world.read(state);
    bool beyond = false;
    for (size_t a = 0; a < state.arm.size(); ++a) {
      const auto& arm = state.arm[a];
      for (size_t j = 0; j < arm.q.size(); ++j) {
        const double excess =
            std::max(actuation[a]->lower[j] - arm.q[j], arm.q[j] - actuation[a]->upper[j]);
        if (!(excess > 0.0)) continue;
        r.joint_limit_exceeded = true;
        if (!beyond) {
          beyond = true;
          if (r.joint_limit.ticks++ == 0) r.joint_limit.first_tick = k;
        }
        if (excess > r.joint_limit.max_excess) {
          r.joint_limit.max_excess = excess;
          r.joint_limit.arm = static_cast<int>(a);
          r.joint_limit.joint = static_cast<int>(j);
        }
      }
    }
    controller.tick(state, command);
    if (read_values) {
      controller.log_values(values);
      for (size_t w = 0; w < options.watch.size(); ++w) {
        const double v = values[options.watch[w]];
        const double was = watched[w];
        if (v == was || (std::isnan(v) && std::isnan(was))) continue;
        watched[w] = v;
        if (r.changes.size() < kMaxRunEvents) {
          r.changes.push_back({k, state.clock.t, options.watch[w] + 1, v});
        } else {
          ++r.changes_dropped;
        }
      }
      // Snapshots and held records: preallocated above, nothing allocated here.
      for (size_t n = 0; n < options.snapshots.size(); ++n) {
        const RunOptions::Snapshot& s = options.snapshots[n];
        Snapshot& taken = r.snapshots[n];
        if (taken.taken || !(values[s.at] != 0.0)) continue;
        taken.taken = true;
        taken.tick = k;
        taken.time = state.clock.t;
        for (size_t i = 0; i < s.columns.size(); ++i) taken.values[i] = values[s.columns[i]];
      }
      for (size_t n = 0; n < options.held.size(); ++n) {
        if (!(values[options.held[n].during] != 0.0)) {
          lapsing[n] = false;
          continue;
        }
        HeldRecord& h = r.held[n];
        const bool holds = values[options.held[n].flag] != 0.0;
        ++h.during_ticks;
        h.last = holds;
        if (holds) {
          ++h.held_ticks;
          if (!h.ever_held) h.first_held_tick = k;
          h.ever_held = true;
          lapsing[n] = false;
          continue;
        }
        if (!h.ever_held) continue;
        if (!lapsing[n] && h.lapses++ == 0) h.first_lapse_tick = k;
        lapsing[n] = true;
        ++h.lapsed_ticks;
      }
      for (size_t a = 0; a < arms; ++a) {
        pushing[a] = false;
        for (size_t i : pushing_columns[a]) pushing[a] = pushing[a] || values[i] != 0.0;
      }
      for (size_t i : latched) {
        const double v = values[i];
        if (!(v != 0.0)) continue;  // 0 (NaN never: flags and events are codes)
        const bool event = columns[i].kind == robot::LogColumnKind::Event;
        const auto code = event && v > 0.0 && v < 256.0 ? static_cast<unsigned>(v) : 1u;
        latch[i] |= code;
        if (!event) {
          ++r.flag_ticks[i];
          continue;
        }
        if (r.events.size() < kMaxRunEvents) {
          r.events.push_back({k, state.clock.t, i + 1, static_cast<int>(code)});
        } else {
          ++r.events_dropped;
        }
      }
    }
    if (any_idle) {
      hold->compute(state, idle_command);
      for (size_t a = 0; a < command.arm_tau.size(); ++a) {
        if (idle[a]) command.arm_tau[a] = idle_command.arm_tau[a];
      }
    }
    double tau_ratio = 0.0;
    bool finite_command = true;
    for (size_t a = 0; a < command.arm_tau.size(); ++a) {
      const auto& arm = command.arm_tau[a];
      double arm_ratio = 0.0;
      for (size_t j = 0; j < arm.size(); ++j) {
        finite_command = finite_command && std::isfinite(arm[j]);
        arm_ratio = std::max(arm_ratio, std::abs(arm[j]) / actuation[a]->effort_limit[j]);
      }
      if (arm_ratio > r.peak_torque_ratio[a]) {
        r.peak_torque_ratio[a] = arm_ratio;
        r.peak_torque_tick[a] = k;
      }
      tau_ratio = std::max(tau_ratio, arm_ratio);
    }
    for (double w : command.wheel_tau) finite_command = finite_command && std::isfinite(w);
    if (!finite_command) {
      if (r.non_finite_ticks++ == 0) r.first_non_finite_tick = k;
      r.non_finite = true;
    }
    r.max_torque_ratio = std::max(r.max_torque_ratio, tau_ratio);
    world.write(command);
    world.step();
    // The contacts of the step the command acted in.
    for (size_t a = 0; a < arms; ++a) {
      ContactRecord& c = r.contact[a];
      if (!pushing[a]) {
        touched[a] = false;
        loss[a] = 0;
        continue;
      }
      ++c.commanded_ticks;
      if (world.mount_active() || world.contact(static_cast<int>(a)).contacts > 0) {
        ++c.touching_ticks;
        touched[a] = true;
        loss[a] = 0;
        continue;
      }
      if (!touched[a]) continue;  // still reaching for it
      if (loss[a]++ == 0 && c.losses++ == 0) {
        c.first_loss_tick = k;
        c.first_loss_time = state.clock.t;
      }
      ++c.lost_ticks;
      c.longest_loss = std::max(c.longest_loss, loss[a]);
    }
    if (options.observer) options.observer->observe(world);
    if (k % every != 0 && k + 1 != ticks) continue;
    controller.log_values(values);
    for (size_t i : latched) {
      values[i] = static_cast<double>(latch[i]);
      latch[i] = 0;
    }
    size_t c = 0;
    row[c++] = world.time();
    bool finite_row = true;
    for (double v : values) {
      finite_row = finite_row && std::isfinite(v);
      row[c++] = v;
    }
    r.non_finite_values += finite_row ? 0 : 1;
    const runtime::Pose X_WP = world.X_WP();
    row[c++] = X_WP.p.x();
    row[c++] = X_WP.p.y();
    row[c++] = std::atan2(X_WP.R(1, 0), X_WP.R(0, 0));
    for (size_t arm = 0; arm < arms; ++arm) {
      const int a = static_cast<int>(arm);
      const runtime::Vec3 p = world.p_WoE_W(a);
      const ArmContact contact = world.contact(a);
      row[c++] = p.x();
      row[c++] = p.y();
      row[c++] = p.z();
      row[c++] = contact.normal_force;
      row[c++] = contact.f_E_W.x();
      row[c++] = contact.f_E_W.y();
      row[c++] = contact.f_E_W.z();
    }
    const runtime::Vec3 ground = world.ground_wrench_P();
    row[c++] = ground.x();
    row[c++] = ground.y();
    row[c++] = ground.z();
    row[c++] = tau_ratio;
    world.read_true(truth);
    for (const robot::ArmMeasurement& arm : truth.arm) {
      for (double x : arm.q) row[c++] = x;
      for (double x : arm.qd) row[c++] = x;
      for (double x : arm.tau) row[c++] = x;
    }
    for (size_t i = 0; i < row.size(); ++i) {
      if (i) r.csv.push_back(',');
      append_number(r.csv, row[i]);
    }
    r.csv.push_back('\n');
  }
  r.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  r.ticks = ticks;
  r.simulated = world.time();
  r.last_row = row;
  r.torque_limit_exceeded = r.max_torque_ratio > 1.0;
  r.instabilities = world.instabilities();
  const auto clamps = world.limiter().records();
  r.clamps.assign(clamps.begin(), clamps.end());
  r.clamped = world.limiter().any();
  return r;
}

bool report_clamps(std::ostream& out, std::span<const robot::ClampRecord> clamps) {
  const std::string lines = robot::describe_clamps(clamps);
  if (lines.empty()) return false;
  out << "mospec: warning: commands beyond the robot's limits were clamped at the robot "
         "interface (the controller asks for more than the actuators can give):\n";
  size_t start = 0;
  while (start < lines.size()) {
    const size_t end = lines.find('\n', start);
    out << "  " << lines.substr(start, end - start) << '\n';
    start = end + 1;
  }
  return true;
}

double last_value(const RunResult& result, const std::string& column) {
  for (size_t i = 0; i < result.columns.size() && i < result.last_row.size(); ++i) {
    if (result.columns[i] == column) return result.last_row[i];
  }
  return std::nan("");
}

}  // namespace mospec::sim
