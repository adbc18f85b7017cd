#include "cli/loop_check.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "cli/verdict.hpp"
#include "ir/controllers.hpp"
#include "ir/interpreter.hpp"
#include "sim/run.hpp"
#include "sim/world.hpp"

namespace mospec::cli {

namespace {

// A gain of a controller kind whose law is u = sum of K x, x the error, its
// integral or its derivative: its Spec member and the power of time that
// makes K x comparable to the error over the probe (1, T or 1/T).
struct Gain {
  std::string_view member;
  int time_power = 0;
};
std::vector<Gain> gains_of(std::string_view kind) {
  if (kind == "pid") return {{"kp", 0}, {"ki", 1}, {"kd", -1}};
  if (kind == "impedance") return {{"stiffness", 0}, {"damping", -1}};
  return {};
}

// Below this, a loop changes its error by less than 1 % over the probe: too
// weak to drive it anywhere, and too weak to be measured with its sign.
constexpr double kWeakLoop = 0.01;

// Runs `program` for `ticks` control ticks from the world's start state.
template <typename Read>
auto run_from_start(ir::Program program, int ticks, const sim::WorldConfig& config,
                    const std::vector<runtime::Chain>& arms, Read read) {
  std::vector<bool> idle(config.arms.size(), true);
  for (const ir::ArmSolver& a : program.arms) idle[static_cast<size_t>(a.port)] = false;
  ir::Interpreter controller(std::move(program));
  sim::World world(config, arms);
  sim::RunOptions options;
  options.duration = ticks * config.control_period;
  options.log_every = ticks;
  options.idle = std::move(idle);
  const sim::RunResult r = sim::run(world, controller, options);
  // A solve that lost directions is no linearisation of anything: not judged.
  bool degraded = false;
  for (const auto& [solver, ticks] : degraded_solves(r)) degraded = degraded || ticks > 0;
  return std::make_pair(read(controller), degraded);
}

// The program with every controller held at its output of the first tick
// (`held`, by step index), and the one at step `probed` at that plus `delta`:
// the probed loop alone, open, about the start state.
ir::Program held_open(const ir::Program& program, const std::vector<double>& held, size_t probed,
                      double delta) {
  ir::Program open = program;
  open.steps.clear();
  for (size_t i = 0; i < program.steps.size(); ++i) {
    const ir::Step& s = program.steps[i];
    if (s.kind != ir::StepKind::Controller || s.out.empty()) {
      open.steps.push_back(s);
      continue;
    }
    open.data[static_cast<size_t>(s.out.front())].value = {held[i] + (i == probed ? delta : 0.0)};
  }
  return open;
}

}  // namespace

std::vector<Diagnostic> check_loop_signs(const ir::Program& program, const sim::WorldConfig& world,
                                         const std::vector<runtime::Chain>& arms,
                                         const SourceFiles& files) {
  std::vector<Diagnostic> problems;
  const auto kinds = ir::controller_kinds();
  const auto probed = [&](size_t i) {
    const ir::Step& c = program.steps[i];
    return c.kind == ir::StepKind::Controller && !c.in.empty() && !c.out.empty() &&
           !gains_of(kinds[static_cast<size_t>(c.controller)].name).empty();
  };
  std::vector<double> held(program.steps.size(), 0.0);
  bool any = false;
  for (size_t i = 0; i < program.steps.size(); ++i) any = any || probed(i);
  if (!any) return problems;
  held = run_from_start(program, 1, world, arms, [&](const ir::Interpreter& c) {
           std::vector<double> out(program.steps.size(), 0.0);
           for (size_t i = 0; i < program.steps.size(); ++i) {
             const ir::Step& s = program.steps[i];
             if (s.kind == ir::StepKind::Controller && !s.out.empty())
               out[i] = c.value(s.out.front());
           }
           return out;
         }).first;
  for (size_t i = 0; i < program.steps.size(); ++i) {
    if (!probed(i)) continue;
    const ir::Step& c = program.steps[i];
    const ir::ControllerKind& kind = kinds[static_cast<size_t>(c.controller)];
    const std::vector<Gain> gains = gains_of(kind.name);
    const auto error_of = [&](const ir::Interpreter& run) { return run.value(c.in.front()); };
    const auto [up, up_degraded] =
        run_from_start(held_open(program, held, i, kProbe), kProbeTicks, world, arms, error_of);
    const auto [down, down_degraded] =
        run_from_start(held_open(program, held, i, -kProbe), kProbeTicks, world, arms, error_of);
    if (up_degraded || down_degraded) continue;
    const double slope = (up - down) / (2 * kProbe);  // d(error)/d(output), at the start
    if (!std::isfinite(slope)) continue;
    const double horizon = kProbeTicks * world.control_period;
    // The loop's first nonzero term (proportional before integral before
    // derivative), relative to the error, over the probe.
    double strength = 0.0;
    for (const Gain& g : gains) {
      const int p = kind.parameter(g.member);
      const double k = p < 0 ? 0.0 : c.parameters[static_cast<size_t>(p)];
      if (k == 0.0) continue;
      strength = std::abs(k * slope) * std::pow(horizon, g.time_power);
      break;
    }
    if (strength < kWeakLoop) continue;  // the probes hardly move the error
    const ir::Data& error = program.data[static_cast<size_t>(c.in.front())];
    const ir::Data& output = program.data[static_cast<size_t>(c.out.front())];
    // The quantity the error is of: the Evaluate step that writes it reads it.
    std::string quantity = error.iri;
    for (const ir::Step& s : program.steps) {
      if (s.kind == ir::StepKind::Evaluate && s.out.size() > 1 && s.out[1] == c.in.front())
        quantity = program.data[static_cast<size_t>(s.in.front())].iri;
    }
    for (const Gain& g : gains) {
      const int p = kind.parameter(g.member);
      if (p < 0) continue;
      const double k = c.parameters[static_cast<size_t>(p)];
      if (!(k * slope > 0.0)) continue;
      const std::string_view property = kind.parameters[static_cast<size_t>(p)].property;
      problems.push_back(located(
          Severity::Error, c.where, files, "loop-sign",
          "the controller '" + c.iri + "' drives the error of '" + quantity +
              "' away from 0: at the start, a larger output '" + output.iri + "' makes the error " +
              (slope > 0 ? "larger" : "smaller") + " (" + exact_number(slope) + " per unit over " +
              std::to_string(kProbeTicks) + " ticks), so its " + std::string(property) +
              " must be " + (slope > 0 ? "<= 0" : ">= 0") + ", and it is " + exact_number(k)));
    }
  }
  return problems;
}

}  // namespace mospec::cli
