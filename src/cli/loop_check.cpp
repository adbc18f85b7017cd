#include "cli/loop_check.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <string>
#include <utility>

#include "ir/controllers.hpp"
#include "ir/interpreter.hpp"
#include "sim/run.hpp"
#include "sim/world.hpp"
#include "verdict/verdict.hpp"

namespace mospec::cli {

using verdict::console_number;
using verdict::degraded_solves;

namespace {

// The indices of a kind's loop gains (ir::ControllerParameter::gain).
std::vector<size_t> gains_of(const ir::ControllerKind& kind) {
  std::vector<size_t> gains;
  for (size_t p = 0; p < kind.parameters.size(); ++p)
    if (kind.parameters[p].gain) gains.push_back(p);
  return gains;
}

// A response this small per unit of output is rounding, not a loop.
constexpr double kResolvable = 1e-12;
// The fit must explain the response within this (relative RMS residual).
constexpr double kFitTolerance = 0.1;

// Records one datum of the controller after every step.
class ErrorTrace final : public sim::StepObserver {
 public:
  ErrorTrace(const ir::Interpreter& controller, int data, size_t ticks)
      : controller_(controller), data_(data) {
    values_.reserve(ticks + 1);
  }
  void observe(const sim::World&) override { values_.push_back(controller_.value(data_)); }
  // The datum the controller computed from the state after k steps, k = 0..:
  // the first observation is before any tick, and a tick's values are seen
  // after its step.
  std::vector<double> after_steps() const {
    return values_.size() < 2 ? std::vector<double>{}
                              : std::vector<double>(values_.begin() + 1, values_.end());
  }

 private:
  const ir::Interpreter& controller_;
  int data_;
  std::vector<double> values_;
};

struct Probe {
  std::vector<double> error;  // after 0, 1, ... steps
  bool degraded = false;      // a solve lost directions: no linearisation of anything
};

// Runs `program` for `ticks` control ticks from the world's start state,
// recording the datum `trace`.
Probe run_from_start(ir::Program program, int ticks, const sim::WorldConfig& config,
                     const std::vector<runtime::Chain>& arms, int trace,
                     std::vector<double>* first_outputs = nullptr) {
  std::vector<bool> idle(config.arms.size(), true);
  for (const ir::ArmSolver& a : program.arms) idle[static_cast<size_t>(a.port)] = false;
  const std::vector<ir::Step> steps = program.steps;
  ir::Interpreter controller(std::move(program));
  sim::World world(config, arms);
  ErrorTrace recorder(controller, trace, static_cast<size_t>(ticks));
  sim::RunOptions options;
  options.duration = ticks * config.control_period;
  options.log_every = ticks;
  options.idle = std::move(idle);
  options.observer = &recorder;
  const sim::RunResult r = sim::run(world, controller, options);
  Probe p{.error = recorder.after_steps()};
  for (const auto& [solver, lost] : degraded_solves(r)) p.degraded = p.degraded || lost > 0;
  if (first_outputs) {
    first_outputs->assign(steps.size(), 0.0);
    for (size_t i = 0; i < steps.size(); ++i)
      if (ir::role(steps[i]) == ir::StepRole::Controller && !steps[i].out.empty())
        (*first_outputs)[i] = controller.value(steps[i].out.front());
  }
  return p;
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
    if (ir::role(s) != ir::StepRole::Controller || s.out.empty()) {
      open.steps.push_back(s);
      continue;
    }
    open.data[static_cast<size_t>(s.out.front())].value = {held[i] + (i == probed ? delta : 0.0)};
  }
  return open;
}

// The sign of d(error)/d(output) over the first kSignTicks steps, or 0 when
// the response there is not one growing effect of one sign.
int early_sign(const std::vector<double>& response) {
  if (response.size() <= static_cast<size_t>(kSignTicks)) return 0;
  const double last = response[kSignTicks];
  if (!(std::abs(last) > kResolvable)) return 0;
  const int sign = last > 0 ? 1 : -1;
  double previous = 0.0;
  for (int k = 1; k <= kSignTicks; ++k) {
    const double v = sign * response[static_cast<size_t>(k)];
    if (!(v > previous)) return 0;
    previous = v;
  }
  return sign;
}

// The growth rate [1/s] of the fastest-growing pole (ln |z| per tick / h).
double growth_rate(const std::vector<std::complex<double>>& poles, double period) {
  double r = 0.0;
  for (const std::complex<double>& p : poles) r = std::max(r, std::abs(p));
  return r > 0.0 ? std::log(r) / period : -1e300;
}

std::string quantity_of(const ir::Program& program, const ir::Step& c) {
  // The quantity the error is of: the Evaluate step that writes it reads it.
  std::string quantity = program.data[static_cast<size_t>(c.in.front())].iri;
  for (const ir::Step& s : program.steps) {
    if (ir::role(s) == ir::StepRole::Constraint && s.out.size() > 1 && s.out[1] == c.in.front())
      quantity = program.data[static_cast<size_t>(s.in.front())].iri;
  }
  return quantity;
}

}  // namespace

std::vector<Diagnostic> check_loops(const ir::Program& program, const sim::WorldConfig& world,
                                    const std::vector<runtime::Chain>& arms,
                                    const SourceFiles& files) {
  std::vector<Diagnostic> problems;
  const auto kinds = ir::controller_kinds();
  const auto probed = [&](size_t i) {
    const ir::Step& c = program.steps[i];
    return ir::role(c) == ir::StepRole::Controller && !c.in.empty() && !c.out.empty() &&
           !gains_of(kinds[static_cast<size_t>(c.controller)]).empty();
  };
  bool any = false;
  for (size_t i = 0; i < program.steps.size(); ++i) any = any || probed(i);
  if (!any) return problems;
  std::vector<double> held;
  (void)run_from_start(program, 1, world, arms, 0, &held);
  const double h = world.control_period;
  const double horizon = kProbeTicks * h;
  for (size_t i = 0; i < program.steps.size(); ++i) {
    if (!probed(i)) continue;
    const ir::Step& c = program.steps[i];
    const ir::ControllerKind& kind = kinds[static_cast<size_t>(c.controller)];
    const Probe up =
        run_from_start(held_open(program, held, i, kProbe), kProbeTicks, world, arms, c.in.front());
    const Probe down = run_from_start(held_open(program, held, i, -kProbe), kProbeTicks, world,
                                      arms, c.in.front());
    if (up.degraded || down.degraded || up.error.size() != down.error.size()) continue;
    std::vector<double> response(up.error.size());  // d(error)/d(output) after k steps
    for (size_t k = 0; k < response.size(); ++k)
      response[k] = (up.error[k] - down.error[k]) / (2 * kProbe);
    const int sign = early_sign(response);
    if (sign == 0) continue;  // the probes do not move the error (consistently)
    const ir::Data& output = program.data[static_cast<size_t>(c.out.front())];
    const std::string quantity = quantity_of(program, c);
    const size_t before = problems.size();
    for (const size_t p : gains_of(kind)) {
      const double k = c.parameters[p];
      if (!(k * sign > 0.0)) continue;
      const std::string_view property = kind.parameters[p].property;
      problems.push_back(located(
          Severity::Error, p < c.parameters_where.size() ? c.parameters_where[p] : c.where, files,
          "loop-sign",
          "the controller '" + c.iri + "' drives the error of '" + quantity +
              "' away from 0: at the start, a larger output '" + output.iri + "' makes the error " +
              (sign > 0 ? "larger" : "smaller") + " (" + console_number(response[kSignTicks]) +
              " per unit after " + std::to_string(kSignTicks) + " ticks), so its " +
              std::string(property) + " must be " + (sign > 0 ? "<= 0" : ">= 0") + ", and it is " +
              exact_number(k)));
    }
    if (problems.size() != before || !kind.linear()) continue;
    const runtime::IdentifiedPlant fit = ir::identify_loop_plant(response);
    if (!(fit.misfit <= kFitTolerance)) continue;  // not a second-order linear plant over the probe
    const auto rate = [&](double scale) {
      std::vector<double> scaled = c.parameters;
      for (const size_t p : gains_of(kind)) scaled[p] *= scale;
      return growth_rate(kind.closed_loop_poles(scaled, h, fit.plant), h);
    };
    // Unstable: growing e-fold within the probe, and faster than the plant
    // alone (the probe holds the rest of the task open, so the plant may
    // drift slowly by itself; a loop that adds nothing to that drift is not
    // what diverges).
    const double limit = 1.0 / horizon + std::max(0.0, rate(0.0));
    const double growth = rate(1.0);
    if (!(growth > limit)) continue;
    // The largest common scale of the gains at which the linearised loop is
    // stable (no pole beyond the plant's own), by bisection from a scale small
    // enough to be.
    // (With a hair of slack: at a vanishing scale the loop's poles are the
    // plant's, up to rounding.)
    const double neutral = std::max(0.0, rate(0.0)) + 1e-3 / horizon;
    std::string advice;
    double stable = 1e-6, unstable = 1.0;
    if (rate(stable) <= neutral) {
      for (int n = 0; n < 60; ++n) {
        const double mid = std::sqrt(stable * unstable);
        (rate(mid) <= neutral ? stable : unstable) = mid;
      }
      advice = "; with every gain scaled by " + console_number(stable) +
               " or less that pole is inside the unit circle (leave a margin: the probe holds the "
               "other loops open)";
    }
    std::string gains;
    for (const size_t p : gains_of(kind))
      gains += (gains.empty() ? "" : ", ") + std::string(kind.parameters[p].property) + " " +
               exact_number(c.parameters[p]);
    // At the loop's first gain that is not 0 (the one the scale applies to first).
    SourceLoc at = c.where;
    for (const size_t p : gains_of(kind)) {
      if (c.parameters[p] != 0.0 && p < c.parameters_where.size()) {
        at = c.parameters_where[p];
        break;
      }
    }
    problems.push_back(
        located(Severity::Error, at, files, "unstable-loop",
                "the loop of the controller '" + c.iri + "' on '" + quantity +
                    "' is unstable at the start: closed around the plant from its output '" +
                    output.iri + "' to its error as the probes identify it (the error moves " +
                    console_number(response.back()) + " per unit of output over " +
                    std::to_string(response.size() - 1) + " ticks of " + exact_number(h) +
                    " s), its gains (" + gains + ") put a pole at |z| = " +
                    console_number(std::exp(growth * h)) + ", which grows the error e-fold every " +
                    console_number(1000.0 / growth) + " ms" + advice));
  }
  return problems;
}

}  // namespace mospec::cli
