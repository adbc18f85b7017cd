// Lowering passes. The mobile base: KELO force distribution (Eq. 2-3) and platform twist.
#include <algorithm>
#include <cmath>

#include "description/base_rdf.hpp"
#include "ir/lowering.hpp"

namespace mospec::ir::lowering {

void lower_base(State& st) {
  const std::string slv = "task/solver-specification";
  const auto forces = st.instances(vocab(slv, "ForceDistributionSolver"));
  const auto velocities = st.instances(vocab(slv, "VelocityCompositionSolver"));
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
  // The base's numbers: the CastorDriveBase the solvers' `configuration`
  // names (mospec/mobile-base), one entity for both solvers.
  std::optional<TermId> configuration;
  TermId configured_by = first;
  for (TermId solver : {forces.empty() ? TermId::any() : forces.front(),
                        velocities.empty() ? TermId::any() : velocities.front()}) {
    if (solver.is_any()) continue;
    auto c = st.object(solver, vocab(slv, "configuration"));
    if (!c) {
      st.error(solver, "missing-property",
               "the solver '" + st.str(solver) +
                   "' names no configuration: name the base it drives (a CastorDriveBase, e.g. "
                   "https://mospec.example/robots/kelo-base/base)");
    } else if (!configuration) {
      configuration = *c;
      configured_by = solver;
    } else if (*c != *configuration) {
      st.error(st.where(solver, vocab(slv, "configuration"), *c), "base-configuration-mismatch",
               "the solver '" + st.str(solver) + "' names the configuration '" + st.str(*c) +
                   "', but '" + st.str(configured_by) + "' (" + st.place(configured_by) +
                   ") names '" + st.str(*configuration) +
                   "': mospec's robot has one base, so both platform solvers must name the same "
                   "configuration");
    }
  }
  if (configuration) {
    base.configuration = st.str(*configuration);
    const description::BaseReading reading =
        description::read_base(st.graph.dataset(), base.configuration);
    const SourceLoc named_at = st.where(configured_by, vocab(slv, "configuration"), *configuration);
    using Kind = description::BaseProblemKind;
    for (const description::BaseProblem& p : reading.problems) {
      const SourceLoc at =
          !p.entity.is_any() && st.defined(p.entity) ? st.where(p.entity) : named_at;
      switch (p.kind) {
        case Kind::Undefined:
          // The configuration itself undefined: say who names it, and the
          // nearest defined entity.
          st.error(at, "undefined-configuration",
                   p.entity == *configuration ? p.message + "; named by '" + st.str(configured_by) +
                                                    "'" + st.did_you_mean(*configuration)
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
    base.config = reading.config;
  }
  // A platform quantity must be at the origin of the frame it is seen by.
  const auto at_frame_origin = [&](const Data& q) {
    std::string origin;
    if (auto frame = st.term(q.as_seen_by); !st.absent(frame)) {
      if (auto o = st.object(frame, vocab("geometry/structural-entities", "origin")))
        origin = st.str(*o);
    }
    return !origin.empty() && q.reference_point == origin;
  };
  // One platform quantity per solver: the twist it composes, the wrench it
  // distributes; each at the origin of the frame it is seen by (the platform's).
  std::vector<Step> new_steps;
  const auto platform_step = [&](TermId solver, const char* property, DataType type, StepKind kind,
                                 int& field) {
    st.pending_iri = st.str(solver);
    auto q = st.object(solver, vocab(slv, property));
    if (!q) {
      st.error(solver, "missing-property",
               "the solver '" + st.str(solver) + "' names no " + property);
      return;
    }
    field = st.datum(*q, type, solver, property);
    const Data& d = st.program.data[static_cast<size_t>(field)];
    if (!at_frame_origin(d)) {
      st.error(
          *q, "frame-mismatch",
          "the platform " + std::string(to_string(type)) + " '" + d.iri +
              "' must be at the origin of the frame it is seen by (the platform's); it is at '" +
              d.reference_point + "' seen by '" + d.as_seen_by + "'");
    }
    Step s = st.step_for(kind, solver);
    (kind == StepKind::BaseVelocityComposition ? s.out : s.in) = {field};
    new_steps.push_back(std::move(s));
  };
  if (!velocities.empty()) {
    platform_step(velocities.front(), "velocity", DataType::Twist,
                  StepKind::BaseVelocityComposition, base.twist);
  }
  if (!forces.empty()) {
    platform_step(forces.front(), "force", DataType::Wrench, StepKind::BaseForceDistribution,
                  base.wrench);
  }
  st.program.base = std::move(base);
  for (Step& s : new_steps) st.add_step(std::move(s));
}

}  // namespace mospec::ir::lowering
