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

// The solver's chain as the robot model relates its frames, their origins and
// links (description::describe_chain): segment i by its frame, its origin
// point or its link; joint i (it moves segment i) by its joint.
//
// The chain's tip frame T, a tool fixed to the last moving link (a URDF's
// tool0, a flange), is the controlled frame of whatever names it or the link
// the model says holds it (its `simplices`), when that is not the last moving
// link itself: outputs, drivers and forces are then computed at T, the
// constant pose composed onto the last segment.
class ChainView {
 public:
  explicit ChainView(description::ChainFrames frames) : frames_(std::move(frames)) {
    if (frames_.segments.empty()) return;
    last_frame_ = frames_.segments.back().frame;
    last_link_ = frames_.segments.back().body;
    if (frames_.tip.body != last_link_) tool_body_ = frames_.tip.body;
    if (frames_.tip.frame.empty()) return;
    tool_named_ = "the tool frame '" + frames_.tip.frame + "' (fixed to '" + last_frame_ +
                  "' by '" + frames_.tip_pose + "'" +
                  (tool_body_.empty() ? std::string() : "; its link '" + tool_body_ + "'") + ")";
  }
  const description::ChainFrames& frames() const { return frames_; }
  int segment_by_frame(const std::string& iri) const {
    return find(iri, &description::FrameEntities::frame);
  }
  int segment_by_link(const std::string& iri) const {
    return find(iri, &description::FrameEntities::body);
  }
  int joint_index(const std::string& iri) const {
    return find(iri, &description::FrameEntities::joint);
  }
  // The last segment whose origin is `point`.
  int segment_by_origin(const std::string& point) const {
    int seg = -1;
    for (size_t i = 0; i < frames_.segments.size(); ++i) {
      if (!point.empty() && frames_.segments[i].origin == point) seg = static_cast<int>(i);
    }
    return seg;
  }
  const std::string& origin_of(int segment) const {
    return frames_.segments[static_cast<size_t>(segment)].origin;
  }
  int last() const { return static_cast<int>(frames_.segments.size()) - 1; }
  bool empty() const { return frames_.segments.empty(); }
  const std::string& root_frame() const { return frames_.root.frame; }
  const std::string& root_link() const { return frames_.root.body; }
  const std::string& last_frame() const { return last_frame_; }
  // The link of the last segment, as the robot model relates it to its frame.
  const std::string& last_link() const { return last_link_; }
  const std::string& tip_frame() const { return frames_.tip.frame; }
  const std::string& tip_origin() const { return frames_.tip.origin; }
  bool is_tool(const std::string& iri) const {
    return !iri.empty() && !empty() && !frames_.tip.frame.empty() &&
           (iri == frames_.tip.frame || iri == tool_body_);
  }
  // How messages name the tool, when the chain has one ("" otherwise).
  const std::string& tool_named() const { return tool_named_; }

 private:
  using Entity = std::string description::FrameEntities::*;
  int find(const std::string& iri, Entity what) const {
    if (iri.empty()) return -1;
    for (size_t i = 0; i < frames_.segments.size(); ++i) {
      if (frames_.segments[i].*what == iri) return static_cast<int>(i);
    }
    return -1;
  }
  description::ChainFrames frames_;
  std::string last_frame_, last_link_, tool_body_, tool_named_;
};

constexpr std::string_view kSlv = "task/solver-specification";

// One solver being lowered: its term, the arm it becomes and that arm's chain.
struct ArmScope {
  State& st;
  TermId solver;
  ArmSolver& arm;
  const ChainView& chain;
};

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

// The unit of a joint quantity of a revolute or prismatic joint.
const char* joint_unit(ArmOutput::What what, bool prismatic) {
  if (what == ArmOutput::What::JointPosition) return prismatic ? "M" : "RAD";
  if (what == ArmOutput::What::JointVelocity) return prismatic ? "M-PER-SEC" : "RAD-PER-SEC";
  return prismatic ? "N" : "N-M";
}

// A joint position, velocity or measured torque the solver outputs: a scalar
// of the joint its `of-joint` names, in the units of the joint's type: RAD,
// RAD-PER-SEC or N-M on a revolute joint; M, M-PER-SEC or N (a force) on a
// prismatic one (mos-jnt:PrismaticJoint).
void lower_joint_output(const ArmScope& a, TermId o, ArmOutput::What what, Step& kin) {
  namespace mj = mospec::vocab::mospec_joints;
  State& st = a.st;
  const std::string of_joint = mospec::vocab::term(mj::ns, "of-joint");
  const int d = st.datum(o, DataType::Scalar, st.term(a.arm.iri), "output");
  const Data& dd = st.program.data[static_cast<size_t>(d)];
  const char* kind = what == ArmOutput::What::JointPosition   ? "joint position"
                     : what == ArmOutput::What::JointVelocity ? "joint velocity"
                                                              : "measured joint torque";
  const auto joint = st.object(o, of_joint);
  if (!joint) {
    st.error(o, "missing-property",
             std::string("the ") + kind + " '" + dd.iri +
                 "' names no `of-joint` (mos-jnt:of-joint): the joint of '" + a.arm.chain_iri +
                 "' it is of");
    return;
  }
  const int j = a.chain.joint_index(st.str(*joint));
  if (j < 0) {
    st.error(st.where(o, of_joint, *joint), "unknown-joint",
             no_joint(a.arm, a.chain.frames(), st.str(*joint),
                      std::string(": the ") + kind + " '" + dd.iri +
                          "' is of it, and the solver '" + a.arm.iri +
                          "' reads that chain; name one of its joints, or output the quantity "
                          "from the solver of that joint's chain"));
    return;
  }
  const bool prismatic = a.arm.chain.segment(j).type == runtime::JointType::Prismatic;
  const char* unit = joint_unit(what, prismatic);
  if (dd.unit != unit) {
    st.error(o, "wrong-unit",
             std::string("the ") + kind + " '" + dd.iri + "' of the " +
                 (prismatic ? "prismatic" : "revolute") + " joint '" + st.str(*joint) + "' is in " +
                 unit + ", not in '" + dd.unit + "'");
    return;
  }
  a.arm.outputs.push_back({what, j, d});
  kin.out.push_back(d);
}

// The vocabulary names the algorithm; mospec's arms run ACHD and nothing else.
void check_algorithm(State& st, TermId solver, const ArmSolver& arm) {
  const std::string achd = vocab(kSlv, "AccelerationConstrainedHybridDynamicsAlgorithm");
  for (TermId algorithm : st.objects(solver, vocab(kSlv, "solver"))) {
    if (st.str(algorithm) == achd) continue;
    st.error(st.where(solver, vocab(kSlv, "solver"), algorithm), "unsupported-solver",
             "the solver '" + arm.iri + "' asks for the algorithm '" + st.str(algorithm) +
                 "', but mospec's arms run only the acceleration-constrained hybrid dynamics "
                 "(AccelerationConstrainedHybridDynamicsAlgorithm); state that or leave `solver` "
                 "out");
  }
}

// The solver's kinematic chain, as its robot model describes it; nullopt when
// it names none or the description is refused (reported).
std::optional<ChainView> read_chain(State& st, TermId solver, ArmSolver& arm) {
  auto chain_t = st.object(solver, vocab(kSlv, "kinematic-chain"));
  if (!chain_t) {
    st.error(solver, "missing-property", "the solver '" + arm.iri + "' names no kinematic-chain");
    return std::nullopt;
  }
  arm.chain_iri = st.str(*chain_t);
  try {
    description::ChainDescription described = description::describe_chain(
        st.graph.dataset(), st.chain_graphs(arm.chain_iri), arm.chain_iri);
    arm.chain = std::move(described.chain);
    arm.robot_chain = arm.chain;
    return ChainView(std::move(described.frames));
  } catch (const Error& e) {
    st.error(st.where(solver, vocab(kSlv, "kinematic-chain"), *chain_t), "invalid-chain",
             "the solver '" + arm.iri + "': " + e.diagnostic().message);
    return std::nullopt;
  }
}

// The arm of the robot the solver's chain is bound to (--bind, or the
// scenario's world file).
void bind_port(State& st, TermId solver, ArmSolver& arm) {
  if (auto it = st.options.ports.find(arm.chain_iri); it != st.options.ports.end()) {
    arm.port = it->second;
    return;
  }
  std::vector<std::pair<int, std::string>> bound;  // by arm index
  for (const auto& [chain, port] : st.options.ports) bound.emplace_back(port, chain);
  std::sort(bound.begin(), bound.end());
  std::string arms;
  for (const auto& [port, chain] : bound) {
    arms += (arms.empty() ? "" : ", ") + std::string("arm ") + std::to_string(port) + ": " + chain;
  }
  st.error(solver, "unbound-chain",
           "no arm of the robot is bound to the chain '" + arm.chain_iri +
               "' (the robot's arms drive " + (arms.empty() ? std::string("no chains") : arms) +
               "); add an arm with this chain to the scenario's world file (`arms`, "
               "docs/simulation.md) or bind it with --bind CHAIN=ARM");
}

// The constant pose of the chain's root w.r.t. and seen by the solver's root
// (the mount), if the model states one; a second, different one is refused.
std::optional<runtime::Pose> find_mount(const ArmScope& a) {
  State& st = a.st;
  ArmSolver& arm = a.arm;
  const std::string& chain_root = a.chain.root_frame();
  std::optional<runtime::Pose> X_RB;
  std::optional<TermId> mount;  // the pose X_RB is read from
  for (TermId p : st.instances(vocab("geometry/spatial-relations", "Pose"))) {
    auto of = st.object(p, vocab("geometry/spatial-relations", "of"));
    auto wrt = st.object(p, vocab("geometry/spatial-relations", "with-respect-to"));
    auto seen = st.object(p, vocab("geometry/coordinates", "as-seen-by"));
    if (!of || !wrt || !seen || st.str(*of) != chain_root || st.str(*wrt) != arm.root_frame ||
        st.str(*seen) != arm.root_frame)
      continue;
    const int d = st.datum(p, DataType::Pose, a.solver, "mount pose");
    const std::vector<double>& value = st.program.data[static_cast<size_t>(d)].value;
    if (value.empty()) continue;
    if (mount) {
      // A second constant pose of the same mount: the chain and the
      // simulated arm can hang at only one, and which one would be the
      // order of the graph. The same numbers twice are one mount.
      const int first = st.datum(*mount, DataType::Pose, a.solver, "mount pose");
      if (st.program.data[static_cast<size_t>(first)].value != value) {
        st.error(p, "mount-mismatch",
                 "'" + st.str(p) + "' is a second, different mount pose of '" + chain_root +
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
  return X_RB;
}

// The chain hung from the solver's root by the constant mount pose, which
// becomes part of the first joint's placement.
void reroot(ArmSolver& arm, const runtime::Pose& X_RB) {
  runtime::Chain rerooted(local_name(arm.root_frame));
  rerooted.add_fixed(arm.chain.root(), X_RB, runtime::RigidInertia{});
  for (int i = 0; i < arm.chain.size(); ++i) rerooted.add_segment(arm.chain.segment(i));
  if (arm.chain.X_NT().R != runtime::Mat3::Identity() || !arm.chain.X_NT().p.isZero(0.0)) {
    rerooted.add_fixed(arm.chain.tip(), arm.chain.X_NT(), runtime::RigidInertia{});
  }
  arm.chain = std::move(rerooted);
}

// The solver's root frame; a solver rooted elsewhere than its chain (e.g. at
// the platform) needs the chain's constant mount pose there.
void lower_root(const ArmScope& a) {
  State& st = a.st;
  ArmSolver& arm = a.arm;
  const std::string& chain_root = a.chain.root_frame();
  if (auto root = st.object(a.solver, vocab(kSlv, "root"))) {
    arm.root_frame = st.str(*root);
  } else {
    st.error(a.solver, "missing-property", "the solver '" + arm.iri + "' names no root");
    arm.root_frame = chain_root;
  }
  if (arm.root_frame == chain_root) return;
  if (const std::optional<runtime::Pose> X_RB = find_mount(a)) {
    reroot(arm, *X_RB);
    return;
  }
  st.error(a.solver, "unsupported-root",
           "the solver '" + arm.iri + "' is rooted at '" + arm.root_frame +
               "', not at the chain's root '" + chain_root +
               "'; mospec needs a constant pose of '" + chain_root + "' w.r.t. and seen by '" +
               arm.root_frame + "' (the mount) to move the chain there");
}

// Gravity: a uniform field in the root frame.
void lower_gravity(State& st, TermId solver, ArmSolver& arm) {
  auto grav = st.object(solver, vocab(kSlv, "gravity"));
  if (!grav) {
    st.error(solver, "missing-property", "the solver '" + arm.iri + "' names no gravity");
    return;
  }
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
}

// The wrench on a segment estimated from the measured joint torques: at a
// segment's origin, seen by the root (runtime::steps::estimated_wrench).
void lower_estimated_wrench(const ArmScope& a, TermId o, Step& kin) {
  const int d = a.st.datum(o, DataType::Wrench, a.solver, "output");
  const Data& dd = a.st.program.data[static_cast<size_t>(d)];
  const int seg = a.chain.segment_by_origin(dd.reference_point);
  if (seg < 0 || dd.as_seen_by != a.arm.root_frame) {
    a.st.error(
        o, "unsupported-output",
        "the solver '" + a.arm.iri +
            "' estimates the wrench on a segment at the segment's origin, seen by the "
            "root '" +
            a.arm.root_frame + "'; '" + dd.iri + "' is at '" + dd.reference_point + "' seen by '" +
            dd.as_seen_by +
            "' (transform it with TransformWrenchToProximal/RotateWrenchToProximalWithPose)");
    return;
  }
  a.arm.outputs.push_back({ArmOutput::What::EstimatedWrench, seg, d});
  kin.out.push_back(d);
}

// A pose of a segment frame (or of the tool frame) w.r.t. and seen by the
// solver's root, or by the chain's own root.
void lower_pose_output(const ArmScope& a, TermId o, Step& kin) {
  const ArmSolver& arm = a.arm;
  const std::string& chain_root = a.chain.root_frame();
  const int d = a.st.datum(o, DataType::Pose, a.solver, "output");
  const Data& dd = a.st.program.data[static_cast<size_t>(d)];
  int seg = a.chain.segment_by_frame(dd.of);
  const bool in_root = dd.with_respect_to == arm.root_frame && dd.as_seen_by == arm.root_frame;
  const bool in_chain_root = arm.root_frame != chain_root && dd.with_respect_to == chain_root &&
                             dd.as_seen_by == chain_root;
  const bool tool = seg < 0 && (in_root || in_chain_root) && a.chain.is_tool(dd.of) &&
                    dd.of == a.chain.tip_frame();
  if (tool) seg = a.chain.last();  // the last segment's pose composed with the tool's
  if (seg < 0 || !(in_root || in_chain_root)) {
    const std::string& tool_named = a.chain.tool_named();
    a.st.error(o, "unsupported-output",
               "the solver '" + arm.iri + "' outputs poses of the chain's segment frames" +
                   (tool_named.empty() ? std::string() : " and of " + tool_named) +
                   ", w.r.t. and seen by its root '" + arm.root_frame + "' (or the chain's root '" +
                   chain_root + "'); '" + dd.iri + "' is of '" + dd.of + "' w.r.t. '" +
                   dd.with_respect_to + "' seen by '" + dd.as_seen_by + "'");
    return;
  }
  using What = ArmOutput::What;
  const What what = tool ? (in_chain_root ? What::TipPoseInChainRoot : What::TipPose)
                         : (in_chain_root ? What::ChainRootPose : What::SegmentPose);
  a.arm.outputs.push_back({what, seg, d});
  kin.out.push_back(d);
}

// A twist of a segment (or of the tool) w.r.t. the root, at its origin, seen
// by the solver's root.
void lower_twist_output(const ArmScope& a, TermId o, Step& kin) {
  const ArmSolver& arm = a.arm;
  const ChainView& chain = a.chain;
  const int d = a.st.datum(o, DataType::Twist, a.solver, "output");
  const Data& dd = a.st.program.data[static_cast<size_t>(d)];
  int seg = chain.segment_by_link(dd.of);
  if (seg < 0) seg = chain.segment_by_frame(dd.of);
  // The tool's twist at its origin: the last segment's, moved there.
  const bool tool = seg < 0 && chain.is_tool(dd.of);
  if (tool) seg = chain.last();
  const std::string origin = tool ? chain.tip_origin() : seg < 0 ? "" : chain.origin_of(seg);
  const bool wrt_root = (!chain.root_link().empty() && dd.with_respect_to == chain.root_link()) ||
                        dd.with_respect_to == chain.root_frame() ||
                        dd.with_respect_to == arm.root_frame;
  if (seg < 0 || !wrt_root || dd.as_seen_by != arm.root_frame || dd.reference_point.empty() ||
      dd.reference_point != origin) {
    const std::string& tool_named = chain.tool_named();
    a.st.error(o, "unsupported-output",
               "the solver '" + arm.iri + "' outputs twists of a segment" +
                   (tool_named.empty() ? std::string() : ", or of " + tool_named + ",") +
                   " w.r.t. the root, at its origin, seen by the root '" + arm.root_frame + "'; '" +
                   dd.iri + "' does not fit");
    return;
  }
  a.arm.outputs.push_back(
      {tool ? ArmOutput::What::TipTwist : ArmOutput::What::SegmentTwist, seg, d});
  kin.out.push_back(d);
}

// One of the solver's outputs, computed by its kinematics step.
void lower_output(const ArmScope& a, TermId o, Step& kin) {
  if (auto joint_output = joint_quantity(a.st, o)) {
    lower_joint_output(a, o, *joint_output, kin);
  } else if (a.st.has_type(
                 o, mospec::vocab::term(mospec::vocab::mospec_joints::ns, "EstimatedWrench"))) {
    lower_estimated_wrench(a, o, kin);
  } else if (const auto t = a.st.type_of(o); t == DataType::Pose) {
    lower_pose_output(a, o, kin);
  } else if (t == DataType::Twist) {
    lower_twist_output(a, o, kin);
  } else {
    a.st.error(o, "unsupported-output",
               "the solver '" + a.arm.iri + "' cannot output '" + a.st.str(o) +
                   "' (poses and twists only)");
  }
}

// One entry of the solver's motion drivers, as DriverReader reads it.
struct Driver {
  TermId spec;
  std::string iri;
  int level = 0;                   // its priority level, 0 the highest
  std::optional<TermId> attached;  // its `attached-to`
  std::optional<TermId> force;     // its `force`, for a force driver
};

// Why a kind of driver must be in the highest priority level, in its message:
// "<plural> must be in the highest priority level: <why>; '<driver>' is in level N".
struct HighestLevelOnly {
  const char* plural;
  const char* why;
};

// The solver's motion drivers: their priority levels (the prioritization
// hierarchy, recorded in arm.priority_levels), and each driver entry with its
// level, its attachment and force, and their located errors.
class DriverReader {
 public:
  DriverReader(State& st, ArmSolver& arm, TermId drivers)
      : st_(st), drivers_(drivers), level_of_(&st.arena) {
    int level = 0;
    for (TermId head : st.objects(drivers, vocab(kSlv, "prioritization-hierarchy"))) {
      for (TermId lv : st.list(head)) {
        std::vector<std::string> names;
        for (TermId d : st.objects(lv, vocab(kSlv, "motion-drivers"))) {
          level_of_[d.index] = level;
          names.push_back(st.str(d));
        }
        arm.priority_levels.push_back(names);
        ++level;
      }
    }
    prioritised_ = level > 0;
  }
  std::vector<TermId> entries(const char* property) const {
    return st_.objects(drivers_, vocab(kSlv, property));
  }
  // ACHD's drivers all act in one solve: every kind must be in the highest level.
  Driver read(TermId spec, const HighestLevelOnly& rule, bool with_force) {
    st_.pending_iri = st_.str(spec);
    Driver d{spec, st_.str(spec), level_for(spec), std::nullopt, std::nullopt};
    if (d.level != 0) {
      st_.error(spec, "unsupported-priority",
                std::string(rule.plural) + " must be in the highest priority level: " + rule.why +
                    "; '" + d.iri + "' is in level " + std::to_string(d.level + 1));
    }
    d.attached = st_.object(spec, vocab(kSlv, "attached-to"));
    if (with_force) d.force = st_.object(spec, vocab(kSlv, "force"));
    return d;
  }

 private:
  int level_for(TermId spec) const {
    auto it = level_of_.find(spec.index);
    if (it != level_of_.end()) return it->second;
    if (prioritised_)
      st_.error(spec, "unprioritised-driver",
                "the motion driver '" + st_.str(spec) + "' is in no prioritization level of '" +
                    st_.str(drivers_) + "'");
    return 0;
  }
  State& st_;
  TermId drivers_;
  std::pmr::map<uint32_t, int> level_of_;  // scratch (the arena)
  bool prioritised_ = false;
};

constexpr HighestLevelOnly kConstraintLevel{"acceleration constraints",
                                            "one ACHD solve honours one level of constraints"};

// The frame an acceleration-constraint specification constrains: ACHD's tip
// frame, the last segment's origin or the tool's. The first one's choice is
// `acting_at` (that specification, and whether at the tool).
void check_constraint_attachment(const ArmScope& a, const Driver& d,
                                 std::optional<std::pair<TermId, bool>>& acting_at) {
  State& st = a.st;
  const ChainView& chain = a.chain;
  const std::string& last_link = chain.last_link();
  const std::string attached = d.attached ? st.str(*d.attached) : std::string("nothing");
  if (d.attached && chain.is_tool(attached)) {
    // At the tool: ACHD's tip frame T is the tool (achd_model).
    if (!acting_at) acting_at = {d.spec, true};
  } else if (last_link.empty() && !chain.empty()) {
    st.error(d.spec, "unsupported-attachment",
             "ACHD constrains the chain's last segment, but no link of the robot model holds its "
             "frame '" +
                 chain.last_frame() +
                 "' (state the link's `simplices`: its frame and origin point, as "
                 "robots/kinova-gen3.jsonld does); '" +
                 d.iri + "' is attached to '" + attached + "'");
  } else if (attached != last_link) {
    st.error(
        d.spec, "unsupported-attachment",
        "ACHD constrains the chain's last segment '" + last_link + "' at its origin" +
            (chain.tool_named().empty() ? std::string()
                                        : ", or " + chain.tool_named() + " at the tool's origin") +
            "; '" + d.iri + "' is attached to '" + attached + "'");
  } else if (!acting_at) {
    acting_at = {d.spec, false};
  }
  // One ACHD solve constrains one frame: every acceleration constraint
  // of the solver acts at the last link's origin, or every one at the tool's.
  if (acting_at && d.attached && (attached == last_link || chain.is_tool(attached)) &&
      acting_at->second != chain.is_tool(attached)) {
    st.error(d.spec, "unsupported-attachment",
             "'" + d.iri + "' is attached to '" + attached + "', but '" + st.str(acting_at->first) +
                 "' (" + st.place(acting_at->first) + ") to '" +
                 st.str(*st.object(acting_at->first, vocab(kSlv, "attached-to"))) +
                 "': one ACHD solve constrains one frame of the chain, the last segment '" +
                 last_link + "' or " + chain.tool_named() +
                 "; attach every acceleration constraint of '" + a.arm.iri +
                 "' to the same one (a constraint at the last link's origin can be stated "
                 "at the tool's: the tool moves with that link)");
  }
}

// One constraint of an acceleration-constraint specification: the tip
// direction it drives (its subspace and axis) and its acceleration energy.
// `constrained_by`: tip component -> the constraint already driving it.
void lower_acceleration_constraint(const ArmScope& a, TermId c, int level,
                                   std::map<int, TermId>& constrained_by, Step& solve) {
  State& st = a.st;
  AccelerationConstraint ac;
  ac.iri = st.str(c);
  ac.level = level;
  auto sub = st.object(c, vocab(kSlv, "subspace"));
  auto axis = st.object(c, vocab(kSlv, "axis"));
  const std::string sn = sub ? local_name(st.str(*sub)) : "",
                    an = axis ? local_name(st.str(*axis)) : "";
  const int base = sn == "angular-acceleration" ? 0 : sn == "linear-acceleration" ? 3 : -1;
  const int ax = an == "x" ? 0 : an == "y" ? 1 : an == "z" ? 2 : -1;
  if (base < 0 || ax < 0) {
    st.error(c, "invalid-constraint",
             "the acceleration constraint '" + ac.iri +
                 "' needs subspace linear-/angular-acceleration and axis x, y or z");
    return;
  }
  ac.component = base + ax;
  // A second constraint on a direction ACHD already constrains makes
  // its system singular, and the solve would average the two.
  if (auto first = constrained_by.emplace(ac.component, c); !first.second) {
    st.error(c, "driven-twice",
             "'" + ac.iri + "' constrains the " + sn + " along " + an + " of '" + a.arm.iri +
                 "', which '" + st.str(first.first->second) + "' (" +
                 st.place(first.first->second) +
                 ") already constrains; ACHD would average the two. Drive each direction "
                 "once: remove one, or combine their controllers' outputs with an operator");
    return;
  }
  auto energy = st.object(c, vocab(kSlv, "acceleration-energy"));
  if (!energy) {
    st.error(c, "missing-property",
             "the acceleration constraint '" + ac.iri + "' names no acceleration-energy");
    return;
  }
  ac.energy = st.datum(*energy, DataType::Scalar, c, "acceleration-energy");
  solve.in.push_back(ac.energy);
  a.arm.acceleration_constraints.push_back(ac);
}

// The acceleration-constraint specifications: all at one frame, one
// constraint per tip direction (driven-twice), which keeps them within
// runtime::kMaxConstraints; the verifier checks it again.
void lower_acceleration_constraints(const ArmScope& a, DriverReader& drivers, Step& solve) {
  std::map<int, TermId> constrained_by;  // tip component -> its acceleration constraint
  // The first acceleration-constraint specification, and whether it acts at the tool.
  std::optional<std::pair<TermId, bool>> acting_at;
  for (TermId spec : drivers.entries("acceleration-constraint")) {
    const Driver d = drivers.read(spec, kConstraintLevel, false);
    check_constraint_attachment(a, d, acting_at);
    for (TermId c : a.st.objects(spec, vocab(kSlv, "constraints")))
      lower_acceleration_constraint(a, c, d.level, constrained_by, solve);
  }
  a.arm.tip_is_last_segment = !(acting_at && acting_at->second);
}

// What a force driver is attached to: a segment (whether at the tool) or a joint.
struct Attachment {
  int index = -1;
  bool at_tip = false;
};

// A kind of force driver (a Cartesian force, a joint force) and what differs
// between the kinds: where it attaches, its data and the checks on them.
struct ForceKind {
  const char* property;  // its entries in the solver's motion drivers
  HighestLevelOnly level;
  const char* noun;         // as messages name a driver of the kind
  const char* attaches_to;  // what `attached-to` must name, for the missing-property message
  DataType type;            // of its force
  std::optional<Attachment> (*attach)(const ArmScope&, const Driver&);
  void (*check)(const ArmScope&, const Driver&, const Attachment&, int force);
  void (*keep)(ArmSolver&, const Driver&, const Attachment&, int force);
};

// A Cartesian force acts on a moving link of the chain, or on the tool:
// applied at its origin, moved to the last segment's each tick.
std::optional<Attachment> attach_to_link(const ArmScope& a, const Driver& d) {
  const std::string link = a.st.str(*d.attached);
  Attachment at{a.chain.segment_by_link(link), false};
  if (at.index < 0 && a.chain.is_tool(link)) at = {a.chain.last(), true};
  if (at.index >= 0) return at;
  a.st.error(d.spec, "unknown-link",
             "'" + d.iri + "' is attached to '" + link + "', which is no moving link of '" +
                 a.arm.chain_iri + "'" +
                 (a.chain.tool_named().empty() ? std::string() : " nor " + a.chain.tool_named()));
  return std::nullopt;
}

// A joint force acts on a joint of the chain.
std::optional<Attachment> attach_to_joint(const ArmScope& a, const Driver& d) {
  const std::string joint = a.st.str(*d.attached);
  const int j = a.chain.joint_index(joint);
  if (j >= 0) return Attachment{j, false};
  a.st.error(a.st.where(d.spec, vocab(kSlv, "attached-to"), *d.attached), "unknown-joint",
             no_joint(a.arm, a.chain.frames(), joint,
                      ": '" + d.iri + "' is attached to it, and the solver '" + a.arm.iri +
                          "' drives that chain; attach it to one of its joints"));
  return std::nullopt;
}

// ACHD takes a Cartesian force's wrench at its link's (or the tool's) origin,
// seen by the root.
void check_wrench_frame(const ArmScope& a, const Driver& d, const Attachment& at, int force) {
  const Data& w = a.st.program.data[static_cast<size_t>(force)];
  const std::string origin = at.at_tip ? a.chain.tip_origin() : a.chain.origin_of(at.index);
  if (!origin.empty() && w.reference_point == origin && w.as_seen_by == a.arm.root_frame) return;
  a.st.error(*d.force, "frame-mismatch",
             "the wrench '" + w.iri + "' drives '" + a.st.str(*d.attached) + "' through '" + d.iri +
                 "', so ACHD needs it at " + (at.at_tip ? "the tool's" : "that link's") +
                 " origin '" + origin + "' and seen by the root '" + a.arm.root_frame +
                 "'; it is at '" + w.reference_point + "' seen by '" + w.as_seen_by +
                 "' (transform it with TransformWrenchToProximal/RotateWrenchToProximalWithPose)");
}

// A revolute joint is driven by a torque, a prismatic one by a force.
void check_joint_force_unit(const ArmScope& a, const Driver& d, const Attachment& at, int force) {
  const Data& f = a.st.program.data[static_cast<size_t>(force)];
  const bool prismatic = a.arm.chain.segment(at.index).type == runtime::JointType::Prismatic;
  if (f.unit == (prismatic ? "N" : "N-M")) return;
  a.st.error(*d.force, "wrong-unit",
             "the joint force '" + f.iri + "' drives the " +
                 (prismatic ? "prismatic" : "revolute") + " joint '" + a.st.str(*d.attached) +
                 "' through '" + d.iri + "', so it is " +
                 (prismatic ? "a force in N" : "a torque in N-M") + ", not in '" + f.unit + "'");
}

void keep_cartesian_force(ArmSolver& arm, const Driver& d, const Attachment& at, int force) {
  arm.cartesian_forces.push_back({d.iri, at.index, force, d.level, at.at_tip});
}
void keep_joint_force(ArmSolver& arm, const Driver& d, const Attachment& at, int force) {
  arm.joint_forces.push_back({d.iri, at.index, force, d.level});
}

// ACHD adds every Cartesian force to one solve, where each acts in what the
// acceleration constraints leave free; a joint force adds its scalar to the
// joint's feed-forward torque (ACHD's tau_ff), which acts in the same free
// directions. A force of a lower level would not yield to those above it.
constexpr ForceKind kCartesianForce{
    "cartesian-force",
    {"Cartesian forces",
     "one ACHD solve adds every force alike (each acting where the acceleration constraints "
     "leave freedom), so a lower level would not yield to the forces above it"},
    "Cartesian force",
    "",
    DataType::Wrench,
    &attach_to_link,
    &check_wrench_frame,
    &keep_cartesian_force};
constexpr ForceKind kJointForce{
    "joint-force",
    {"joint forces",
     "one ACHD solve adds every feed-forward joint force alike, so a lower level would not "
     "yield to the drivers above it"},
    "joint force",
    " (a joint)",
    DataType::Scalar,
    &attach_to_joint,
    &check_joint_force_unit,
    &keep_joint_force};

// One force driver of the solver, of either kind: its force becomes an input of the solve.
void lower_force(const ArmScope& a, DriverReader& drivers, const ForceKind& kind, TermId spec,
                 Step& solve) {
  const Driver d = drivers.read(spec, kind.level, true);
  if (!d.attached || !d.force) {
    a.st.error(spec, "missing-property",
               std::string("the ") + kind.noun + " '" + d.iri +
                   "' needs `force` and `attached-to`" + kind.attaches_to);
    return;
  }
  const std::optional<Attachment> at = kind.attach(a, d);
  if (!at) return;
  const int force = a.st.datum(*d.force, kind.type, spec, "force");
  kind.check(a, d, *at, force);
  solve.in.push_back(force);
  kind.keep(a.arm, d, *at, force);
}

// Motion drivers and their priority levels: the solve's inputs.
void lower_drivers(const ArmScope& a, std::optional<TermId> drivers, Step& solve) {
  if (!drivers) {
    a.st.error(a.solver, "missing-property",
               "the solver '" + a.arm.iri + "' names no motion-drivers");
    return;
  }
  DriverReader reader(a.st, a.arm, *drivers);
  lower_acceleration_constraints(a, reader, solve);
  for (const ForceKind* kind : {&kCartesianForce, &kJointForce}) {
    for (TermId spec : reader.entries(kind->property)) lower_force(a, reader, *kind, spec, solve);
  }
}

// One of the arm's two steps, named and located by its solver.
Step arm_step(const ArmSolver& arm, int arm_index, StepKind kind, const char* suffix) {
  Step s;
  s.kind = kind;
  s.iri = arm.iri;
  s.name = arm.name + suffix;
  s.where = arm.where;
  s.solver = arm_index;
  return s;
}

}  // namespace

void lower_arm(State& st, TermId solver) {
  st.pending_iri = st.str(solver);
  ArmSolver arm;
  arm.iri = st.str(solver);
  arm.name = identifier(local_name(arm.iri));
  arm.where = st.where(solver);
  check_algorithm(st, solver, arm);
  const std::optional<ChainView> chain = read_chain(st, solver, arm);
  if (!chain) return;
  bind_port(st, solver, arm);
  const ArmScope a{st, solver, arm, *chain};
  lower_root(a);
  lower_gravity(st, solver, arm);
  lower_arm_behaviour(st, solver, arm);
  const int arm_index = static_cast<int>(st.program.arms.size());
  Step kin = arm_step(arm, arm_index, StepKind::ArmKinematics, "_kinematics");
  for (TermId o : st.objects(solver, vocab(kSlv, "output"))) lower_output(a, o, kin);
  const auto drivers = st.object(solver, vocab(kSlv, "motion-drivers"));
  Step solve = arm_step(arm, arm_index, StepKind::ArmSolve, "_solve");
  lower_drivers(a, drivers, solve);
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
    if (role(controller) != StepRole::Controller || controller.in.empty()) continue;
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
  return role(step) == StepRole::Constraint &&
         (step.constraint.kind == runtime::ConstraintKind::LessThan ||
          step.constraint.kind == runtime::ConstraintKind::GreaterThan);
}

void mark_one_sided(State& st, ArmSolver& arm, Step& solve) {
  for (AccelerationConstraint& ac : arm.acceleration_constraints) {
    const auto from = st.producer.find(ac.energy);
    if (from == st.producer.end() || from->second < 0) continue;
    const Step& controller = st.steps[static_cast<size_t>(from->second)];
    if (role(controller) == StepRole::Controller && !controller.in.empty()) {
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
      // Signals flow through controllers (not their running flag) and
      // computations (operators, views).
      if (role(p) == StepRole::Controller) {
        const size_t signals = controller_kinds()[static_cast<size_t>(p.controller)].in.size();
        todo.insert(todo.end(), p.in.begin(),
                    p.in.begin() + static_cast<std::ptrdiff_t>(std::min(signals, p.in.size())));
      } else if (role(p) == StepRole::Computation) {
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
      if (role(solve) == StepRole::Solver && solve.solver == static_cast<int>(a))
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
      if (writer.views.empty()) continue;  // not assembled by views
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
    if (role(solve) != StepRole::Solver) continue;
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
      // A gated step's running flag (a controller's after its signals, an
      // assignment's after its value): its kind says which input it is.
      const GateHook gate_of = info(p.kind).gate;
      const int gate = gate_of ? gate_of(p) : -1;
      const bool gated = gate >= 0;
      if (gated) gates.insert(p.in[static_cast<size_t>(gate)]);
      // Motions and measurements start the chain: nothing upstream drives.
      if (role(p) == StepRole::Motion || role(p) == StepRole::Measurement) continue;
      for (size_t k = 0; k < p.in.size(); ++k) {
        if (gated && k == static_cast<size_t>(gate)) continue;
        todo.push_back(p.in[k]);
      }
    }
    solve.in.insert(solve.in.end(), gates.begin(), gates.end());
    // An arm some motion gates is idle while none of them runs: the model
    // says what it does then.
    if (solve.solver >= 0 && !gates.empty()) {  // an arm's
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
