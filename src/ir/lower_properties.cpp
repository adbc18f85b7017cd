// Lowering pass. What the hand-written passes read: for each class of the
// vocabulary that lower_{arms,base,constraints,views}.cpp lower, the
// properties they read. A property of that class's vocabulary that lowering
// does not read would be ignored: it is refused here, located at its
// statement (`unsupported-property`), before anything is lowered. Operators
// and controllers refuse theirs through their registries (lower_operators.cpp,
// lower_controllers.cpp). docs/ir.md ("What lowering does with each
// property") lists the outcome of every property.
#include <algorithm>
#include <map>
#include <memory_resource>
#include <set>

#include "ir/controllers.hpp"
#include "ir/lowering.hpp"

namespace mospec::ir::lowering {

namespace {

// One class and the properties of its vocabulary that lowering reads for it.
struct Role {
  std::string_view type;  // class (local name)
  std::string_view what;  // as messages name an instance ("bilateral constraint")
  std::vector<std::string_view> reads;
};

// Classes of one vocabulary. Exclusive: lowering gives an instance the first
// role it has (a constraint that is bilateral and greater-than is lowered as
// bilateral, so its `threshold` is not read); otherwise every role it has.
struct Family {
  std::string_view ns;
  bool exclusive;
  std::vector<Role> roles;
};

const std::vector<Family>& families() {
  namespace v = mospec::vocab;
  static const std::vector<Family> table = {
      // lower_evaluators (the kinds in its order).
      {v::cstr::ns,
       true,
       {{"BilateralConstraint",
         "bilateral constraint",
         {"quantity", "lower-threshold", "upper-threshold"}},
        {"GreaterThanConstraint", "greater-than constraint", {"quantity", "threshold"}},
        {"LessThanConstraint", "less-than constraint", {"quantity", "threshold"}},
        {"EqualityConstraint", "equality constraint", {"quantity", "reference-value"}},
        {"UnilateralConstraint", "unilateral constraint", {"quantity", "threshold"}},
        {"Constraint", "constraint", {"quantity"}}}},
      // lower_evaluators: an assignment is lowered as one, whatever else it is.
      {v::cstr_hdl::ns,
       true,
       {{"AssignmentEvaluator", "assignment evaluator", {"constraint"}},
        {"ErrorEvaluator", "error evaluator", {"constraint", "error"}},
        {"ConstraintEvaluator", "constraint evaluator", {"constraint"}}}},
      // lower_monitors: each kind it has.
      {v::cstr_hdl::ns,
       false,
       {{"LevelTriggeredMonitor", "level-triggered monitor", {"error", "flag"}},
        {"EdgeTriggeredMonitor", "edge-triggered monitor", {"error", "event"}},
        {"Monitor", "monitor", {"error"}}}},
      // lower_handlers (`monitors`: a monitor reports while a motion whose handler lists it runs).
      {v::cstr_hdl::ns,
       false,
       {{"ConstraintHandler",
         "constraint handler",
         {"motion", "evaluators", "controllers", "monitors"}}}},
      // lower_handlers: the guards (`while`: enforced by the controllers or checked).
      {v::mot::ns, false, {{"GuardedMotion", "guarded motion", {"when", "while", "until"}}}},
      // lower_arm, lower_base.
      {v::slv::ns,
       false,
       {{"SolverWithInputAndOutput",
         "solver",
         {"solver", "kinematic-chain", "root", "gravity", "output", "motion-drivers"}},
        {"MotionDrivers",
         "set of motion drivers",
         {"acceleration-constraint", "cartesian-force", "joint-force", "prioritization-hierarchy"}},
        {"PrioritizationLevel", "prioritisation level", {"motion-drivers"}},
        {"AccelerationConstraintSpecification",
         "acceleration-constraint specification",
         {"attached-to", "constraints"}},
        {"AccelerationConstraint",
         "acceleration constraint",
         {"acceleration-energy", "subspace", "axis"}},
        {"AxisAligned", "acceleration constraint", {"acceleration-energy", "subspace", "axis"}},
        {"CartesianForceSpecification", "Cartesian force", {"force", "attached-to"}},
        {"JointForceSpecification", "joint force", {"force", "attached-to"}},
        {"ForceDistributionSolver", "force-distribution solver", {"configuration", "force"}},
        {"VelocityCompositionSolver",
         "velocity-composition solver",
         {"configuration", "velocity"}}}},
      // lower_views.
      {v::map::ns,
       false,
       {{"View", "view", {"superobject", "subobject", "subspace", "axis"}},
        {"PoseCoordinateView", "view", {"superobject", "subobject", "subspace", "axis"}},
        {"VelocityTwistCoordinateView", "view", {"superobject", "subobject", "subspace", "axis"}},
        {"WrenchCoordinateView", "view", {"superobject", "subobject", "subspace", "axis"}}}},
      // lower_clocks.
      {v::mospec_time::ns, false, {{"Clock", "clock", {"time"}}}},
      // lower_arm (the solver's `when-idle`).
      {v::mospec_solver::ns,
       false,
       {{"BrakeAndHold", "brake-and-hold idle behaviour", {"time-constant"}},
        {"Float", "float idle behaviour", {}}}},
      {v::mospec_joints::ns,
       false,
       {{"JointPosition", "joint position", {"of-joint"}},
        {"JointVelocity", "joint velocity", {"of-joint"}},
        {"JointTorque", "measured joint torque", {"of-joint"}},
        {"EstimatedWrench", "estimated wrench", {}}}},
  };
  return table;
}

// What to do instead, for a property a role does not read.
std::string advice(std::string_view type, std::string_view property) {
  if (property == "event-queue")
    return "mospec emits every event on its one event stream (the run's log); remove "
           "`event-queue`";
  if (type == "AssignmentEvaluator" && property == "error")
    return "an assignment writes its constraint's quantity and computes no error; remove "
           "`error`, or drop the class AssignmentEvaluator to evaluate the constraint's error";
  if (type == "LevelTriggeredMonitor" && property == "event")
    return "a level-triggered monitor raises a flag; for an event make it an "
           "EdgeTriggeredMonitor";
  if (type == "EdgeTriggeredMonitor" && property == "flag")
    return "an edge-triggered monitor emits an event; for a flag make it a "
           "LevelTriggeredMonitor";
  if (property.find("priorit") != std::string_view::npos)
    return "a motion driver's priority is the level of the solver's prioritization-hierarchy "
           "that lists it (mospec honours one level); remove `" +
           std::string(property) + "`";
  if (type == "GuardedMotion")
    return "a motion starts when its `when` constraints hold and ends when one of its `until` "
           "constraints does (a timeout is a GreaterThanConstraint on the clock's time in "
           "`until`); remove `" +
           std::string(property) + "`";
  if (type == "Float" && property == "time-constant")
    return "a Float does not brake; for braking, make it a BrakeAndHold";
  if (type == "EqualityConstraint" && property == "threshold")
    return "an equality constraint's tolerance is `tolerance` (cstr-ext:tolerance, the "
           "secorolab task/constraint-extension.json); for a band, make it a "
           "BilateralConstraint with a lower-threshold and an upper-threshold";
  if (type.ends_with("Constraint") &&
      (property == "threshold" || property == "lower-threshold" || property == "upper-threshold" ||
       property == "reference-value"))
    return "a constraint has one kind, and only that kind's bounds are evaluated; remove `" +
           std::string(property) + "`, or state it on a second constraint of the kind that has it";
  return "remove it";
}

// A constraint's tolerance (the published cstr-ext:tolerance): lower_evaluators
// reads it on an equality, less-than or greater-than constraint. mospec's
// guard extension (metamodels/mospec/guards.json): lower_monitors reads `edge`
// on an edge-triggered monitor; its `tolerance` (mos-grd:tolerance) is retired
// for the published term. On any other constraint or monitor, or any other
// term of the extension, they would be ignored: refused.
void refuse_misplaced_guard_terms(State& st) {
  namespace v = mospec::vocab;
  const std::string ns(v::mospec_guards::ns);
  const std::string tolerance = v::term(v::cstr_ext::ns, "tolerance");
  const std::string cstr(v::cstr::ns), hdl(v::cstr_hdl::ns);
  std::set<uint32_t> seen;
  for (const std::string& type :
       {cstr + "Constraint", cstr + "EqualityConstraint", cstr + "BilateralConstraint",
        cstr + "UnilateralConstraint", cstr + "GreaterThanConstraint", cstr + "LessThanConstraint",
        hdl + "Monitor", hdl + "LevelTriggeredMonitor", hdl + "EdgeTriggeredMonitor"}) {
    for (TermId e : st.instances(type)) {
      if (!seen.insert(e.index).second) continue;
      std::set<std::string_view> reported;  // views of the term table's IRIs
      st.graph.each_statement(e, [&](const Graph::Statement& statement) {
        const std::string_view p = st.graph.str(statement.predicate);
        const bool published = p == tolerance;
        if ((!published && !p.starts_with(ns)) || !reported.insert(p).second) return;
        const std::string local(published ? "tolerance" : p.substr(ns.size()));
        const SourceLoc at = statement.where.known() ? statement.where : st.where(e);
        if (!published && local == "tolerance") {
          st.error(at, "unsupported-property",
                   "'" + st.str(e) +
                       "' states mos-grd:tolerance, which is retired: a constraint's tolerance "
                       "is the published cstr-ext:tolerance; list the context " +
                       std::string(v::kSecorolab) +
                       "task/constraint-extension.json (after mospec/guards.json, if the file "
                       "lists it) and keep the key `tolerance`");
          return;
        }
        const bool equality = st.has_type(e, cstr + "EqualityConstraint") ||
                              st.has_type(e, cstr + "LessThanConstraint") ||
                              st.has_type(e, cstr + "GreaterThanConstraint");
        const bool edge = st.has_type(e, hdl + "EdgeTriggeredMonitor");
        if ((local == "tolerance" && equality) || (local == "edge" && edge)) return;
        std::string why;
        if (local == "tolerance")
          why =
              "a tolerance widens an equality, a less-than or a greater-than constraint; a "
              "band is satisfied inside its bounds, and a monitor uses its constraint's "
              "tolerance";
        else if (local == "edge")
          why =
              "only an edge-triggered monitor reports edges (a level-triggered one raises a "
              "flag while its constraint holds)";
        else
          why =
              "mospec's guard extension has `edge` (edge-triggered monitors); a constraint's "
              "tolerance is the published `tolerance` (cstr-ext:tolerance)";
        std::string message = "'";
        message.append(st.str(e)).append("' states `").append(local).append("` (");
        message.append(published ? "cstr-ext:" : "mos-grd:").append(local);
        message.append("), which mospec does not read for it, so it would be ");
        message.append("ignored; ").append(why).append("; remove it");
        st.error(at, "unsupported-property", std::move(message));
      });
    }
  }
}

}  // namespace

void refuse_unread_properties(State& st) {
  // Entities the controller registry checks (their class's vocabulary is
  // cstr-hdl too).
  // Its sets and lists are scratch: from the lowering's arena.
  std::pmr::set<uint32_t> controllers{&st.arena};
  for (const ControllerKind& k : controller_kinds()) {
    for (TermId c : st.instances(k.class_iri())) controllers.insert(c.index);
  }
  // Per vocabulary, per entity (in order of first role, then instance): the
  // roles it has.
  struct Entity {
    TermId term;
    std::pmr::vector<const Role*> roles;
  };
  for (std::string_view ns :
       {mospec::vocab::cstr::ns, mospec::vocab::cstr_hdl::ns, mospec::vocab::mot::ns,
        mospec::vocab::slv::ns, mospec::vocab::map::ns, mospec::vocab::mospec_time::ns,
        mospec::vocab::mospec_solver::ns, mospec::vocab::mospec_joints::ns}) {
    std::vector<Entity> entities;
    std::pmr::map<uint32_t, size_t> index{&st.arena};
    for (const Family& f : families()) {
      if (f.ns != ns) continue;
      std::pmr::set<uint32_t> placed{&st.arena};  // exclusive: entities given a role of this family
      for (const Role& r : f.roles) {
        for (TermId e : st.instances(std::string(ns).append(r.type))) {
          if (f.exclusive && !placed.insert(e.index).second) continue;
          if (ns == mospec::vocab::cstr_hdl::ns && controllers.count(e.index)) continue;
          auto [it, fresh] = index.emplace(e.index, entities.size());
          if (fresh) entities.push_back({e, std::pmr::vector<const Role*>(&st.arena)});
          entities[it->second].roles.push_back(&r);
        }
      }
    }
    for (const Entity& e : entities) {
      const auto reads = [&](std::string_view local) {
        for (const Role* r : e.roles) {
          if (std::find(r->reads.begin(), r->reads.end(), local) != r->reads.end()) return true;
        }
        return false;
      };
      std::vector<std::string_view> seen;  // unread properties reported (views of the term table)
      st.graph.each_statement(e.term, [&](const Graph::Statement& statement) {
        const std::string_view p = st.graph.str(statement.predicate);
        if (!p.starts_with(ns)) return;
        const std::string_view local = p.substr(ns.size());
        if (reads(local) || std::find(seen.begin(), seen.end(), p) != seen.end()) return;
        seen.push_back(p);
        const Role& role = *e.roles.front();
        std::set<std::string_view> read;  // sorted, as the message lists them
        for (const Role* r : e.roles) read.insert(r->reads.begin(), r->reads.end());
        std::string known;
        for (std::string_view r : read) known.append(known.empty() ? "" : ", ").append(r);
        st.error(statement.where.known() ? statement.where : st.where(e.term),
                 "unsupported-property",
                 "the " + std::string(role.what) + " '" + st.str(e.term) + "' states `" +
                     std::string(local) + "`, which mospec does not read for " +
                     article(role.what) + std::string(role.what) + " (it reads " +
                     (known.empty() ? std::string("nothing") : known) +
                     "), so it would be ignored; " + advice(role.type, local));
      });
    }
  }
  refuse_misplaced_guard_terms(st);
}

}  // namespace mospec::ir::lowering
