#include "ir/ir.hpp"

#include <algorithm>
#include <array>
#include <initializer_list>
#include <nlohmann/json.hpp>

#include "ir/controllers.hpp"
#include "ir/kinds/kinds.hpp"
#include "ir/operators.hpp"
#include "runtime/steps.hpp"

namespace mospec::ir {

std::string_view to_string(DataType t) {
  switch (t) {
    case DataType::Scalar:
      return "scalar";
    case DataType::Vector3:
      return "vector3";
    case DataType::Pose:
      return "pose";
    case DataType::Twist:
      return "twist";
    case DataType::Wrench:
      return "wrench";
    case DataType::Flag:
      return "flag";
    case DataType::Event:
      return "event";
    case DataType::Inertia:
      return "inertia";
  }
  return "?";
}

std::string_view to_string(StepKind k) {
  return info(k).name;
}

std::vector<int> arm_joints(const Program& program) {
  std::vector<int> joints;
  for (const ArmSolver& a : program.arms) {
    if (a.port < 0) continue;
    const auto port = static_cast<size_t>(a.port);
    if (port >= joints.size()) joints.resize(port + 1, 0);
    joints[port] = a.chain.size();
  }
  return joints;
}

std::string_view kind_name(const Step& step) {
  if (step.kind == StepKind::Operator) {
    const auto kinds = operator_kinds();
    if (step.op >= 0 && static_cast<size_t>(step.op) < kinds.size())
      return kinds[static_cast<size_t>(step.op)].name;
  }
  if (step.kind == StepKind::Controller) {
    const auto kinds = controller_kinds();
    if (step.controller >= 0 && static_cast<size_t>(step.controller) < kinds.size())
      return kinds[static_cast<size_t>(step.controller)].name;
  }
  return to_string(step.kind);
}

runtime::AchdModel achd_model(const ArmSolver& arm, bool physical) {
  const runtime::Vec3 g = physical || !arm.gravity_compensated
                              ? runtime::Vec3(arm.gravity[0], arm.gravity[1], arm.gravity[2])
                              : runtime::Vec3::Zero();
  runtime::AchdModel model(arm.chain, g);
  if (!physical && arm.tip_is_last_segment) model.X_NT = runtime::Pose{};
  return model;
}

namespace {

// Tight enough that a goal met is met for the task (a millimetre of a
// position, half a degree of an angle, half a newton of a force), loose
// enough for a PD that converges exponentially to reach it within a motion.
constexpr DefaultTolerance kDefaultTolerances[] = {
    {"M", 1e-3, "length, position: 1 mm"},
    {"RAD", 0.01, "angle: 0.01 rad (0.57 deg)"},
    {"M-PER-SEC", 0.01, "linear velocity: 1 cm/s"},
    {"RAD-PER-SEC", 0.05, "angular velocity: 0.05 rad/s (2.9 deg/s)"},
    {"M-PER-SEC2", 0.05, "linear acceleration: 0.05 m/s^2"},
    {"RAD-PER-SEC2", 0.1, "angular acceleration: 0.1 rad/s^2"},
    {"N", 0.5, "force: 0.5 N"},
    {"N-M", 0.1, "torque: 0.1 N m"},
    {"SEC", 1e-3, "time: 1 ms (one control tick at 1 kHz)"},
    {"UNITLESS", 0.01, "a ratio: 0.01"},
};

}  // namespace

std::span<const DefaultTolerance> default_tolerances() {
  return kDefaultTolerances;
}

std::string_view relation_name(runtime::ConstraintKind kind) {
  switch (kind) {
    case runtime::ConstraintKind::Equality:
      return "equality";
    case runtime::ConstraintKind::LessThan:
      return "less-than";
    case runtime::ConstraintKind::GreaterThan:
      return "greater-than";
    case runtime::ConstraintKind::Bilateral:
      return "bilateral";
    case runtime::ConstraintKind::Assignment:
      return "assignment";
  }
  return "?";
}

std::optional<double> default_tolerance(std::string_view unit) {
  for (const DefaultTolerance& d : kDefaultTolerances)
    if (d.unit == unit) return d.tolerance;
  return std::nullopt;
}

double idle_time_constant(const ArmSolver& arm) {
  return arm.idle == ArmSolver::Idle::BrakeAndHold ? arm.idle_time_constant
                                                   : runtime::steps::kFloatTimeConstant;
}

runtime::KeloConfig kelo_config(const BaseSolver& base) {
  return base.config;
}

runtime::Pose constant_pose(const std::vector<double>& v) {
  runtime::Pose X;
  if (v.size() != 12) return X;
  X.R << v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7], v[8];
  X.p = runtime::Vec3(v[9], v[10], v[11]);
  return X;
}

namespace {

// The step kinds, in StepKind's order; their hooks are in kinds/*.cpp.
const StepKindInfo kStepKinds[] = {
    {.kind = StepKind::ReadClock,
     .name = "read-clock",
     .state = std::nullopt,
     .lowered_from = "mospec/time Clock",
     .summary = "out: [time]",
     .role = StepRole::Clock,
     .member = StepMember::None,
     .signature = &kinds::signature_read_clock,
     .verify = nullptr,
     .print = nullptr,
     .log = nullptr,
     .gate = nullptr,
     .prepare = nullptr,
     .interpret = &kinds::interpret_read_clock,
     .emit = &kinds::emit_read_clock},
    {.kind = StepKind::ArmKinematics,
     .name = "arm-kinematics",
     .state = std::nullopt,
     .lowered_from = "slv:SolverWithInputAndOutput (its outputs)",
     .summary =
         "outs: the solver's outputs (poses, twists of segments w.r.t. the root; joint positions, "
         "velocities, measured torques)",
     .role = StepRole::Measurement,
     .member = StepMember::None,
     .signature = &kinds::signature_arm_kinematics,
     .verify = &kinds::verify_arm_solver,
     .print = nullptr,
     .log = nullptr,
     .gate = nullptr,
     .prepare = nullptr,
     .interpret = &kinds::interpret_arm_kinematics,
     .emit = &kinds::emit_arm_kinematics},
    {.kind = StepKind::ViewRead,
     .name = "view-read",
     .state = std::nullopt,
     .lowered_from =
         "map:PoseCoordinateView, VelocityTwistCoordinateView, WrenchCoordinateView (read)",
     .summary = "in: [pose|twist|wrench]; out: [scalar]",
     .role = StepRole::Computation,
     .member = StepMember::None,
     .signature = &kinds::signature_view_read,
     .verify = &kinds::verify_view_read,
     .print = &kinds::print_view,
     .log = nullptr,
     .gate = nullptr,
     .prepare = nullptr,
     .interpret = &kinds::interpret_view_read,
     .emit = &kinds::emit_view_read},
    {.kind = StepKind::ViewWrite,
     .name = "view-write",
     .state = std::nullopt,
     .lowered_from = "map:VelocityTwistCoordinateView, WrenchCoordinateView (written)",
     .summary = "ins: [scalar...]; out: [twist|wrench] (other components zero)",
     .role = StepRole::Computation,
     .member = StepMember::None,
     .signature = &kinds::signature_view_write,
     .verify = &kinds::verify_view_write,
     .print = &kinds::print_view,
     .log = nullptr,
     .gate = nullptr,
     .prepare = nullptr,
     .interpret = &kinds::interpret_view_write,
     .emit = &kinds::emit_view_write},
    {.kind = StepKind::Operator,
     .name = "operator",
     .state = std::nullopt,
     .lowered_from = "the operator registry (operators.hpp)",
     .summary = "the operator kind's ports",
     .role = StepRole::Computation,
     .member = StepMember::None,
     .signature = &kinds::signature_operator,
     .verify = &kinds::verify_operator,
     .print = nullptr,
     .log = nullptr,
     .gate = nullptr,
     .prepare = &kinds::prepare_operator,
     .interpret = &kinds::interpret_operator,
     .emit = &kinds::emit_operator},
    {.kind = StepKind::Evaluate,
     .name = "evaluate",
     .state = std::nullopt,
     .lowered_from = "cstr-hdl:ErrorEvaluator, AssignmentEvaluator",
     .summary = "ins: [quantity, (active flag)]; outs: [satisfied flag, error|output]",
     .role = StepRole::Constraint,
     .member = StepMember::Evaluator,
     .signature = &kinds::signature_evaluate,
     .verify = &kinds::verify_evaluate,
     .print = &kinds::print_evaluate,
     .log = &kinds::log_evaluate,
     .gate = &kinds::gate_evaluate,
     .prepare = &kinds::prepare_evaluate,
     .interpret = &kinds::interpret_evaluate,
     .emit = &kinds::emit_evaluate},
    {.kind = StepKind::LevelMonitor,
     .name = "level-monitor",
     .state = StateKind::Monitor,
     .lowered_from = "cstr-hdl:LevelTriggeredMonitor",
     .summary = "ins: [error, (running flag)]; out: [flag]",
     .role = StepRole::Monitor,
     .member = StepMember::MonitorTolerance,
     .signature = &kinds::signature_monitor,
     .verify = &kinds::verify_monitor,
     .print = &kinds::print_monitor,
     .log = &kinds::log_monitor,
     .gate = nullptr,
     .prepare = nullptr,
     .interpret = &kinds::interpret_monitor,
     .emit = &kinds::emit_monitor},
    {.kind = StepKind::EdgeMonitor,
     .name = "edge-monitor",
     .state = StateKind::Monitor,
     .lowered_from = "cstr-hdl:EdgeTriggeredMonitor",
     .summary = "ins: [error, (running flag)]; out: [event: 1 rising, 2 falling, as its edges say]",
     .role = StepRole::Monitor,
     .member = StepMember::MonitorTolerance,
     .signature = &kinds::signature_monitor,
     .verify = &kinds::verify_monitor,
     .print = &kinds::print_monitor,
     .log = &kinds::log_monitor,
     .gate = nullptr,
     .prepare = nullptr,
     .interpret = &kinds::interpret_monitor,
     .emit = &kinds::emit_monitor},
    {.kind = StepKind::GuardedMotion,
     .name = "guarded-motion",
     .state = StateKind::Motion,
     .lowered_from = "mot:GuardedMotion",
     .summary =
         "ins: [when flags..., checked while flags..., until flags...]; outs: [running flag, "
         "ended event: 1 an until held, 2 a while was violated]",
     .role = StepRole::Motion,
     .member = StepMember::None,
     .signature = &kinds::signature_guarded_motion,
     .verify = &kinds::verify_guarded_motion,
     .print = &kinds::print_guarded_motion,
     .log = &kinds::log_guarded_motion,
     .gate = nullptr,
     .prepare = nullptr,
     .interpret = &kinds::interpret_guarded_motion,
     .emit = &kinds::emit_guarded_motion},
    {.kind = StepKind::AnyOf,
     .name = "any-of",
     .state = std::nullopt,
     .lowered_from =
         "cstr-hdl:ConstraintHandler (a controller or evaluator several motions' handlers list)",
     .summary = "ins: [running flags...]; out: [flag]: true while any of them is",
     .role = StepRole::Computation,
     .member = StepMember::None,
     .signature = &kinds::signature_any_of,
     .verify = nullptr,
     .print = nullptr,
     .log = nullptr,
     .gate = nullptr,
     .prepare = nullptr,
     .interpret = &kinds::interpret_any_of,
     .emit = &kinds::emit_any_of},
    {.kind = StepKind::Controller,
     .name = "controller",
     .state = std::nullopt,
     .lowered_from = "the controller registry (controllers.hpp); state slots per controller kind",
     .summary = "ins: [signals..., (active flag)]; out: [control signal]",
     .role = StepRole::Controller,
     .member = StepMember::Controller,
     .signature = &kinds::signature_controller,
     .verify = &kinds::verify_controller,
     .print = &kinds::print_controller,
     .log = &kinds::log_controller,
     .gate = &kinds::gate_controller,
     .prepare = &kinds::prepare_controller,
     .interpret = &kinds::interpret_controller,
     .emit = &kinds::emit_controller},
    {.kind = StepKind::ArmSolve,
     .name = "arm-solve",
     .state = std::nullopt,
     .lowered_from = "slv:SolverWithInputAndOutput (its drivers)",
     .summary =
         "ins: the drivers' data, then the motion gates; out: [degraded flag]; writes the arm's "
         "joint torques",
     .role = StepRole::Solver,
     .member = StepMember::None,
     .signature = &kinds::signature_arm_solve,
     .verify = &kinds::verify_arm_solve,
     .print = &kinds::print_drivers,
     .log = &kinds::log_arm_solve,
     .gate = nullptr,
     .prepare = nullptr,
     .interpret = &kinds::interpret_arm_solve,
     .emit = &kinds::emit_arm_solve},
    {.kind = StepKind::BaseForceDistribution,
     .name = "base-force-distribution",
     .state = std::nullopt,
     .lowered_from = "mospec platform force-distribution solver",
     .summary = "ins: [platform wrench, motion gates...]; writes the hub torques",
     .role = StepRole::Solver,
     .member = StepMember::None,
     .signature = &kinds::signature_base_force_distribution,
     .verify = &kinds::verify_base_force_distribution,
     .print = &kinds::print_drivers,
     .log = &kinds::log_base_force_distribution,
     .gate = nullptr,
     .prepare = nullptr,
     .interpret = &kinds::interpret_base_force_distribution,
     .emit = &kinds::emit_base_force_distribution},
    {.kind = StepKind::BaseVelocityComposition,
     .name = "base-velocity-composition",
     .state = std::nullopt,
     .lowered_from = "mospec platform velocity-composition solver",
     .summary = "out: [platform twist] from the pivots' and wheels' rates",
     .role = StepRole::Measurement,
     .member = StepMember::None,
     .signature = &kinds::signature_base_velocity_composition,
     .verify = &kinds::verify_base,
     .print = nullptr,
     .log = &kinds::log_base_velocity_composition,
     .gate = nullptr,
     .prepare = nullptr,
     .interpret = &kinds::interpret_base_velocity_composition,
     .emit = &kinds::emit_base_velocity_composition},
};
static_assert(std::size(kStepKinds) == kStepKindCount, "one kStepKinds entry per StepKind");

Signature signature(const Step& st, const Program& p) {
  const auto k = static_cast<size_t>(st.kind);
  if (k >= std::size(kStepKinds)) return {{}, {}, true, "has an unknown kind"};
  return kStepKinds[k].signature(st, p);
}

}  // namespace

std::span<const StepKindInfo> step_kinds() {
  static const std::vector<StepKindInfo> infos = [] {
    std::vector<StepKindInfo> out;
    for (const StepKindInfo& e : kStepKinds) out.push_back(e);
    return out;
  }();
  return infos;
}

const StepKindInfo& info(StepKind kind) {
  static const StepKindInfo unknown{static_cast<StepKind>(kStepKindCount), "?", std::nullopt, "",
                                    ""};
  const auto k = static_cast<size_t>(kind);
  return k < std::size(kStepKinds) ? kStepKinds[k] : unknown;
}

StepRole role(const Step& step) {
  return info(step.kind).role;
}

namespace kinds {

LogColumn step_column(const Program& p, const Step& st, std::string_view suffix, int data,
                      robot::LogColumnKind kind) {
  std::string name = lowering::local_name(st.iri);
  name.append(suffix);
  return {std::move(name), p.data[static_cast<size_t>(data)].unit, data, -1, kind};
}

void verify_gates(const Step& st, const Program& p, Findings& f) {
  if (st.drivers() > st.in.size()) {
    f.step(st, "has " + std::to_string(st.drivers()) + " drivers but " +
                   std::to_string(st.in.size()) + " inputs");
    return;
  }
  for (size_t k = st.drivers(); k < st.in.size(); ++k) {
    if (f.valid_datum(st.in[k]) && p.data[static_cast<size_t>(st.in[k])].type != DataType::Flag)
      f.step(st, "motion gate " + std::to_string(k - st.drivers()) + " must be a flag; it is " +
                     f.describe(st.in[k]));
  }
}

}  // namespace kinds

std::string template_section(StepKind kind) {
  std::string out = "is_";
  for (char c : info(kind).name) out.push_back(c == '-' ? '_' : c);
  return out;
}

namespace {

// Slots: dense per type, each used once.
void check_slots(const Program& p, Findings& f) {
  std::array<std::vector<char>, kDataTypes> used;
  for (int t = 0; t < kDataTypes; ++t)
    used[static_cast<size_t>(t)].assign(
        static_cast<size_t>(std::max(0, p.slots[static_cast<size_t>(t)])), 0);
  for (const Data& d : p.data) {
    auto& u = used[static_cast<size_t>(d.type)];
    if (d.slot < 0 || static_cast<size_t>(d.slot) >= u.size()) {
      f.add(d.where, "datum '" + d.name + "' has slot " + std::to_string(d.slot) +
                         "; expected 0.." + std::to_string(static_cast<long>(u.size()) - 1) +
                         " (the program has " + std::to_string(u.size()) + " " +
                         std::string(to_string(d.type)) + " slots)");
      continue;
    }
    if (u[static_cast<size_t>(d.slot)]) {
      f.add(d.where, "datum '" + d.name + "' has slot " + std::to_string(d.slot) + " of type " +
                         std::string(to_string(d.type)) + ", which another datum also has");
    }
    u[static_cast<size_t>(d.slot)] = 1;
  }
}

// A constant has as many values as its type.
void check_constants(const Program& p, Findings& f) {
  for (const Data& d : p.data) {
    if (d.value.empty()) continue;
    const size_t need = d.type == DataType::Pose                                  ? 12
                        : d.type == DataType::Vector3                             ? 3
                        : d.type == DataType::Twist || d.type == DataType::Wrench ? 6
                        : d.type == DataType::Event                               ? 0
                        : d.type == DataType::Inertia                             ? 10
                                                                                  : 1;
    if (d.value.size() != need)
      f.add(d.where, "constant '" + d.name + "' has " + std::to_string(d.value.size()) +
                         " values; a " + std::string(to_string(d.type)) + " constant has " +
                         std::to_string(need));
  }
}

// Which step writes each datum (-2: a model constant; -1: none), each datum
// written once. Producers first, so an unscheduled program's reads can be
// checked for a producer regardless of order.
std::vector<int> check_producers(const Program& p, Findings& f) {
  const size_t n_data = p.data.size();
  std::vector<int> producer(n_data, -1);  // step index; -2: a constant
  for (size_t i = 0; i < n_data; ++i) {
    if (!p.data[i].value.empty()) producer[i] = -2;
  }
  for (size_t i = 0; i < p.steps.size(); ++i) {
    const Step& st = p.steps[i];
    for (int d : st.out) {
      if (!f.valid_datum(d)) continue;
      int& who = producer[static_cast<size_t>(d)];
      if (who == -1) {
        who = static_cast<int>(i);
      } else {
        f.step(st, "writes '" + p.data[static_cast<size_t>(d)].name + "', which " +
                       (who == -2 ? std::string("is a model constant")
                                  : "step '" + p.steps[static_cast<size_t>(who)].name +
                                        "' already writes"));
      }
    }
  }
  return producer;
}

// The step's inputs and outputs against its kind's signature.
void check_signature(const Program& p, const Step& st, Findings& f) {
  const Signature sig = signature(st, p);
  if (!sig.problem.empty()) f.step(st, sig.problem);
  for (int d : st.in) {
    if (!f.valid_datum(d)) f.step(st, "reads " + f.describe(d));
  }
  for (int d : st.out) {
    if (!f.valid_datum(d)) f.step(st, "writes " + f.describe(d));
  }
  if (sig.problem.empty()) {
    const bool ins_ok = sig.variadic_in || sig.in.size() == st.in.size();
    const bool outs_ok = sig.variadic_out || sig.out.size() == st.out.size();
    if (!ins_ok || !outs_ok) {
      f.step(
          st,
          "has " + std::to_string(st.in.size()) + " inputs and " + std::to_string(st.out.size()) +
              " outputs; expected " +
              (sig.variadic_in ? std::string("any number of") : std::to_string(sig.in.size())) +
              " and " +
              (sig.variadic_out ? std::string("any number of") : std::to_string(sig.out.size())));
    } else {
      for (size_t k = 0; !sig.variadic_in && k < st.in.size(); ++k) {
        if (f.valid_datum(st.in[k]) && p.data[static_cast<size_t>(st.in[k])].type != sig.in[k])
          f.step(st, "input " + std::to_string(k) + " must be a " +
                         std::string(to_string(sig.in[k])) + "; it is " + f.describe(st.in[k]));
      }
      for (size_t k = 0; !sig.variadic_out && k < st.out.size(); ++k) {
        if (f.valid_datum(st.out[k]) && p.data[static_cast<size_t>(st.out[k])].type != sig.out[k])
          f.step(st, "output " + std::to_string(k) + " must be a " +
                         std::string(to_string(sig.out[k])) + "; it is " + f.describe(st.out[k]));
      }
    }
  }
}

// The kind's own rules, its state slot, and that what it reads is produced
// (before it, once scheduled).
void check_step(const Program& p, size_t i, const std::vector<int>& producer, Stage stage,
                Findings& f) {
  const Step& st = p.steps[i];
  if (static_cast<size_t>(st.kind) < kStepKindCount) {
    if (const VerifyHook verify = info(st.kind).verify) verify(st, p, f);
  }
  if (const auto sk =
          static_cast<size_t>(st.kind) < kStepKindCount ? info(st.kind).state : std::nullopt) {
    const int n = p.states[static_cast<size_t>(*sk)];
    if (st.state < 0 || st.state >= n)
      f.step(st, "has state slot " + std::to_string(st.state) + "; expected 0.." +
                     std::to_string(n - 1));
  }
  for (int d : st.in) {
    if (!f.valid_datum(d)) continue;
    const int who = producer[static_cast<size_t>(d)];
    if (stage == Stage::Unscheduled) continue;  // later passes may produce it
    if (who == -1) {
      f.step(st, "reads '" + p.data[static_cast<size_t>(d)].name +
                     "', which no step produces and the model does not give");
    } else if (stage == Stage::Scheduled && who >= static_cast<int>(i)) {
      f.step(st, "reads '" + p.data[static_cast<size_t>(d)].name + "' before step '" +
                     p.steps[static_cast<size_t>(who)].name + "' (at " + std::to_string(who) +
                     " in the schedule) produces it");
    }
  }
}

// An arm solver's own tables: its acceleration constraints, outputs and joint
// forces.
void check_arm(const Program& p, const ArmSolver& a, Findings& f) {
  for (const AccelerationConstraint& c : a.acceleration_constraints) {
    if (c.component < 0 || c.component > 5)
      f.add(a.where, "arm solver '" + a.name + "': acceleration constraint '" + c.iri +
                         "' has component " + std::to_string(c.component) + "; expected 0..5");
    if (c.engaged_by >= 0 && !f.valid_datum(c.engaged_by))
      f.add(a.where, "arm solver '" + a.name + "': acceleration constraint '" + c.iri +
                         "' is engaged by " + f.describe(c.engaged_by));
  }
  if (a.acceleration_constraints.size() > static_cast<size_t>(runtime::kMaxConstraints))
    f.add(a.where, "arm solver '" + a.name + "' has " +
                       std::to_string(a.acceleration_constraints.size()) +
                       " acceleration constraints; ACHD supports " +
                       std::to_string(runtime::kMaxConstraints));
  for (const ArmOutput& o : a.outputs) {
    if (o.segment < 0 || o.segment >= a.chain.size())
      f.add(a.where, "arm solver '" + a.name + "': an output names segment " +
                         std::to_string(o.segment) + " of " + std::to_string(a.chain.size()));
    if (!f.valid_datum(o.data)) {
      f.add(a.where, "arm solver '" + a.name + "' outputs " + f.describe(o.data));
      continue;
    }
    const bool tip = o.what == ArmOutput::What::TipPose || o.what == ArmOutput::What::TipTwist ||
                     o.what == ArmOutput::What::TipPoseInChainRoot;
    if (tip && o.segment != a.chain.size() - 1)
      f.add(a.where, "arm solver '" + a.name + "': an output of the tip frame names segment " +
                         std::to_string(o.segment) + ", not the last one");
    const DataType expected =
        o.what == ArmOutput::What::SegmentTwist || o.what == ArmOutput::What::TipTwist
            ? DataType::Twist
        : o.what == ArmOutput::What::EstimatedWrench ? DataType::Wrench
        : o.what == ArmOutput::What::SegmentPose || o.what == ArmOutput::What::ChainRootPose ||
                o.what == ArmOutput::What::TipPose || o.what == ArmOutput::What::TipPoseInChainRoot
            ? DataType::Pose
            : DataType::Scalar;
    if (p.data[static_cast<size_t>(o.data)].type != expected)
      f.add(a.where, "arm solver '" + a.name + "' writes an output of its kind into " +
                         f.describe(o.data) + "; expected a " + std::string(to_string(expected)));
  }
  for (const JointForce& j : a.joint_forces) {
    if (j.joint < 0 || j.joint >= a.chain.size())
      f.add(a.where, "arm solver '" + a.name + "': joint force '" + j.iri + "' names joint " +
                         std::to_string(j.joint) + " of " + std::to_string(a.chain.size()));
    if (!f.valid_datum(j.force) || p.data[static_cast<size_t>(j.force)].type != DataType::Scalar)
      f.add(a.where, "arm solver '" + a.name + "': joint force '" + j.iri + "' applies " +
                         f.describe(j.force) + "; expected a scalar");
  }
}

// What an arm's drivers mean to ACHD, as lowering established it and every
// later pass must keep it: an acceleration energy is in N m^2/s^2, a Cartesian
// force's wrench is seen by the solver's root, a joint force is a torque on a
// revolute joint and a force on a prismatic one. (A datum with no unit or
// frame stated is a hand-built program's, judged by its type alone.) Judged
// once the program is scheduled: lowering's driver-directions pass, before
// the schedule, is where a model that breaks them is refused, with advice.
void check_arm_drivers(const Program& p, const ArmSolver& a, Findings& f) {
  const auto datum = [&](int d) -> const Data* {
    return f.valid_datum(d) ? &p.data[static_cast<size_t>(d)] : nullptr;
  };
  const std::string arm = "arm solver '" + a.name + "': ";
  for (const AccelerationConstraint& c : a.acceleration_constraints) {
    const Data* e = datum(c.energy);
    if (e && !e->unit.empty() && e->unit != "N-M2-PER-SEC2")
      f.add(a.where, arm + "acceleration constraint '" + c.iri + "' takes its energy from '" +
                         e->name + "' in '" + e->unit + "'; expected N-M2-PER-SEC2");
  }
  for (const CartesianForce& c : a.cartesian_forces) {
    const Data* w = datum(c.wrench);
    if (!w || w->type != DataType::Wrench) {
      f.add(a.where, arm + "Cartesian force '" + c.iri + "' applies " + f.describe(c.wrench) +
                         "; expected a wrench");
    } else if (!w->as_seen_by.empty() && w->as_seen_by != a.root_frame) {
      f.add(a.where, arm + "Cartesian force '" + c.iri + "' applies '" + w->name + "' seen by '" +
                         w->as_seen_by + "'; ACHD needs it seen by the root '" + a.root_frame +
                         "'");
    }
  }
  for (const JointForce& j : a.joint_forces) {
    const Data* d = datum(j.force);
    if (!d || d->unit.empty() || j.joint < 0 || j.joint >= a.chain.size()) continue;
    const bool prismatic = a.chain.segment(j.joint).type == runtime::JointType::Prismatic;
    const char* expected = prismatic ? "N" : "N-M";
    if (d->unit != expected)
      f.add(a.where, arm + "joint force '" + j.iri + "' applies '" + d->name + "' in '" + d->unit +
                         "' to " + (prismatic ? "prismatic" : "revolute") + " joint " +
                         std::to_string(j.joint) + "; expected " + expected);
  }
}

// Each log column reads a datum (a component of a twist or wrench), latched
// as its type needs.
void check_log(const Program& p, Findings& f) {
  for (const LogColumn& c : p.log) {
    if (!f.valid_datum(c.data)) {
      f.add({}, "log column '" + c.name + "' refers to " + f.describe(c.data));
      continue;
    }
    const DataType t = p.data[static_cast<size_t>(c.data)].type;
    if (c.component >= 0 && (c.component > 5 || (t != DataType::Twist && t != DataType::Wrench)))
      f.add(p.data[static_cast<size_t>(c.data)].where,
            "log column '" + c.name + "' reads component " + std::to_string(c.component) + " of " +
                f.describe(c.data) + "; components are of a twist or wrench, 0..5");
    // Every event is latched (a decimated log would lose it); a latched flag is a flag.
    if ((t == DataType::Event) != (c.kind == robot::LogColumnKind::Event) ||
        (c.kind == robot::LogColumnKind::Flag && t != DataType::Flag))
      f.add(p.data[static_cast<size_t>(c.data)].where,
            "log column '" + c.name + "' of " + f.describe(c.data) + " is latched as " +
                (c.kind == robot::LogColumnKind::Event  ? "an event"
                 : c.kind == robot::LogColumnKind::Flag ? "a flag"
                                                        : "nothing") +
                "; an event column is latched as an event, a flag column as a flag or not at all");
  }
}

}  // namespace

std::vector<Diagnostic> check(const Program& p, const SourceFiles* files, Stage stage) {
  Findings f(p, files);
  check_slots(p, f);
  check_constants(p, f);
  const std::vector<int> producer = check_producers(p, f);
  for (size_t i = 0; i < p.steps.size(); ++i) {
    check_signature(p, p.steps[i], f);
    check_step(p, i, producer, stage, f);
  }
  for (const ArmSolver& a : p.arms) {
    check_arm(p, a, f);
    if (stage == Stage::Scheduled) check_arm_drivers(p, a, f);
  }
  check_log(p, f);
  return f.take();
}

VerifyError::VerifyError(std::vector<Diagnostic> diagnostics)
    : Error("ir-invalid",
            [&] {
              std::string out;
              for (size_t i = 0; i < diagnostics.size(); ++i) {
                if (i) out.push_back('\n');
                out.append(format(diagnostics[i]));
              }
              return out;
            }()),
      diagnostics_(std::move(diagnostics)) {}

void verify(const Program& p, const SourceFiles* files) {
  auto problems = check(p, files, Stage::Scheduled);
  if (!problems.empty()) throw VerifyError(std::move(problems));
}

namespace {

using Json = nlohmann::ordered_json;

Json location(const SourceLoc& loc, const SourceFiles* files) {
  if (!files || !loc.known()) return nullptr;
  std::string s = files->path(loc.file);
  s.append(":").append(std::to_string(loc.line));
  return s;
}

Json pose_json(const runtime::Pose& X) {
  Json j;
  j["R"] = {X.R(0, 0), X.R(0, 1), X.R(0, 2), X.R(1, 0), X.R(1, 1),
            X.R(1, 2), X.R(2, 0), X.R(2, 1), X.R(2, 2)};
  j["p"] = {X.p.x(), X.p.y(), X.p.z()};
  return j;
}

}  // namespace

namespace {

Json datum_json(const Data& d, size_t i, const SourceFiles* files) {
  Json e;
  e["id"] = i;
  e["name"] = d.name;
  e["iri"] = d.iri;
  e["type"] = to_string(d.type);
  e["slot"] = d.slot;
  if (!d.of.empty()) e["of"] = d.of;
  if (!d.with_respect_to.empty()) e["with-respect-to"] = d.with_respect_to;
  if (!d.reference_point.empty()) e["reference-point"] = d.reference_point;
  if (!d.as_seen_by.empty()) e["as-seen-by"] = d.as_seen_by;
  if (!d.quantity_kind.empty()) e["quantity-kind"] = d.quantity_kind;
  if (!d.unit.empty()) e["unit"] = d.unit;
  if (!d.value.empty()) e["value"] = d.value;
  e["where"] = location(d.where, files);
  return e;
}

Json arm_json(const ArmSolver& a, const SourceFiles* files) {
  Json e;
  e["name"] = a.name;
  e["iri"] = a.iri;
  e["chain"] = a.chain_iri;
  e["root"] = a.root_frame;
  if (!a.mount_pose_iri.empty()) {
    e["mount"] = a.mount_pose_iri;
    e["X_RB"] = pose_json(a.X_RB);
  }
  e["port"] = a.port;
  e["gravity"] = a.gravity;
  e["gravity-compensated"] = a.gravity_compensated;
  if (a.idle != ArmSolver::Idle::Unstated) {
    Json idle;
    idle["kind"] = a.idle == ArmSolver::Idle::BrakeAndHold ? "brake-and-hold" : "float";
    if (a.idle == ArmSolver::Idle::BrakeAndHold) idle["time-constant"] = a.idle_time_constant;
    e["when-idle"] = std::move(idle);
  }
  e["tip-is-last-segment"] = a.tip_is_last_segment;
  Json segs = Json::array();
  for (int i = 0; i < a.chain.size(); ++i) {
    const runtime::Segment& s = a.chain.segment(i);
    Json sj;
    sj["link"] = s.link;
    sj["joint"] = s.joint;
    sj["type"] = std::string(runtime::to_string(s.type));
    sj["X_PJ"] = pose_json(s.X_PJ);
    sj["axis"] = {s.axis_J.x(), s.axis_J.y(), s.axis_J.z()};
    sj["mass"] = s.inertia.mass;
    sj["com"] = {s.inertia.p_SoScm_S.x(), s.inertia.p_SoScm_S.y(), s.inertia.p_SoScm_S.z()};
    const runtime::Mat3& I = s.inertia.I_Scm_S;
    sj["inertia"] = {I(0, 0), I(0, 1), I(0, 2), I(1, 1), I(1, 2), I(2, 2)};
    sj["armature"] = s.armature;
    segs.push_back(std::move(sj));
  }
  e["segments"] = std::move(segs);
  e["X_NT"] = pose_json(a.chain.X_NT());
  Json outs = Json::array();
  for (const ArmOutput& o : a.outputs) {
    const char* what = o.what == ArmOutput::What::SegmentPose       ? "segment-pose"
                       : o.what == ArmOutput::What::ChainRootPose   ? "segment-pose-in-chain-root"
                       : o.what == ArmOutput::What::JointPosition   ? "joint-position"
                       : o.what == ArmOutput::What::JointVelocity   ? "joint-velocity"
                       : o.what == ArmOutput::What::JointTorque     ? "measured-joint-torque"
                       : o.what == ArmOutput::What::EstimatedWrench ? "estimated-wrench"
                       : o.what == ArmOutput::What::TipPose         ? "tip-pose"
                       : o.what == ArmOutput::What::TipPoseInChainRoot ? "tip-pose-in-chain-root"
                       : o.what == ArmOutput::What::TipTwist           ? "tip-twist"
                                                                       : "segment-twist";
    outs.push_back({{"what", what}, {"segment", o.segment}, {"data", o.data}});
  }
  e["outputs"] = std::move(outs);
  Json acc = Json::array();
  for (const AccelerationConstraint& c : a.acceleration_constraints) {
    Json e = {{"iri", c.iri}, {"component", c.component}, {"energy", c.energy}, {"level", c.level}};
    if (c.engaged_by >= 0) {
      e["engaged-by"] = c.engaged_by;
      e["engaged-tolerance"] = c.tolerance;
    }
    acc.push_back(std::move(e));
  }
  e["acceleration-constraints"] = std::move(acc);
  Json frc = Json::array();
  for (const CartesianForce& c : a.cartesian_forces) {
    Json f = {{"iri", c.iri}, {"segment", c.segment}, {"wrench", c.wrench}, {"level", c.level}};
    if (c.at_tip) f["at-tip"] = true;  // its wrench is at the tool's origin
    frc.push_back(std::move(f));
  }
  e["cartesian-forces"] = std::move(frc);
  Json jf = Json::array();
  for (const JointForce& c : a.joint_forces) {
    jf.push_back({{"iri", c.iri}, {"joint", c.joint}, {"force", c.force}, {"level", c.level}});
  }
  e["joint-forces"] = std::move(jf);
  e["priority-levels"] = a.priority_levels;
  e["where"] = location(a.where, files);
  return e;
}

Json base_json(const BaseSolver& base, const SourceFiles* files) {
  Json b;
  b["name"] = base.name;
  b["iri"] = base.iri;
  b["configuration"] = base.configuration;
  const runtime::KeloConfig& c = base.config;
  Json drives = Json::array();
  for (size_t i = 0; i < c.geometry.p_PoAi_P.size(); ++i) {
    const auto& d = c.geometry.p_PoAi_P[i];
    Json e;
    e["pivot"] = {d.x(), d.y()};
    e["drive-weight"] = c.drive_weight[i];
    e["force-alignment-weight"] = c.align_force_weight[i];
    e["moment-alignment-weight"] = c.align_moment_weight[i];
    drives.push_back(std::move(e));
  }
  b["drives"] = std::move(drives);
  b["wheel-radius"] = c.geometry.wheel_radius;
  b["wheel-distance"] = c.geometry.wheel_distance;
  b["castor-offset"] = c.geometry.castor_offset;
  b["wrench"] = base.wrench;
  b["twist"] = base.twist;
  b["where"] = location(base.where, files);
  return b;
}

// The common fields, then the kind's own (its print hook), then its state and
// place.
Json step_json(const Step& st, const SourceFiles* files) {
  Json e;
  e["kind"] = kind_name(st);
  e["name"] = st.name;
  e["iri"] = st.iri;
  e["in"] = st.in;
  e["out"] = st.out;
  if (st.solver >= 0) e["solver"] = st.solver;
  if (static_cast<size_t>(st.kind) < kStepKindCount) {
    if (const PrintHook print = info(st.kind).print) {
      StepJson fields{e};
      print(st, fields);
    }
  }
  if (st.state >= 0) e["state"] = st.state;
  e["where"] = location(st.where, files);
  return e;
}

}  // namespace

std::string to_json(const Program& p, const SourceFiles* files) {
  Json j;
  j["mospec-ir"] = 1;
  j["app"] = p.app;
  Json slots;
  for (int t = 0; t < kDataTypes; ++t)
    slots[std::string(to_string(static_cast<DataType>(t)))] = p.slots[static_cast<size_t>(t)];
  j["slots"] = slots;
  Json data = Json::array();
  for (size_t i = 0; i < p.data.size(); ++i) data.push_back(datum_json(p.data[i], i, files));
  j["data"] = std::move(data);
  Json arms = Json::array();
  for (const ArmSolver& a : p.arms) arms.push_back(arm_json(a, files));
  j["arms"] = std::move(arms);
  j["base"] = p.base ? base_json(*p.base, files) : Json(nullptr);
  Json steps = Json::array();
  for (const Step& st : p.steps) steps.push_back(step_json(st, files));
  j["schedule"] = std::move(steps);
  Json log = Json::array();
  for (const LogColumn& c : p.log) {
    Json e = {{"name", c.name}, {"unit", c.unit}, {"data", c.data}};
    if (c.component >= 0) e["component"] = c.component;
    if (c.kind == robot::LogColumnKind::Flag) e["latched"] = "flag";
    if (c.kind == robot::LogColumnKind::Event) e["latched"] = "event";
    log.push_back(std::move(e));
  }
  j["log"] = std::move(log);
  return j.dump(2) + "\n";
}

}  // namespace mospec::ir
