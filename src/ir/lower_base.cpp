// Lowering passes. The mobile base: KELO force distribution (Eq. 2-3) and platform twist.
#include <algorithm>
#include <cmath>

#include "description/base_rdf.hpp"
#include "ir/lowering.hpp"

namespace mospec::ir::lowering {

namespace {

const std::string kSlv = "task/solver-specification";

// A problem of the base's description, at `at`, with its code. The
// configuration itself undefined: say who names it, and the nearest defined
// entity.
void report_base_problem(State& st, SourceLoc at, const description::BaseProblem& p,
                         TermId configuration, TermId configured_by) {
  using Kind = description::BaseProblemKind;
  switch (p.kind) {
    case Kind::Undefined:
      st.error(at, "undefined-configuration",
               p.entity == configuration ? p.message + "; named by '" + st.str(configured_by) +
                                               "'" + st.did_you_mean(configuration)
                                         : p.message);
      break;
    case Kind::MissingNumber:
      st.error(at, "missing-base-number", p.message);
      break;
    case Kind::Unit:
      st.error(at, "base-unit", p.message);
      break;
    case Kind::DriveCount:
      st.error(at, "unsupported-drive-count", p.message);
      break;
    case Kind::Degenerate:
      st.error(at, "degenerate-base", p.message);
      break;
  }
}

// The base's numbers: the CastorDriveBase the solvers' `configuration` names
// (mospec/mobile-base), one entity for both solvers; its term, and the solver
// naming it (`configured_by`, the first solver when none does).
std::optional<TermId> find_configuration(State& st, const std::vector<TermId>& solvers,
                                         TermId& configured_by) {
  std::optional<TermId> configuration;
  for (TermId solver : solvers) {
    const auto c = st.object(solver, vocab(kSlv, "configuration"));
    if (c && !configuration) {
      configuration = *c;
      configured_by = solver;
    } else if (c && *c != *configuration) {
      st.error(st.where(solver, vocab(kSlv, "configuration"), *c), "base-configuration-mismatch",
               "the solver '" + st.str(solver) + "' names the configuration '" + st.str(*c) +
                   "', but '" + st.str(configured_by) + "' (" + st.place(configured_by) +
                   ") names '" + st.str(*configuration) +
                   "': mospec's robot has one base, so both platform solvers must name the same "
                   "configuration");
    } else if (!c) {
      st.error(solver, "missing-property",
               "the solver '" + st.str(solver) +
                   "' names no configuration: name the base it drives (a CastorDriveBase, e.g. "
                   "https://mospec.example/robots/kelo-base/base)");
    }
  }
  return configuration;
}

// The base's geometry read from its configuration; its problems reported at
// the entity they are about (or where the configuration is named).
void read_configuration(State& st, BaseSolver& base, TermId configuration, TermId configured_by) {
  base.configuration = st.str(configuration);
  const description::BaseReading reading =
      description::read_base(st.graph.dataset(), base.configuration);
  const SourceLoc named_at = st.where(configured_by, vocab(kSlv, "configuration"), configuration);
  for (const description::BaseProblem& p : reading.problems) {
    const SourceLoc at = !p.entity.is_any() && st.defined(p.entity) ? st.where(p.entity) : named_at;
    report_base_problem(st, at, p, configuration, configured_by);
  }
  base.config = reading.config;
}

// A platform quantity must be at the origin of the frame it is seen by.
bool at_frame_origin(State& st, const Data& q) {
  std::string origin;
  if (auto frame = st.term(q.as_seen_by); !st.absent(frame)) {
    if (auto o = st.object(frame, vocab("geometry/structural-entities", "origin")))
      origin = st.str(*o);
  }
  return !origin.empty() && q.reference_point == origin;
}

// One platform quantity per solver: the twist it composes, the wrench it
// distributes; each at the origin of the frame it is seen by (the
// platform's). Its datum into `field`, its step into `steps`.
void platform_step(State& st, TermId solver, const char* property, DataType type, StepKind kind,
                   int& field, std::vector<Step>& steps) {
  st.pending_iri = st.str(solver);
  auto q = st.object(solver, vocab(kSlv, property));
  if (!q) {
    st.error(solver, "missing-property",
             "the solver '" + st.str(solver) + "' names no " + property);
    return;
  }
  field = st.datum(*q, type, solver, property);
  const Data& d = st.program.data[static_cast<size_t>(field)];
  if (!at_frame_origin(st, d)) {
    st.error(*q, "frame-mismatch",
             "the platform " + std::string(to_string(type)) + " '" + d.iri +
                 "' must be at the origin of the frame it is seen by (the platform's); it is at '" +
                 d.reference_point + "' seen by '" + d.as_seen_by + "'");
  }
  Step s = st.step_for(kind, solver);
  // The twist a measurement gives, the wrench a solver takes.
  (role(s) == StepRole::Measurement ? s.out : s.in) = {field};
  steps.push_back(std::move(s));
}

}  // namespace

void lower_base(State& st) {
  const auto forces = st.instances(vocab(kSlv, "ForceDistributionSolver"));
  const auto velocities = st.instances(vocab(kSlv, "VelocityCompositionSolver"));
  if (forces.size() > 1)
    st.error(forces[1], "too-many-bases",
             "mospec's robot has one base; a second force distribution solver '" +
                 st.str(forces[1]) + "' has nothing to drive");
  if (velocities.size() > 1)
    st.error(velocities[1], "too-many-bases",
             "mospec's robot has one base; a second velocity composition solver '" +
                 st.str(velocities[1]) + "' has nothing to measure");
  if (forces.empty() && velocities.empty()) return;
  BaseSolver base;
  const TermId first = forces.empty() ? velocities.front() : forces.front();
  base.iri = st.str(first);
  base.name = identifier(local_name(base.iri));
  base.where = st.where(first);
  std::vector<TermId> solvers;  // the force solver, then the velocity one
  if (!forces.empty()) solvers.push_back(forces.front());
  if (!velocities.empty()) solvers.push_back(velocities.front());
  TermId configured_by = first;
  if (const auto configuration = find_configuration(st, solvers, configured_by))
    read_configuration(st, base, *configuration, configured_by);
  std::vector<Step> new_steps;
  if (!velocities.empty()) {
    platform_step(st, velocities.front(), "velocity", DataType::Twist,
                  StepKind::BaseVelocityComposition, base.twist, new_steps);
  }
  if (!forces.empty()) {
    platform_step(st, forces.front(), "force", DataType::Wrench, StepKind::BaseForceDistribution,
                  base.wrench, new_steps);
  }
  st.program.base = std::move(base);
  for (Step& s : new_steps) st.add_step(std::move(s));
}

}  // namespace mospec::ir::lowering
