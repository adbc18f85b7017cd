// Lowering passes. Arms: each solver specification becomes an arm (its chain, ACHD's inputs and
// priorities) and the clocks, and motions gate their arm's solve.
#include <algorithm>
#include <cmath>
#include <memory_resource>
#include <optional>
#include <utility>

#include "description/chain_rdf.hpp"
#include "ir/controllers.hpp"
#include "ir/lowering.hpp"
#include "support/spelling.hpp"

namespace mospec::ir::lowering {

// ---------------------------------------------------------------------------
void lower_clocks(State& st) {
  for (TermId c : st.instances(vocab("mospec/time", "Clock"))) {
    st.pending_iri = st.str(c);
    auto t = st.object(c, vocab("mospec/time", "time"));
    if (!t) {
      st.error(c, "missing-property", "the clock '" + st.str(c) + "' names no `time` quantity");
      continue;
    }
    Step s = st.step_for(StepKind::ReadClock, c);
    s.out = {st.datum(*t, DataType::Scalar, c, "time")};
    if (st.program.data[static_cast<size_t>(s.out[0])].unit != "SEC")
      st.error(*t, "wrong-unit", "the clock's time '" + st.str(*t) + "' must be in SEC");
    st.add_step(std::move(s));
  }
}

void lower_arms(State& st) {
  for (TermId s : st.instances(vocab("task/solver-specification", "SolverWithInputAndOutput")))
    lower_arm(st, s);
  // Each solve writes its arm's joint torques: two solvers on one arm would
  // silently overwrite each other.
  for (size_t i = 0; i < st.program.arms.size(); ++i) {
    for (size_t j = 0; j < i; ++j) {
      const ArmSolver& a = st.program.arms[j];
      const ArmSolver& b = st.program.arms[i];
      if (a.port != b.port || !st.options.ports.count(a.chain_iri) ||
          !st.options.ports.count(b.chain_iri))
        continue;
      st.error(b.where, "arm-driven-twice",
               "the solvers '" + a.iri + "' (" + st.place(a.where) + ") and '" + b.iri +
                   "' both drive arm " + std::to_string(b.port) +
                   " of the robot (their chains are bound to it), and each would overwrite the "
                   "other's joint torques; bind the chains to different arms (--bind CHAIN=ARM) "
                   "or merge the solvers' motion drivers");
      break;
    }
  }
}

namespace {

// mospec/solver: whether the task solve compensates gravity, and what the arm
// does while no motion drives it (checked against the gates in
// gate_arm_solves).
void lower_arm_behaviour(State& st, TermId solver, ArmSolver& arm) {
  namespace ms = mospec::vocab::mospec_solver;
  arm.gravity_compensated = st.has_type(solver, mospec::vocab::term(ms::ns, "GravityCompensated"));
  const std::string when_idle = mospec::vocab::term(ms::ns, "when-idle");
  const auto idle = st.object(solver, when_idle);
  if (!idle) return;
  arm.idle_where = st.where(solver, when_idle, *idle);
  const std::string what = "the idle behaviour '" + st.str(*idle) + "' of '" + arm.iri + "'";
  if (st.has_type(*idle, mospec::vocab::term(ms::ns, "Float"))) {
    arm.idle = ArmSolver::Idle::Float;
    return;
  }
  if (!st.has_type(*idle, mospec::vocab::term(ms::ns, "BrakeAndHold"))) {
    st.error(arm.idle_where, "unsupported-idle",
             what +
                 " is neither a BrakeAndHold nor a Float (mospec/solver), the two an arm "
                 "can do while no motion drives it");
    return;
  }
  const std::string tc_prop = mospec::vocab::term(ms::ns, "time-constant");
  const auto tc = st.object(*idle, tc_prop);
  if (!tc) {
    st.error(*idle, "missing-property",
             what + " names no `time-constant` (a quantity in SEC: how fast the joints stop)");
    return;
  }
  std::string unit;
  if (auto u = st.object(*tc, kQudt + "unit")) unit = local_name(st.str(*u));
  const auto value = st.number(*tc, kQudt + "value");
  if (unit != "SEC") {
    st.error(*tc, "wrong-unit",
             "the time constant '" + st.str(*tc) + "' of " + what + " must be in SEC, not '" +
                 unit + "'");
  } else if (!value || !(*value > 0.0)) {
    st.error(*tc, "invalid-number",
             "the time constant '" + st.str(*tc) + "' of " + what +
                 " must be a number of seconds > 0 (the joints' velocities decay with it)");
  } else {
    arm.idle = ArmSolver::Idle::BrakeAndHold;
    arm.idle_time_constant = *value;
  }
}

// mospec/joints: a solver output that is a joint quantity, and its kind.
std::optional<ArmOutput::What> joint_quantity(State& st, TermId o) {
  namespace mj = mospec::vocab::mospec_joints;
  if (st.has_type(o, mospec::vocab::term(mj::ns, "JointPosition")))
    return ArmOutput::What::JointPosition;
  if (st.has_type(o, mospec::vocab::term(mj::ns, "JointVelocity")))
    return ArmOutput::What::JointVelocity;
  if (st.has_type(o, mospec::vocab::term(mj::ns, "JointTorque")))
    return ArmOutput::What::JointTorque;
  return std::nullopt;
}

// "no joint 'X' in the chain 'C'; its joints are ...": what a reference to a
// joint the solver's chain lacks is told, with the nearest joint when X looks
// like a typo of it (after `how`, what to do). The joints in chain order,
// their common IRI prefix once.
std::string no_joint(const ArmSolver& arm, const description::ChainFrames& frames,
                     const std::string& joint, const std::string& how) {
  std::string prefix;
  for (size_t i = 0; i < frames.segments.size(); ++i) {
    const std::string& j = frames.segments[i].joint;
    const std::string p = j.substr(0, j.rfind('/') + 1);
    prefix = i == 0 || p == prefix ? p : "";
  }
  std::string names;
  Nearest nearest(joint);
  for (const description::FrameEntities& s : frames.segments) {
    names += (names.empty() ? "" : ", ") + s.joint.substr(prefix.size());
    nearest.offer(s.joint);
  }
  std::string message = "no joint '" + joint + "' in the chain '" + arm.chain_iri +
                        "'; its joints are " + (names.empty() ? std::string("none") : names) +
                        (prefix.empty() ? "" : " (under " + prefix + ")");
  message += how;
  if (!nearest.best().empty()) message += "; did you mean '" + std::string(nearest.best()) + "'?";
  return message;
}

// A joint position, velocity or measured torque the solver outputs: a scalar
// of the joint its `of-joint` names, in the units of the joint's type: RAD,
// RAD-PER-SEC or N-M on a revolute joint; M, M-PER-SEC or N (a force) on a
// prismatic one (mos-jnt:PrismaticJoint).
template <class JointIndex>
void lower_joint_output(State& st, ArmSolver& arm, TermId o, ArmOutput::What what,
                        const JointIndex& joint_index, const description::ChainFrames& frames,
                        Step& kin) {
  namespace mj = mospec::vocab::mospec_joints;
  const std::string of_joint = mospec::vocab::term(mj::ns, "of-joint");
  const int d = st.datum(o, DataType::Scalar, st.term(arm.iri), "output");
  const Data& dd = st.program.data[static_cast<size_t>(d)];
  const char* kind = what == ArmOutput::What::JointPosition   ? "joint position"
                     : what == ArmOutput::What::JointVelocity ? "joint velocity"
                                                              : "measured joint torque";
  const auto joint = st.object(o, of_joint);
  if (!joint) {
    st.error(o, "missing-property",
             std::string("the ") + kind + " '" + dd.iri +
                 "' names no `of-joint` (mos-jnt:of-joint): the joint of '" + arm.chain_iri +
                 "' it is of");
    return;
  }
  const int j = joint_index(st.str(*joint));
  if (j < 0) {
    st.error(st.where(o, of_joint, *joint), "unknown-joint",
             no_joint(arm, frames, st.str(*joint),
                      std::string(": the ") + kind + " '" + dd.iri +
                          "' is of it, and the solver '" + arm.iri +
                          "' reads that chain; name one of its joints, or output the quantity "
                          "from the solver of that joint's chain"));
    return;
  }
  const bool prismatic = arm.chain.segment(j).type == runtime::JointType::Prismatic;
  const char* unit = what == ArmOutput::What::JointPosition ? (prismatic ? "M" : "RAD")
                     : what == ArmOutput::What::JointVelocity
                         ? (prismatic ? "M-PER-SEC" : "RAD-PER-SEC")
                     : prismatic ? "N"
                                 : "N-M";
  if (dd.unit != unit) {
    st.error(o, "wrong-unit",
             std::string("the ") + kind + " '" + dd.iri + "' of the " +
                 (prismatic ? "prismatic" : "revolute") + " joint '" + st.str(*joint) + "' is in " +
                 unit + ", not in '" + dd.unit + "'");
    return;
  }
  arm.outputs.push_back({what, j, d});
  kin.out.push_back(d);
}

}  // namespace

void lower_arm(State& st, TermId solver) {
  const std::string slv = "task/solver-specification";
  st.pending_iri = st.str(solver);
  ArmSolver arm;
  arm.iri = st.str(solver);
  arm.name = identifier(local_name(arm.iri));
  arm.where = st.where(solver);
  // The vocabulary names the algorithm; mospec's arms run ACHD and nothing else.
  const std::string achd = vocab(slv, "AccelerationConstrainedHybridDynamicsAlgorithm");
  for (TermId algorithm : st.objects(solver, vocab(slv, "solver"))) {
    if (st.str(algorithm) == achd) continue;
    st.error(st.where(solver, vocab(slv, "solver"), algorithm), "unsupported-solver",
             "the solver '" + arm.iri + "' asks for the algorithm '" + st.str(algorithm) +
                 "', but mospec's arms run only the acceleration-constrained hybrid dynamics "
                 "(AccelerationConstrainedHybridDynamicsAlgorithm); state that or leave `solver` "
                 "out");
  }
  auto chain_t = st.object(solver, vocab(slv, "kinematic-chain"));
  if (!chain_t) {
    st.error(solver, "missing-property", "the solver '" + arm.iri + "' names no kinematic-chain");
    return;
  }
  arm.chain_iri = st.str(*chain_t);
  description::ChainFrames frames;
  try {
    description::ChainDescription described = description::describe_chain(
        st.graph.dataset(), st.chain_graphs(arm.chain_iri), arm.chain_iri);
    arm.chain = std::move(described.chain);
    arm.robot_chain = arm.chain;
    frames = std::move(described.frames);
  } catch (const Error& e) {
    st.error(st.where(solver, vocab(slv, "kinematic-chain"), *chain_t), "invalid-chain",
             "the solver '" + arm.iri + "': " + e.diagnostic().message);
    return;
  }
  if (auto it = st.options.ports.find(arm.chain_iri); it != st.options.ports.end()) {
    arm.port = it->second;
  } else {
    std::vector<std::pair<int, std::string>> bound;  // by arm index
    for (const auto& [chain, port] : st.options.ports) bound.emplace_back(port, chain);
    std::sort(bound.begin(), bound.end());
    std::string arms;
    for (const auto& [port, chain] : bound) {
      arms +=
          (arms.empty() ? "" : ", ") + std::string("arm ") + std::to_string(port) + ": " + chain;
    }
    st.error(solver, "unbound-chain",
             "no arm of the robot is bound to the chain '" + arm.chain_iri +
                 "' (the robot's arms drive " + (arms.empty() ? std::string("no chains") : arms) +
                 "); add an arm with this chain to the scenario's world file (`arms`, "
                 "docs/simulation.md) or bind it with --bind CHAIN=ARM");
  }
  // The chain's frames, their origins and links, as the robot model relates
  // them (description::describe_chain): segment i by its frame, its origin
  // point or its link.
  using Entity = std::string description::FrameEntities::*;
  const auto segment_by = [&](const std::string& iri, Entity what) {
    if (iri.empty()) return -1;
    for (size_t i = 0; i < frames.segments.size(); ++i) {
      if (frames.segments[i].*what == iri) return static_cast<int>(i);
    }
    return -1;
  };
  const Entity frame_of = &description::FrameEntities::frame;
  const Entity link_of = &description::FrameEntities::body;
  const auto origin_of = [&](int segment) {
    return frames.segments[static_cast<size_t>(segment)].origin;
  };
  // The chain's tip frame T, a tool fixed to the last moving link (a URDF's
  // tool0, a flange), is the controlled frame of whatever names it or the
  // link the model says holds it (its `simplices`), when that is not the
  // last moving link itself: outputs, drivers and forces are then computed
  // at T, the constant pose composed onto the last segment.
  const std::string last_frame = frames.segments.empty() ? "" : frames.segments.back().frame;
  const std::string tool_body =
      frames.segments.empty() || frames.tip.body == frames.segments.back().body ? ""
                                                                                : frames.tip.body;
  const auto is_tool = [&](const std::string& iri) {
    return !iri.empty() && !frames.segments.empty() && !frames.tip.frame.empty() &&
           (iri == frames.tip.frame || iri == tool_body);
  };
  // How messages name the tool, when the chain has one.
  const std::string tool_named =
      frames.tip.frame.empty() || frames.segments.empty()
          ? std::string()
          : "the tool frame '" + frames.tip.frame + "' (fixed to '" + last_frame + "' by '" +
                frames.tip_pose + "'" +
                (tool_body.empty() ? std::string() : "; its link '" + tool_body + "'") + ")";
  const std::string chain_root_frame = frames.root.frame;
  const std::string chain_root_link = frames.root.body;
  if (auto root = st.object(solver, vocab(slv, "root"))) {
    arm.root_frame = st.str(*root);
  } else {
    st.error(solver, "missing-property", "the solver '" + arm.iri + "' names no root");
    arm.root_frame = chain_root_frame;
  }
  if (arm.root_frame != chain_root_frame) {
    // A solver rooted at, e.g., the platform: the chain hangs from it by a
    // constant mount pose, which becomes part of the first joint's placement.
    std::optional<runtime::Pose> X_RB;
    std::optional<TermId> mount;  // the pose X_RB is read from
    for (TermId p : st.instances(vocab("geometry/spatial-relations", "Pose"))) {
      auto of = st.object(p, vocab("geometry/spatial-relations", "of"));
      auto wrt = st.object(p, vocab("geometry/spatial-relations", "with-respect-to"));
      auto seen = st.object(p, vocab("geometry/coordinates", "as-seen-by"));
      if (!of || !wrt || !seen || st.str(*of) != chain_root_frame ||
          st.str(*wrt) != arm.root_frame || st.str(*seen) != arm.root_frame)
        continue;
      const int d = st.datum(p, DataType::Pose, solver, "mount pose");
      const std::vector<double>& value = st.program.data[static_cast<size_t>(d)].value;
      if (value.empty()) continue;
      if (mount) {
        // A second constant pose of the same mount: the chain and the
        // simulated arm can hang at only one, and which one would be the
        // order of the graph. The same numbers twice are one mount.
        const std::vector<double>& first =
            st.program
                .data[static_cast<size_t>(st.datum(*mount, DataType::Pose, solver, "mount pose"))]
                .value;
        if (first != value) {
          st.error(p, "mount-mismatch",
                   "'" + st.str(p) + "' is a second, different mount pose of '" + chain_root_frame +
                       "' w.r.t. '" + arm.root_frame + "' (the root of '" + arm.chain_iri +
                       "', which the solver '" + arm.iri + "' drives); '" + st.str(*mount) + "' (" +
                       st.place(*mount) +
                       ") already mounts it elsewhere. State the arm's mount once");
        }
        continue;
      }
      X_RB = constant_pose(value);
      mount = p;
      arm.mount_pose_iri = st.str(p);
      arm.X_RB = *X_RB;
    }
    if (!X_RB) {
      st.error(solver, "unsupported-root",
               "the solver '" + arm.iri + "' is rooted at '" + arm.root_frame +
                   "', not at the chain's root '" + chain_root_frame +
                   "'; mospec needs a constant pose of '" + chain_root_frame +
                   "' w.r.t. and seen by '" + arm.root_frame +
                   "' (the mount) to move the chain there");
    } else {
      runtime::Chain rerooted(local_name(arm.root_frame));
      rerooted.add_fixed(arm.chain.root(), *X_RB, runtime::RigidInertia{});
      for (int i = 0; i < arm.chain.size(); ++i) rerooted.add_segment(arm.chain.segment(i));
      if (arm.chain.X_NT().R != runtime::Mat3::Identity() || !arm.chain.X_NT().p.isZero(0.0)) {
        rerooted.add_fixed(arm.chain.tip(), arm.chain.X_NT(), runtime::RigidInertia{});
      }
      arm.chain = std::move(rerooted);
    }
  }
  // Gravity: a uniform field in the root frame.
  if (auto grav = st.object(solver, vocab(slv, "gravity"))) {
    const std::string gc = "geometry/coordinates";
    auto x = st.number(*grav, vocab(gc, "x")), y = st.number(*grav, vocab(gc, "y")),
         z = st.number(*grav, vocab(gc, "z"));
    std::string seen;
    if (auto s = st.object(*grav, vocab(gc, "as-seen-by"))) seen = st.str(*s);
    if (auto s = st.object(*grav, vocab("newtonian-rigid-body-dynamics/coordinates", "as-seen-by")))
      seen = st.str(*s);
    std::string unit;
    if (auto u = st.object(*grav, kQudt + "unit")) unit = local_name(st.str(*u));
    if (!x || !y || !z) {
      st.error(*grav, "missing-property", "the gravity '" + st.str(*grav) + "' needs x, y and z");
    } else if (seen != arm.root_frame) {
      st.error(*grav, "frame-mismatch",
               "the gravity '" + st.str(*grav) + "' is seen by '" + seen + "', but the solver '" +
                   arm.iri + "' needs it in its root frame '" + arm.root_frame + "'");
    } else if (unit != "M-PER-SEC2") {
      st.error(*grav, "wrong-unit",
               "the gravity '" + st.str(*grav) + "' must be in M-PER-SEC2, not '" + unit + "'");
    } else {
      arm.gravity = {*x, *y, *z};
    }
  } else {
    st.error(solver, "missing-property", "the solver '" + arm.iri + "' names no gravity");
  }
  lower_arm_behaviour(st, solver, arm);
  const int arm_index = static_cast<int>(st.program.arms.size());
  // The arm's two steps, named and located by its solver.
  const auto arm_step = [&](StepKind kind, const char* suffix) {
    Step s;
    s.kind = kind;
    s.iri = arm.iri;
    s.name = arm.name + suffix;
    s.where = arm.where;
    s.solver = arm_index;
    return s;
  };
  // Outputs.
  Step kin = arm_step(StepKind::ArmKinematics, "_kinematics");
  // Joint i of the chain (it moves segment i), by the robot model's joint IRI.
  const auto joint_index = [&](const std::string& iri) {
    for (size_t i = 0; i < frames.segments.size(); ++i) {
      if (frames.segments[i].joint == iri) return static_cast<int>(i);
    }
    return -1;
  };
  for (TermId o : st.objects(solver, vocab(slv, "output"))) {
    if (auto joint_output = joint_quantity(st, o)) {
      lower_joint_output(st, arm, o, *joint_output, joint_index, frames, kin);
      continue;
    }
    if (st.has_type(o, mospec::vocab::term(mospec::vocab::mospec_joints::ns, "EstimatedWrench"))) {
      // The wrench on a segment estimated from the measured joint torques:
      // at a segment's origin, seen by the root (runtime::steps::estimated_wrench).
      const int d = st.datum(o, DataType::Wrench, solver, "output");
      const Data& dd = st.program.data[static_cast<size_t>(d)];
      int seg = -1;
      for (size_t i = 0; i < frames.segments.size(); ++i) {
        if (!dd.reference_point.empty() && frames.segments[i].origin == dd.reference_point)
          seg = static_cast<int>(i);
      }
      if (seg < 0 || dd.as_seen_by != arm.root_frame) {
        st.error(
            o, "unsupported-output",
            "the solver '" + arm.iri +
                "' estimates the wrench on a segment at the segment's origin, seen by the "
                "root '" +
                arm.root_frame + "'; '" + dd.iri + "' is at '" + dd.reference_point +
                "' seen by '" + dd.as_seen_by +
                "' (transform it with TransformWrenchToProximal/RotateWrenchToProximalWithPose)");
        continue;
      }
      arm.outputs.push_back({ArmOutput::What::EstimatedWrench, seg, d});
      kin.out.push_back(d);
      continue;
    }
    const auto t = st.type_of(o);
    if (t == DataType::Pose) {
      const int d = st.datum(o, DataType::Pose, solver, "output");
      const Data& dd = st.program.data[static_cast<size_t>(d)];
      const int seg = segment_by(dd.of, frame_of);
      const bool in_root = dd.with_respect_to == arm.root_frame && dd.as_seen_by == arm.root_frame;
      const bool in_chain_root = arm.root_frame != chain_root_frame &&
                                 dd.with_respect_to == chain_root_frame &&
                                 dd.as_seen_by == chain_root_frame;
      if (seg < 0 && (in_root || in_chain_root) && is_tool(dd.of) && dd.of == frames.tip.frame) {
        // The tool's pose: the last segment's composed with the tool's.
        const int last = static_cast<int>(frames.segments.size()) - 1;
        arm.outputs.push_back(
            {in_chain_root ? ArmOutput::What::TipPoseInChainRoot : ArmOutput::What::TipPose, last,
             d});
        kin.out.push_back(d);
        continue;
      }
      if (seg < 0 || !(in_root || in_chain_root)) {
        st.error(o, "unsupported-output",
                 "the solver '" + arm.iri + "' outputs poses of the chain's segment frames" +
                     (tool_named.empty() ? std::string() : " and of " + tool_named) +
                     ", w.r.t. and seen by its root '" + arm.root_frame +
                     "' (or the chain's root '" + chain_root_frame + "'); '" + dd.iri +
                     "' is of '" + dd.of + "' w.r.t. '" + dd.with_respect_to + "' seen by '" +
                     dd.as_seen_by + "'");
        continue;
      }
      if (in_chain_root) {
        arm.outputs.push_back({ArmOutput::What::ChainRootPose, seg, d});
        kin.out.push_back(d);
        continue;
      }
      arm.outputs.push_back({ArmOutput::What::SegmentPose, seg, d});
      kin.out.push_back(d);
    } else if (t == DataType::Twist) {
      const int d = st.datum(o, DataType::Twist, solver, "output");
      const Data& dd = st.program.data[static_cast<size_t>(d)];
      int seg = segment_by(dd.of, link_of);
      if (seg < 0) seg = segment_by(dd.of, frame_of);
      // The tool's twist at its origin: the last segment's, moved there.
      const bool tool = seg < 0 && is_tool(dd.of);
      if (tool) seg = static_cast<int>(frames.segments.size()) - 1;
      const std::string origin = tool ? frames.tip.origin : seg < 0 ? "" : origin_of(seg);
      const bool wrt_root = (!chain_root_link.empty() && dd.with_respect_to == chain_root_link) ||
                            dd.with_respect_to == chain_root_frame ||
                            dd.with_respect_to == arm.root_frame;
      if (seg < 0 || !wrt_root || dd.as_seen_by != arm.root_frame || dd.reference_point.empty() ||
          dd.reference_point != origin) {
        st.error(o, "unsupported-output",
                 "the solver '" + arm.iri + "' outputs twists of a segment" +
                     (tool_named.empty() ? std::string() : ", or of " + tool_named + ",") +
                     " w.r.t. the root, at its origin, seen by the root '" + arm.root_frame +
                     "'; '" + dd.iri + "' does not fit");
        continue;
      }
      arm.outputs.push_back(
          {tool ? ArmOutput::What::TipTwist : ArmOutput::What::SegmentTwist, seg, d});
      kin.out.push_back(d);
    } else {
      st.error(
          o, "unsupported-output",
          "the solver '" + arm.iri + "' cannot output '" + st.str(o) + "' (poses and twists only)");
    }
  }
  // Motion drivers and their priority levels.
  auto drivers = st.object(solver, vocab(slv, "motion-drivers"));
  Step solve = arm_step(StepKind::ArmSolve, "_solve");
  // The link of the last segment, as the robot model relates it to its frame.
  const std::string last_link = frames.segments.empty() ? "" : frames.segments.back().body;
  if (!drivers) {
    st.error(solver, "missing-property", "the solver '" + arm.iri + "' names no motion-drivers");
  } else {
    std::pmr::map<uint32_t, int> level_of{&st.arena};  // scratch (the arena)
    int level = 0;
    for (TermId head : st.objects(*drivers, vocab(slv, "prioritization-hierarchy"))) {
      for (TermId lv : st.list(head)) {
        std::vector<std::string> names;
        for (TermId d : st.objects(lv, vocab(slv, "motion-drivers"))) {
          level_of[d.index] = level;
          names.push_back(st.str(d));
        }
        arm.priority_levels.push_back(names);
        ++level;
      }
    }
    const auto level_for = [&](TermId spec) {
      auto it = level_of.find(spec.index);
      if (it == level_of.end()) {
        if (!arm.priority_levels.empty())
          st.error(spec, "unprioritised-driver",
                   "the motion driver '" + st.str(spec) + "' is in no prioritization level of '" +
                       st.str(*drivers) + "'");
        return 0;
      }
      return it->second;
    };
    std::map<int, TermId> constrained_by;  // tip component -> its acceleration constraint
    // The first acceleration-constraint specification, and whether it acts at the tool.
    std::optional<std::pair<TermId, bool>> acting_at;
    for (TermId spec : st.objects(*drivers, vocab(slv, "acceleration-constraint"))) {
      st.pending_iri = st.str(spec);
      const int lv = level_for(spec);
      if (lv != 0) {
        st.error(spec, "unsupported-priority",
                 "acceleration constraints must be in the highest priority level: one ACHD solve "
                 "honours one level of constraints; '" +
                     st.str(spec) + "' is in level " + std::to_string(lv + 1));
      }
      auto link = st.object(spec, vocab(slv, "attached-to"));
      const std::string attached = link ? st.str(*link) : std::string("nothing");
      if (link && is_tool(attached)) {
        // At the tool: ACHD's tip frame T is the tool (achd_model).
        if (!acting_at) acting_at = {spec, true};
      } else if (last_link.empty() && !frames.segments.empty()) {
        st.error(
            spec, "unsupported-attachment",
            "ACHD constrains the chain's last segment, but no link of the robot model holds its "
            "frame '" +
                frames.segments.back().frame +
                "' (state the link's `simplices`: its frame and origin point, as "
                "robots/kinova-gen3.jsonld does); '" +
                st.str(spec) + "' is attached to '" + attached + "'");
      } else if (attached != last_link) {
        st.error(spec, "unsupported-attachment",
                 "ACHD constrains the chain's last segment '" + last_link + "' at its origin" +
                     (tool_named.empty() ? std::string()
                                         : ", or " + tool_named + " at the tool's origin") +
                     "; '" + st.str(spec) + "' is attached to '" + attached + "'");
      } else if (!acting_at) {
        acting_at = {spec, false};
      }
      // One ACHD solve constrains one frame: every acceleration constraint
      // of the solver acts at the last link's origin, or every one at the tool's.
      if (acting_at && link && (attached == last_link || is_tool(attached)) &&
          acting_at->second != is_tool(attached)) {
        st.error(spec, "unsupported-attachment",
                 "'" + st.str(spec) + "' is attached to '" + attached + "', but '" +
                     st.str(acting_at->first) + "' (" + st.place(acting_at->first) + ") to '" +
                     st.str(*st.object(acting_at->first, vocab(slv, "attached-to"))) +
                     "': one ACHD solve constrains one frame of the chain, the last segment '" +
                     last_link + "' or " + tool_named +
                     "; attach every acceleration constraint of '" + arm.iri +
                     "' to the same one (a constraint at the last link's origin can be stated "
                     "at the tool's: the tool moves with that link)");
      }
      for (TermId c : st.objects(spec, vocab(slv, "constraints"))) {
        AccelerationConstraint ac;
        ac.iri = st.str(c);
        ac.level = lv;
        auto sub = st.object(c, vocab(slv, "subspace"));
        auto axis = st.object(c, vocab(slv, "axis"));
        const std::string sn = sub ? local_name(st.str(*sub)) : "",
                          an = axis ? local_name(st.str(*axis)) : "";
        const int base = sn == "angular-acceleration" ? 0 : sn == "linear-acceleration" ? 3 : -1;
        const int ax = an == "x" ? 0 : an == "y" ? 1 : an == "z" ? 2 : -1;
        if (base < 0 || ax < 0) {
          st.error(c, "invalid-constraint",
                   "the acceleration constraint '" + ac.iri +
                       "' needs subspace linear-/angular-acceleration and axis x, y or z");
          continue;
        }
        ac.component = base + ax;
        // A second constraint on a direction ACHD already constrains makes
        // its system singular, and the solve would average the two.
        if (auto first = constrained_by.emplace(ac.component, c); !first.second) {
          st.error(c, "driven-twice",
                   "'" + ac.iri + "' constrains the " + sn + " along " + an + " of '" + arm.iri +
                       "', which '" + st.str(first.first->second) + "' (" +
                       st.place(first.first->second) +
                       ") already constrains; ACHD would average the two. Drive each direction "
                       "once: remove one, or combine their controllers' outputs with an operator");
          continue;
        }
        auto energy = st.object(c, vocab(slv, "acceleration-energy"));
        if (!energy) {
          st.error(c, "missing-property",
                   "the acceleration constraint '" + ac.iri + "' names no acceleration-energy");
          continue;
        }
        ac.energy = st.datum(*energy, DataType::Scalar, c, "acceleration-energy");
        solve.in.push_back(ac.energy);
        arm.acceleration_constraints.push_back(ac);
      }
    }
    arm.tip_is_last_segment = !(acting_at && acting_at->second);
    // One constraint per tip direction (driven-twice) keeps them within
    // runtime::kMaxConstraints; the verifier checks it again.
    for (TermId spec : st.objects(*drivers, vocab(slv, "cartesian-force"))) {
      st.pending_iri = st.str(spec);
      CartesianForce cf;
      cf.iri = st.str(spec);
      cf.level = level_for(spec);
      if (cf.level != 0) {
        // ACHD adds every Cartesian force to one solve, where each acts in
        // what the acceleration constraints leave free; a force of a lower
        // level would not yield to the forces above it.
        st.error(spec, "unsupported-priority",
                 "Cartesian forces must be in the highest priority level: one ACHD solve adds "
                 "every force alike (each acting where the acceleration constraints leave "
                 "freedom), so a lower level would not yield to the forces above it; '" +
                     cf.iri + "' is in level " + std::to_string(cf.level + 1));
      }
      auto link = st.object(spec, vocab(slv, "attached-to"));
      auto force = st.object(spec, vocab(slv, "force"));
      if (!link || !force) {
        st.error(spec, "missing-property",
                 "the Cartesian force '" + cf.iri + "' needs `force` and `attached-to`");
        continue;
      }
      cf.segment = segment_by(st.str(*link), link_of);
      if (cf.segment < 0 && is_tool(st.str(*link))) {
        // On the tool: applied at its origin, moved to the last segment's each tick.
        cf.segment = static_cast<int>(frames.segments.size()) - 1;
        cf.at_tip = true;
      }
      if (cf.segment < 0) {
        st.error(spec, "unknown-link",
                 "'" + cf.iri + "' is attached to '" + st.str(*link) +
                     "', which is no moving link of '" + arm.chain_iri + "'" +
                     (tool_named.empty() ? std::string() : " nor " + tool_named));
        continue;
      }
      cf.wrench = st.datum(*force, DataType::Wrench, spec, "force");
      const Data& w = st.program.data[static_cast<size_t>(cf.wrench)];
      const std::string origin = cf.at_tip ? frames.tip.origin : origin_of(cf.segment);
      if (origin.empty() || w.reference_point != origin || w.as_seen_by != arm.root_frame) {
        st.error(
            *force, "frame-mismatch",
            "the wrench '" + w.iri + "' drives '" + st.str(*link) + "' through '" + cf.iri +
                "', so ACHD needs it at " + (cf.at_tip ? "the tool's" : "that link's") +
                " origin '" + origin + "' and seen by the root '" + arm.root_frame +
                "'; it is at '" + w.reference_point + "' seen by '" + w.as_seen_by +
                "' (transform it with TransformWrenchToProximal/RotateWrenchToProximalWithPose)");
      }
      solve.in.push_back(cf.wrench);
      arm.cartesian_forces.push_back(cf);
    }
    // A joint force adds its scalar to the joint's feed-forward torque
    // (ACHD's tau_ff), which acts in the directions the acceleration
    // constraints leave free.
    for (TermId spec : st.objects(*drivers, vocab(slv, "joint-force"))) {
      st.pending_iri = st.str(spec);
      JointForce jf;
      jf.iri = st.str(spec);
      jf.level = level_for(spec);
      if (jf.level != 0) {
        st.error(spec, "unsupported-priority",
                 "joint forces must be in the highest priority level: one ACHD solve adds every "
                 "feed-forward joint force alike, so a lower level would not yield to the drivers "
                 "above it; '" +
                     jf.iri + "' is in level " + std::to_string(jf.level + 1));
      }
      auto joint = st.object(spec, vocab(slv, "attached-to"));
      auto force = st.object(spec, vocab(slv, "force"));
      if (!joint || !force) {
        st.error(spec, "missing-property",
                 "the joint force '" + jf.iri + "' needs `force` and `attached-to` (a joint)");
        continue;
      }
      jf.joint = joint_index(st.str(*joint));
      if (jf.joint < 0) {
        st.error(st.where(spec, vocab(slv, "attached-to"), *joint), "unknown-joint",
                 no_joint(arm, frames, st.str(*joint),
                          ": '" + jf.iri + "' is attached to it, and the solver '" + arm.iri +
                              "' drives that chain; attach it to one of its joints"));
        continue;
      }
      jf.force = st.datum(*force, DataType::Scalar, spec, "force");
      const Data& f = st.program.data[static_cast<size_t>(jf.force)];
      // A revolute joint is driven by a torque, a prismatic one by a force.
      const bool prismatic = arm.chain.segment(jf.joint).type == runtime::JointType::Prismatic;
      if (f.unit != (prismatic ? "N" : "N-M")) {
        st.error(
            *force, "wrong-unit",
            "the joint force '" + f.iri + "' drives the " + (prismatic ? "prismatic" : "revolute") +
                " joint '" + st.str(*joint) + "' through '" + jf.iri + "', so it is " +
                (prismatic ? "a force in N" : "a torque in N-M") + ", not in '" + f.unit + "'");
      }
      solve.in.push_back(jf.force);
      arm.joint_forces.push_back(jf);
    }
  }
  // Drivers a level lists but the solver's drivers do not.
  st.pending_iri = arm.iri;
  // Whether the tick's solve lost constraint directions (ACHD's
  // ConstraintsDegraded: the coupling matrix is singular in this
  // configuration, or the constraints conflict): logged, and counted by a run.
  solve.out = {
      st.synthetic(arm.iri + "#degraded", arm.name + "_degraded", DataType::Flag, arm.where)};
  st.program.arms.push_back(std::move(arm));
  st.add_step(std::move(kin));
  st.add_step(std::move(solve));
}

namespace {

// The tip's spatial-acceleration components, in ACHD's order, as messages name them.
constexpr const char* kComponent[6] = {"angular x", "angular y", "angular z",
                                       "linear x",  "linear y",  "linear z"};

// An acceleration constraint's energy is what a controller asks of one tip
// direction: it must be an acceleration energy, and a controller of a linear
// quantity (M, M-PER-SEC) drives a linear direction, one of an angle an
// angular one. Known once controllers are lowered.
void check_acceleration_energies(State& st, const ArmSolver& arm) {
  for (const AccelerationConstraint& ac : arm.acceleration_constraints) {
    const Data& energy = st.program.data[static_cast<size_t>(ac.energy)];
    const TermId constraint = st.term(ac.iri);
    if (!energy.unit.empty() && energy.unit != "N-M2-PER-SEC2") {
      st.error(constraint, "wrong-unit",
               "the acceleration constraint '" + ac.iri + "' takes '" + energy.iri +
                   "' as its acceleration energy, but it is in '" + energy.unit +
                   "'; an acceleration energy is in N-M2-PER-SEC2 (a controller's output meant "
                   "for a force is applied through a wrench and a CartesianForceSpecification)");
      continue;
    }
    const auto it = st.producer.find(ac.energy);
    if (it == st.producer.end()) continue;
    const Step& controller = st.steps[static_cast<size_t>(it->second)];
    if (controller.kind != StepKind::Controller || controller.in.empty()) continue;
    const Data& signal = st.program.data[static_cast<size_t>(controller.in[0])];
    const bool linear = signal.unit == "M" || signal.unit == "M-PER-SEC";
    const bool angular = signal.unit == "RAD" || signal.unit == "RAD-PER-SEC";
    if ((ac.component < 3 && linear) || (ac.component >= 3 && angular)) {
      st.error(constraint, "subspace-mismatch",
               "the acceleration constraint '" + ac.iri + "' drives the " +
                   kComponent[ac.component] + " acceleration of '" + arm.iri +
                   "', but its energy '" + energy.iri + "' comes from '" + controller.iri +
                   "', which controls '" + signal.iri + "' (in '" + signal.unit + "', " +
                   (linear ? "a linear" : "an angular") + " quantity); constrain the " +
                   (linear ? "linear" : "angular") +
                   "-acceleration subspace, or feed it a controller of " +
                   (linear ? "an angular" : "a linear") + " quantity");
    }
  }
}

// A controller acting directly on the error of a less-than/greater-than
// constraint drives its acceleration constraint one-sided: the row is engaged
// only while the quantity is beyond the bound, within the constraint's
// tolerance (runtime::steps::one_sided_engaged), so a satisfied bound leaves
// its direction free instead of locking it, and a bound a PD approaches
// asymptotically is released once the quantity is close enough. An inequality reached
// through anything else (an operator mixing it with other signals) has no
// single error that says when the bound is reached: refused.
bool evaluates_inequality(const Step& step) {
  return step.kind == StepKind::Evaluate &&
         (step.constraint.kind == runtime::ConstraintKind::LessThan ||
          step.constraint.kind == runtime::ConstraintKind::GreaterThan);
}

void mark_one_sided(State& st, ArmSolver& arm, Step& solve) {
  for (AccelerationConstraint& ac : arm.acceleration_constraints) {
    const auto from = st.producer.find(ac.energy);
    if (from == st.producer.end() || from->second < 0) continue;
    const Step& controller = st.steps[static_cast<size_t>(from->second)];
    if (controller.kind == StepKind::Controller && !controller.in.empty()) {
      const auto e = st.producer.find(controller.in[0]);
      if (e != st.producer.end() && e->second >= 0) {
        if (const Step& evaluate = st.steps[static_cast<size_t>(e->second)];
            evaluates_inequality(evaluate)) {
          ac.engaged_by = controller.in[0];
          ac.tolerance = evaluate.constraint.tolerance;
          solve.in.push_back(ac.engaged_by);
          continue;
        }
      }
    }
    // Anything else upstream: look for an inequality feeding it indirectly.
    std::pmr::set<int> seen{&st.arena};  // scratch, from the lowering's arena
    std::vector<int> todo{ac.energy};
    while (!todo.empty()) {
      const int d = todo.back();
      todo.pop_back();
      if (!seen.insert(d).second) continue;
      const auto it = st.producer.find(d);
      if (it == st.producer.end() || it->second < 0) continue;
      const Step& p = st.steps[static_cast<size_t>(it->second)];
      if (evaluates_inequality(p)) {
        st.error(st.term(ac.iri), "unsupported-one-sided",
                 "the acceleration constraint '" + ac.iri + "' is driven by the inequality '" +
                     p.iri + "' through '" + controller.iri +
                     "', not by a controller acting on its error alone; a less-than or "
                     "greater-than constraint drives a direction one-sided (only while it is "
                     "violated), which mospec can do only when one controller acts directly on "
                     "that constraint's error: feed the controller the evaluator's error, or "
                     "use an equality or bilateral constraint");
        break;
      }
      // Signals flow through controllers (not their running flag) and operators.
      if (p.kind == StepKind::Controller) {
        const size_t signals = controller_kinds()[static_cast<size_t>(p.controller)].in.size();
        todo.insert(todo.end(), p.in.begin(),
                    p.in.begin() + static_cast<std::ptrdiff_t>(std::min(signals, p.in.size())));
      } else if (p.kind == StepKind::Operator) {
        todo.insert(todo.end(), p.in.begin(), p.in.end());
      }
    }
  }
}

}  // namespace

// A Cartesian force on the constrained segment whose view writes a component
// an acceleration constraint also drives: ACHD satisfies the constraint and
// cancels that component of the force, silently. Known once views are
// lowered: a wrench assembled by views writes exactly their components (a
// wrench an operator computes may point anywhere and is not judged here).
void check_driver_directions(State& st) {
  for (size_t a = 0; a < st.program.arms.size(); ++a) {
    ArmSolver& arm = st.program.arms[a];
    check_acceleration_energies(st, arm);
    for (Step& solve : st.steps) {
      if (solve.kind == StepKind::ArmSolve && solve.solver == static_cast<int>(a))
        mark_one_sided(st, arm, solve);
    }
    // One wrench applied by two Cartesian forces would push twice.
    std::map<int, const CartesianForce*> applied_by;
    for (const CartesianForce& cf : arm.cartesian_forces) {
      auto [it, fresh] = applied_by.emplace(cf.wrench, &cf);
      if (fresh) continue;
      st.error(st.term(cf.iri), "driven-twice",
               "the Cartesian forces '" + it->second->iri + "' (" +
                   st.place(st.term(it->second->iri)) + ") and '" + cf.iri + "' both apply '" +
                   st.program.data[static_cast<size_t>(cf.wrench)].iri + "' to '" + arm.iri +
                   "', so ACHD would push with it twice; apply each wrench once");
    }
    const int last = arm.chain.size() - 1;
    for (const CartesianForce& cf : arm.cartesian_forces) {
      // Only a force at the point the constraints act at (both at the last
      // link's origin, or both at the tool's).
      if (cf.segment != last || cf.at_tip == arm.tip_is_last_segment) continue;
      const auto it = st.producer.find(cf.wrench);
      if (it == st.producer.end()) continue;
      const Step& writer = st.steps[static_cast<size_t>(it->second)];
      if (writer.kind != StepKind::ViewWrite) continue;
      for (int component : writer.views) {
        for (const AccelerationConstraint& ac : arm.acceleration_constraints) {
          // A one-sided row cancels the force only while its bound is hit:
          // the force moves the tip until then (a limit, not a conflict).
          if (ac.component != component || ac.engaged_by >= 0) continue;
          const TermId force = st.term(cf.iri), constraint = st.term(ac.iri);
          st.error(force, "driven-twice",
                   "the Cartesian force '" + cf.iri + "' pushes along the " +
                       kComponent[component] + " of '" + arm.iri +
                       "', which the acceleration constraint '" + ac.iri + "' (" +
                       st.place(constraint) +
                       ") drives: ACHD would cancel that part of the force. Drive each "
                       "direction once: drop the constraint on it, or the force's view of it");
        }
      }
    }
  }
}

// Which motions drive each arm and the base: the running flags gating the controllers and
// assignments whose outputs reach the arm's drivers, through any operators.
void gate_arm_solves(State& st) {
  for (Step& solve : st.steps) {
    if (solve.kind != StepKind::ArmSolve && solve.kind != StepKind::BaseForceDistribution) continue;
    solve.n_drivers = static_cast<int>(solve.in.size());
    std::pmr::set<int> gates{&st.arena}, seen_data{&st.arena};  // scratch (the arena)
    std::vector<int> todo(solve.in.begin(), solve.in.end());
    while (!todo.empty()) {
      const int d = todo.back();
      todo.pop_back();
      if (!seen_data.insert(d).second) continue;
      auto it = st.producer.find(d);
      if (it == st.producer.end() || it->second < 0) continue;
      const Step& p = st.steps[static_cast<size_t>(it->second)];
      // A gated step's running flag: a controller's after its signals, an
      // assignment's after its value.
      const size_t gate =
          p.kind == StepKind::Controller
              ? controller_kinds()[static_cast<size_t>(p.controller)].in.size()
          : p.kind == StepKind::Evaluate && p.constraint.kind == runtime::ConstraintKind::Assignment
              ? 1
              : p.in.size();
      const bool gated = gate + 1 == p.in.size();
      if (gated) gates.insert(p.in[gate]);
      if (p.kind == StepKind::GuardedMotion || p.kind == StepKind::ArmKinematics ||
          p.kind == StepKind::BaseVelocityComposition)
        continue;
      for (size_t k = 0; k < p.in.size(); ++k) {
        if (gated && k == gate) continue;
        todo.push_back(p.in[k]);
      }
    }
    solve.in.insert(solve.in.end(), gates.begin(), gates.end());
    // An arm some motion gates is idle while none of them runs: the model
    // says what it does then.
    if (solve.kind == StepKind::ArmSolve && !gates.empty()) {
      const ArmSolver& arm = st.program.arms[static_cast<size_t>(solve.solver)];
      if (arm.idle == ArmSolver::Idle::Unstated && !arm.idle_where.known())  // else refused there
        st.error(arm.where, "unstated-idle",
                 "the solver '" + arm.iri +
                     "' drives its arm only while its motions run; say what the arm does "
                     "before and after them: `when-idle` (mospec/solver) naming a BrakeAndHold "
                     "with a `time-constant`, or a Float");
    }
  }
}

}  // namespace mospec::ir::lowering
