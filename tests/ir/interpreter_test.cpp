// The interpreter executes the IR with the semantics the generated code
// mirrors: guarded motions start on their `when` and end on any `until`,
// controllers run only while their motion runs, monitors raise flags and
// events; and a tick allocates nothing.
#include "ir/interpreter.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "../codegen/programs.hpp"
#include "alloc_counter.hpp"  // NOLINT(llvm-include-order): after every other header
#include "app/app.hpp"
#include "default_robot_ports.hpp"
#include "ir/lower.hpp"
#include "robot/limits.hpp"
#include "runtime/kelo.hpp"
#include "sim/config.hpp"
#include "sim/world.hpp"

namespace mospec::ir {
namespace {

Program lower_app(const std::string& app, const std::string& root) {
  app::LoadOptions options;
  options.root = root;
  app::LoadedModel model = app::load({app}, options);
  LowerOptions lower_options;
  lower_options.ports = testing::default_robot_ports();
  return lower(model, lower_options);
}

Program tiny() {
  const std::string dir = std::string(MOSPEC_SOURCE_DIR) + "/tests/ir/data";
  return lower_app(dir + "/tiny.json", dir);
}

int column(const Interpreter& in, const std::string& name) {
  const auto cols = in.log_columns();
  for (size_t i = 0; i < cols.size(); ++i) {
    if (name == cols[i].name) return static_cast<int>(i);
  }
  ADD_FAILURE() << "no log column " << name;
  return 0;
}

// Tick k of a 1 kHz run (dt 0 on the first tick), then the log row.
void tick_at(Interpreter& in, int k, robot::MeasuredState& state, robot::Command& command,
             std::vector<double>& values) {
  state.clock.tick = static_cast<std::uint64_t>(k);
  state.clock.t = 0.001 * k;
  state.clock.dt = k == 0 ? 0.0 : 0.001;
  in.tick(state, command);
  in.log_values(values);
}

TEST(Interpreter, GuardedMotionRunsBetweenItsWhenAndUntil) {
  Interpreter in(tiny());
  const int running = column(in, "motion.running");
  const int effort = column(in, "ctrl-track.output");
  const int started = column(in, "mon-started.event");
  const int done = column(in, "mon-done.flag");
  robot::MeasuredState state = robot::make_state(robot::gen3_pair_shape());
  robot::Command command = robot::make_command(robot::gen3_pair_shape());
  std::vector<double> values(in.log_columns().size());
  int events = 0;
  for (int k = 0; k <= 3000; ++k) {
    tick_at(in, k, state, command, values);
    const double t = state.clock.t;
    const bool should_run = t >= 0.5 - 1e-12 && t < 2.0 - 1e-12;
    ASSERT_EQ(values[static_cast<size_t>(running)] == 1.0, should_run) << "t = " << t;
    if (!should_run) {
      ASSERT_EQ(values[static_cast<size_t>(effort)], 0.0) << "t = " << t;
    }
    if (should_run && t > 0.6 && t < 0.9) {
      ASSERT_GT(values[static_cast<size_t>(effort)], 0.0) << "error 1 - t > 0 pushes up; t = " << t;
    }
    if (values[static_cast<size_t>(started)] == 1.0) {
      ++events;
      EXPECT_NEAR(t, 0.5, 1e-9) << "the listed edge monitor fires in the motion's first tick";
    }
    // No handler lists mon-done: it watches the whole run, motion or not.
    ASSERT_EQ(values[static_cast<size_t>(done)] == 1.0, t >= 2.0 - 1e-12) << "t = " << t;
  }
  EXPECT_EQ(events, 1) << "the edge monitor fires once, when the start condition becomes true";
}

// tests/ir/data/controllers: a damping controller and an impedance controller
// gated by a motion (0.5 s <= t < 2 s), and an angular damper gated by a
// motion that runs from the start for 10^6 s.
TEST(Interpreter, DampingAndImpedanceControllersFromAModel) {
  const std::string dir = std::string(MOSPEC_SOURCE_DIR) + "/tests/ir/data";
  Interpreter in(lower_app(dir + "/controllers.json", dir));
  const int damper = column(in, "damper.output");
  const int angular = column(in, "damper-ang.output");
  const int spring = column(in, "spring.output");
  const int error = column(in, "cstr-x.error");
  robot::MeasuredState state = robot::make_state(robot::gen3_pair_shape());
  robot::Command command = robot::make_command(robot::gen3_pair_shape());
  std::vector<double> values(in.log_columns().size());
  for (int k = 0; k <= 2500; ++k) {
    tick_at(in, k, state, command, values);
    const double t = state.clock.t;
    const bool running = t >= 0.5 - 1e-12 && t < 2.0 - 1e-12;
    const auto at = [&](int c) { return values[static_cast<size_t>(c)]; };
    // v = 0.1 m/s, v_max = 0.2 m/s, F_max = 10 N: -(10 / 0.2) 0.1 = -5 N.
    ASSERT_EQ(at(damper), running ? -5.0 : 0.0) << "t = " << t;
    // w = 0.75 rad/s beyond w_max = 0.5 rad/s: saturated at -2 N m, always.
    ASSERT_EQ(at(angular), -2.0) << "t = " << t;
    // A constant error: the damper of the impedance adds nothing; K = 300 N/m.
    ASSERT_NE(at(error), 0.0);
    ASSERT_EQ(at(spring), running ? 300.0 * at(error) : 0.0) << "t = " << t;
  }
}

TEST(Interpreter, RejectsAProgramThatDoesNotVerify) {
  Program p = tiny();
  std::swap(p.steps.front(), p.steps.back());  // the controller before its inputs
  EXPECT_THROW(Interpreter{p}, Error);
}

// The verifier's checks of controller steps, against the registry's kind.
TEST(Verifier, ChecksControllerStepsAgainstTheirKind) {
  const std::string dir = std::string(MOSPEC_SOURCE_DIR) + "/tests/ir/data";
  const Program good = lower_app(dir + "/controllers.json", dir);
  EXPECT_TRUE(check(good).empty());
  const auto problems = [&](const auto& edit) {
    Program p = good;
    for (Step& st : p.steps) {
      if (st.kind == StepKind::Controller && kind_name(st) == std::string_view("damping")) {
        edit(st);
        break;
      }
    }
    std::string all;
    for (const Diagnostic& d : check(p)) all.append(d.message).append("\n");
    return all;
  };
  EXPECT_NE(problems([](Step& st) {
              st.parameters.pop_back();
            }).find("has 1 parameters; a damping controller has 2"),
            std::string::npos);
  EXPECT_NE(problems([](Step& st) {
              st.state = 0;
            }).find("a damping controller keeps no state (expected -1)"),
            std::string::npos);
  EXPECT_NE(problems([](Step& st) {
              st.controller = 99;
            }).find("names controller kind 99, which does not exist"),
            std::string::npos);
  EXPECT_NE(problems([](Step& st) { st.in.push_back(st.in.front()); }).find("inputs"),
            std::string::npos);
}

// A tick of the right-arm scenario against a robot standing in its initial
// pose: arm kinematics, views, operators, evaluators, monitors, controllers,
// the ACHD solve. Deterministic, finite, allocation-free.
robot::MeasuredState standing_robot() {
  const sim::WorldConfig world = sim::default_world();
  robot::MeasuredState state = robot::make_state(robot::gen3_pair_shape());
  for (size_t arm = 0; arm < state.arm.size(); ++arm) state.arm[arm].q = world.arms[arm].q0;
  return state;
}

void advance(robot::MeasuredState& state, int k) {
  state.clock.tick = static_cast<std::uint64_t>(k);
  state.clock.t = 0.001 * k;
  state.clock.dt = k == 0 ? 0.0 : 0.001;
  state.arm[0].qd[0] = 0.01 * std::sin(0.01 * k);  // some motion
}

Program sc0a() {
  return lower_app(std::string(MOSPEC_SOURCE_DIR) + "/models/sc0a.json", MOSPEC_SOURCE_DIR);
}

// Lowering runs its passes in the declared order, hands each intermediate
// program to after_pass, and every one of them passes ir::check.
TEST(Lowering, RunsEveryPassInOrderEachProgramChecked) {
  app::LoadOptions options;
  options.root = MOSPEC_SOURCE_DIR;
  app::LoadedModel model =
      app::load({std::string(MOSPEC_SOURCE_DIR) + "/models/sc0a.json"}, options);
  LowerOptions lower_options;
  lower_options.ports = testing::default_robot_ports();
  std::vector<std::string> seen;
  size_t steps_before_schedule = 0;
  lower_options.after_pass = [&](std::string_view pass, const Program& p) {
    seen.emplace_back(pass);
    const bool ordered = pass == "schedule" || pass == "log";
    EXPECT_TRUE(check(p, &model.files(), ordered ? Stage::Scheduled : Stage::Unscheduled).empty())
        << pass;
    if (pass == "producers") steps_before_schedule = p.steps.size();
    if (pass == "schedule") {
      EXPECT_EQ(p.steps.size(), steps_before_schedule);
    }
  };
  const Program p = lower(model, lower_options);
  const auto passes = lowering_passes();
  EXPECT_EQ(seen, std::vector<std::string>(passes.begin(), passes.end()));
  EXPECT_GT(steps_before_schedule, 0u);
  EXPECT_FALSE(p.log.empty());
}

TEST(Interpreter, Sc0aTickIsDeterministic) {
  const Program program = sc0a();
  Interpreter a(program), b(program);
  robot::MeasuredState state = standing_robot();
  robot::Command ca = robot::make_command(robot::gen3_pair_shape()), cb = ca;
  std::vector<double> va(a.log_columns().size()), vb(va.size());
  for (int k = 0; k < 2000; ++k) {
    advance(state, k);
    a.tick(state, ca);
    b.tick(state, cb);
    a.log_values(va);
    b.log_values(vb);
    ASSERT_EQ(va, vb);
    ASSERT_EQ(ca.arm_tau, cb.arm_tau);
    for (double tau : ca.arm_tau[0]) ASSERT_TRUE(std::isfinite(tau));
  }
  bool any_torque = false;
  for (double tau : ca.arm_tau[0]) any_torque = any_torque || tau != 0.0;
  EXPECT_TRUE(any_torque) << "the right arm is commanded";
  EXPECT_EQ(ca.arm_tau[1], robot::JointValues(7, 0.0)) << "sc0a does not drive the left arm";
}

TEST(Interpreter, Sc0aTickAllocatesNothing) {
#ifdef MOSPEC_NO_ALLOC_COUNTING
  GTEST_SKIP() << "allocation counting is off under AddressSanitizer (it owns malloc)";
#else
  Interpreter in(sc0a());
  robot::MeasuredState state = standing_robot();
  robot::Command command = robot::make_command(robot::gen3_pair_shape());
  std::vector<double> values(in.log_columns().size());
  // The robot interface's clamp, as the simulator applies it after the tick.
  const sim::WorldConfig world = sim::default_world();
  robot::CommandLimits limits;
  limits.arm_names = {"right", "left"};
  limits.arm_effort = {world.actuation.effort_limit, world.actuation.effort_limit};
  limits.wheel_torque.assign(8, world.platform.wheel_torque_limit);
  limits.platform_force = 1000.0;
  limits.platform_moment = 300.0;
  robot::CommandLimiter limiter(limits);
  const runtime::KeloModel kelo(::mospec::testing::paper_base());
  long allocations = 0;
  for (int k = 0; k < 10000; ++k) {
    advance(state, k);
    allocations += alloc_counter::during([&] {
      in.tick(state, command);
      in.log_values(values);
      if (k % 100 < 10) command.arm_tau[0][0] = 1e300;  // beyond the limit
      limiter.clamp(command, state.clock.tick, [&](std::span<const double> tau) noexcept {
        return sim::hub_wrench(kelo, state.pivot_q, tau);
      });
    });
  }
  EXPECT_EQ(allocations, 0);
  EXPECT_TRUE(limiter.any()) << "the clamp was exercised";
#endif
}

// Every operator kind of the registry: the interpreter's call of its kernel
// allocates nothing either.
TEST(Interpreter, EveryOperatorKindTicksWithoutAllocating) {
#ifdef MOSPEC_NO_ALLOC_COUNTING
  GTEST_SKIP() << "allocation counting is off under AddressSanitizer (it owns malloc)";
#else
  SourceFiles files;
  Interpreter in(codegen::testing::operators_program(files));
  robot::Command command = robot::make_command(robot::gen3_pair_shape());
  std::vector<double> values(in.log_columns().size());
  long allocations = 0;
  for (std::uint64_t k = 0; k < 1000; ++k) {
    const robot::MeasuredState state = codegen::testing::measurement(k);
    allocations += alloc_counter::during([&] {
      in.tick(state, command);
      in.log_values(values);
    });
  }
  EXPECT_EQ(allocations, 0);
  for (double v : values) EXPECT_TRUE(std::isfinite(v));
#endif
}

}  // namespace
}  // namespace mospec::ir

namespace mospec::ir {
namespace {

// AnyOf (a controller listed by the handlers of several motions): its flag is
// on while any input is, and the controller it gates runs only then.
TEST(Interpreter, AnyOfIsOnWhileAnyOfItsFlagsIs) {
  SourceFiles files;
  Interpreter in(codegen::testing::operators_program(files));
  const auto& columns = in.log_columns();
  std::size_t either = columns.size(), out = columns.size();
  for (std::size_t c = 0; c < columns.size(); ++c) {
    if (std::string_view(columns[c].name) == "gate_either") either = c;
    if (std::string_view(columns[c].name) == "c_either_out") out = c;
  }
  ASSERT_LT(either, columns.size());
  ASSERT_LT(out, columns.size());
  robot::Command command = robot::make_command(robot::gen3_pair_shape());
  std::vector<double> values(columns.size());
  for (std::uint64_t k = 0; k < 300; ++k) {
    const robot::MeasuredState state = codegen::testing::measurement(k);
    in.tick(state, command);
    in.log_values(values);
    const double t = state.clock.t;
    const bool expected = t <= 0.1 || t >= 0.2;  // the evaluators count the threshold as met
    EXPECT_EQ(values[either], expected ? 1.0 : 0.0) << "t = " << t;
    if (!expected) {
      EXPECT_EQ(values[out], 0.0) << "the gated PID runs at t = " << t;
    }
  }
}

}  // namespace
}  // namespace mospec::ir

namespace mospec::ir {
namespace {

// Every arm solve logs whether its ACHD lost constraint directions (the
// kernel's status: tests/runtime/arm_steps_test.cpp); a bent arm standing in
// sc0a's initial pose solves all five end-effector constraints.
TEST(Interpreter, AnArmSolveLogsWhetherItsSolveDegraded) {
  Interpreter in(sc0a());
  const int degraded = column(in, "slv-rightarm.degraded");
  EXPECT_EQ(in.log_columns()[static_cast<size_t>(degraded)].kind, robot::LogColumnKind::Flag)
      << "latched like a monitor's flag, so a decimated log keeps it";
  robot::MeasuredState state = standing_robot();
  robot::Command command = robot::make_command(robot::gen3_pair_shape());
  std::vector<double> values(in.log_columns().size());
  for (int k = 0; k < 3; ++k) {
    tick_at(in, k, state, command, values);
    EXPECT_EQ(values[static_cast<size_t>(column(in, "motion-rightarm.running"))], 1.0);
    EXPECT_EQ(values[static_cast<size_t>(degraded)], 0.0);
  }
}

}  // namespace
}  // namespace mospec::ir

namespace mospec::ir {
namespace {

// A step whose inputs are any number (an arm solve's drivers and gates) still
// has its outputs checked: the back-ends write its degraded flag.
TEST(Verifier, ChecksTheOutputsOfAStepWithAnyNumberOfInputs) {
  Program p = sc0a();
  ASSERT_TRUE(check(p).empty());
  for (Step& st : p.steps) {
    if (st.kind == StepKind::ArmSolve) st.out.clear();
  }
  std::string all;
  for (const Diagnostic& d : check(p)) all.append(d.message).append("\n");
  EXPECT_NE(all.find("0 outputs; expected any number of and 1"), std::string::npos) << all;
}

}  // namespace
}  // namespace mospec::ir

namespace mospec::ir {
namespace {

// The hand-built arm program's one-sided row (a less-than bound on the tip's
// height driving its linear x) is both engaged and released in the 2000 ticks
// codegen's equivalence test runs, so both branches are compared there.
TEST(Interpreter, TheArmProgramsOneSidedRowEngagesAndReleases) {
  SourceFiles files;
  Interpreter in(codegen::testing::arm_program(files));
  const int low_err = column(in, "low_err");
  robot::Command command = robot::make_command(robot::gen3_pair_shape());
  std::vector<double> values(in.log_columns().size());
  int engaged = 0, released = 0;
  for (std::uint64_t k = 0; k < 2000; ++k) {
    in.tick(codegen::testing::measurement(k), command);
    in.log_values(values);
    (values[static_cast<size_t>(low_err)] != 0.0 ? engaged : released)++;
  }
  EXPECT_GT(engaged, 0);
  EXPECT_GT(released, 0);
}

}  // namespace
}  // namespace mospec::ir
