// The IR: a validated task model lowered to what one control tick executes.
//
// Lowering (lower.hpp) makes every decision: which runtime function computes
// each quantity, in which frame, from which inputs, in which order. What is
// left is a flat program over typed storage slots that two back-ends read
// without deciding anything: the interpreter (src/ir/interpreter.hpp) and the
// code generator's logic-less templates (src/codegen).
//
//   Data    a quantity of the model (a pose, a twist, a wrench, a direction or
//           position vector, a scalar, a flag, an event) with its frames and
//           units; each lives in one slot of the array for its type.
//   Step    one call of the runtime in schedule order: read the clock, arm
//           kinematics, a view, an operator, a constraint evaluation, a monitor,
//           a guarded motion's state update, a controller, an arm's ACHD solve,
//           the base's force distribution. Steps consume data that earlier
//           steps produce (a topological order, checked by verify()).
//   Solver  the constants of an arm's ACHD (chain, root, gravity, motion
//           drivers with their priority levels) and of the base.
//
// Units are SI throughout; lowering rejects anything else. Ids are the
// model's IRIs; names are unique C++ identifiers derived from them.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "robot/controller.hpp"
#include "runtime/chain.hpp"
#include "runtime/evaluators.hpp"
#include "runtime/kelo.hpp"
#include "runtime/model.hpp"
#include "runtime/monitors.hpp"
#include "support/diagnostics.hpp"

namespace mospec::mustache {
class Data;
}

namespace mospec::ir {

// Inertia: a rigid body's inertia (runtime::RigidBodyInertia), always a model
// constant: mass, first moment of mass, rotational inertia about a point.
enum class DataType : uint8_t { Scalar, Vector3, Pose, Twist, Wrench, Flag, Event, Inertia };
inline constexpr int kDataTypes = 8;
std::string_view to_string(DataType);

struct Data {
  std::string iri;
  std::string name;  // C++ identifier, unique in the program
  DataType type = DataType::Scalar;
  int slot = 0;  // index into the storage array of its type
  // Frames (IRIs, empty when they do not apply to the type).
  std::string of, with_respect_to, reference_point, as_seen_by;
  std::string quantity_kind;  // QUDT local names joined by ',' (angular part first)
  std::string unit;           // QUDT local names joined by ','
  // A model constant (a reference value, a fixed pose): Scalar 1 value, Vector3
  // 3, Pose 12 (R row-major, then p), Inertia 10 (m; h; Ixx, Iyy, Izz, Ixy,
  // Ixz, Iyz). Empty for data a step produces.
  std::vector<double> value;
  SourceLoc where;
};

enum class StepKind : uint8_t {
  ReadClock,      // out: [time]
  ArmKinematics,  // solver; outs: the solver's outputs (arm_outputs)
  ViewRead,       // in: [pose|twist|wrench]; out: [scalar]; view
  ViewWrite,      // ins: [scalar...]; out: [twist|wrench] (others zero); views
  Operator,       // a pure computation: Step::op indexes operator_kinds() (operators.hpp)
  Evaluate,       // ins: [quantity, (active flag)]; outs: [satisfied flag, error|output scalar]
  LevelMonitor,   // ins: [error, (running flag)]; out: [flag]
  EdgeMonitor,    // ins: [error, (running flag)]; out: [event]; edges
  GuardedMotion,  // ins: [when..., while..., until... flags]; outs: [running flag, ended event]
  AnyOf,          // ins: [flags...] (2 or more); out: [flag] = any of them
  Controller,     // ins: [signals..., (active flag)]; out: [control signal]; Step::controller
                  // indexes controller_kinds() (controllers.hpp)
  ArmSolve,       // solver; ins: drivers' data, motion gates; out: [degraded flag]; writes
                  // the arm's joint torques
  BaseForceDistribution,    // base solver; ins: [platform wrench, motion gates...]; writes the hub
                            // torques
  BaseVelocityComposition,  // base solver; out: [platform twist] from pivots and wheel rates
};
// Keep BaseVelocityComposition the last StepKind (the table below checks it).
inline constexpr size_t kStepKindCount = static_cast<size_t>(StepKind::BaseVelocityComposition) + 1;
std::string_view to_string(StepKind);

// Per-step state the tick keeps across ticks (controllers, monitors, motions).
enum class StateKind : uint8_t { Monitor, Motion };

// What a step kind is to the code that reads a program without knowing its
// kinds: lowering's later passes, the verdict, the report and the CLI's checks
// (StepKindInfo::role). A new kind picks the role whose outputs it shares.
enum class StepRole : uint8_t {
  Clock,        // out[0]: the control clock's time
  Measurement,  // reads the robot's sensors into its outputs (arm kinematics, base velocity)
  Computation,  // a pure function of its inputs (views, operators, any-of)
  Constraint,   // evaluates a constraint: out[0] its satisfied flag, out[1] its error or output
  Monitor,      // watches an error: out[0] its flag or event
  Motion,       // a guarded motion: out[0] its running flag, out[1] its ended event
  Controller,   // a control law: out[0] its signal, from its input signals
  Solver,       // writes the robot's command from its drivers (out[0], if any: degraded)
};

// The member a step owns in generated code, by which codegen names and
// declares it.
enum class StepMember : uint8_t { None, Evaluator, Controller, MonitorTolerance };

struct Step;
struct Program;
struct Machine;
class EmitContext;
struct Signature;
class Findings;
struct StepJson;
using SignatureHook = Signature (*)(const Step&, const Program&);
using VerifyHook = void (*)(const Step&, const Program&, Findings&);
using PrintHook = void (*)(const Step&, StepJson&);
struct LogColumn;
using LogHook = void (*)(const Program&, const Step&, std::vector<LogColumn>&);
using GateHook = int (*)(const Step&);
using InterpretHook = void (*)(Machine&, const Step&, size_t index, const robot::MeasuredState&,
                               robot::Command&) noexcept;
using PrepareHook = void (*)(Machine&, const Step&, size_t index);
using EmitHook = void (*)(const EmitContext&, const Step&, size_t index, mustache::Data& section);

// Every step kind, declared once (kStepKinds in ir.cpp): its IR name (the
// JSON's "kind", and codegen's template section `is_<name>` with '-' as '_'),
// the state slot it owns, the vocabulary it lowers from, what it reads and
// writes, its role, and its hooks (kinds/*.cpp): the data types it takes and
// gives (signature) and the rules of its own fields (verify, optional), which
// the verifier applies; its own fields in the IR's JSON (print, optional);
// the columns lowering logs for it, which the verdict reads (log, optional);
// what the interpreter allocates for it (prepare, optional) and executes each
// tick (interpret); and the template section codegen emits for it (emit).
// ir_step_kinds_test fails when a hook is missing or the controller template
// lacks its section. Operators
// and controllers are one kind each, whose instances come from their own
// registries (operators.hpp, controllers.hpp).
struct StepKindInfo {
  StepKind kind;
  std::string_view name;
  std::optional<StateKind> state;  // the per-step state slot, if any
  std::string_view lowered_from;   // the vocabulary class(es), or how lowering derives it
  std::string_view summary;        // inputs and outputs
  StepRole role = StepRole::Computation;
  StepMember member = StepMember::None;
  SignatureHook signature = nullptr;
  VerifyHook verify = nullptr;
  PrintHook print = nullptr;
  LogHook log = nullptr;
  // The input holding the running flag that gates the step's output, which
  // lowering's gating pass gives the solves it reaches; -1 (or none): ungated.
  GateHook gate = nullptr;
  PrepareHook prepare = nullptr;
  InterpretHook interpret = nullptr;
  EmitHook emit = nullptr;
};
std::span<const StepKindInfo> step_kinds();
const StepKindInfo& info(StepKind kind);
// The codegen template's section for a kind: "is_" + name, '-' -> '_'.
std::string template_section(StepKind kind);

struct ViewSpec {
  int index = 0;  // component: 0..5 of an angular-first 6-vector; 0..5 of a pose
                  // (0..2 rotation vector, 3..5 position)
};

struct Step {
  StepKind kind = StepKind::ReadClock;
  std::string iri;           // the model entity that asked for it
  std::string name;          // C++ identifier
  std::vector<int> in, out;  // data indices
  SourceLoc where;
  // Per kind (unused fields stay default):
  int op = -1;                         // Operator: index into operator_kinds()
  int solver = -1;                     // ArmKinematics, ArmSolve: arm solver index
  std::vector<int> views;              // ViewRead: 1 component; ViewWrite: one per input
  runtime::ConstraintSpec constraint;  // Evaluate
  // Evaluate: where constraint.tolerance comes from: the model's
  // (mos-grd:tolerance), the default of its unit (default_tolerance(), for a
  // constraint a motion enforces), or none (0: satisfied only exactly, or
  // inside an inequality's bounds).
  enum class Tolerance : uint8_t { None, Stated, Default } tolerance_source = Tolerance::None;
  bool has_error_output = false;  // Evaluate: out[1] is the error (else none/output)
  // Evaluate of a bilateral constraint: the data of its lower and upper
  // bounds, logged beside its value (-1: none). Not in the IR's JSON.
  int lower_bound = -1, upper_bound = -1;
  int n_when = 0;   // GuardedMotion: ins[0, n_when) are `when`,
  int n_while = 0;  // then n_while `while` (checked per-conditions),
                    // then the `until`
  // GuardedMotion: the satisfied flags of the constraints the motion enforces
  // (its goals), which the step does not read: the verdict judges them when
  // the motion ends and watches them while it runs. goals[0, n_goal_whiles)
  // are the `while` constraints on quantities the motion acts on (not
  // checked by the step), the rest the constraints whose errors its
  // controllers read that its `while` does not list.
  std::vector<int> goals;
  int n_goal_whiles = 0;
  runtime::Edges edges = runtime::Edges::Rising;  // EdgeMonitor: the edges it reports
  int controller = -1;                            // Controller: index into controller_kinds()
  std::vector<double> parameters;                 // Controller: one value per parameter of its kind
  // Controller: where each parameter is stated (the literal, or the quantity
  // the property names); the controller's place for the runtime's defaults.
  // For diagnostics only: not in the IR's JSON.
  std::vector<SourceLoc> parameters_where;
  int state = -1;  // stateful controllers, monitors, motions: their state slot
  // ArmSolve: in[0, n_drivers) are the drivers' data; in[n_drivers, ...) the
  // running flags of the motions whose controllers drive this arm. With such
  // gates and none of them running, the arm holds (steps::arm_hold).
  // -1: every input is a driver (no gates). drivers() resolves it.
  int n_drivers = -1;
  size_t drivers() const { return n_drivers < 0 ? in.size() : static_cast<size_t>(n_drivers); }
};

// What a step is to code that does not know its kind (info(kind).role).
StepRole role(const Step& step);

// What ArmKinematics writes into each output: the pose of segment frame S_i
// w.r.t. the root (as seen by the root), or the twist of S_i w.r.t. the root at
// So_i as seen by the root.
// With a mount (root_frame is not the chain's root), a pose may also be asked
// w.r.t. the chain's own root: X_BS = X_RB^-1 X_RS (ChainRootPose).
// The Tip* kinds are the same of the chain's tip frame T, a tool fixed to the
// last segment (`segment` is the last one): its pose X_BN X_NT, and its twist
// at To (runtime::steps::tip_pose, tip_twist).
// Joint quantities (mospec/joints) are scalars of joint `segment` (segment i
// is moved by joint i): its position q_i, its velocity qd_i (as read by the
// kinematics step, a non-finite sample keeping the last finite value) and its
// measured torque tau_i (the arm's torque sensors, robot::ArmMeasurement::tau,
// likewise).
struct ArmOutput {
  enum class What : uint8_t {
    SegmentPose,
    SegmentTwist,
    ChainRootPose,
    JointPosition,
    JointVelocity,
    JointTorque,
    EstimatedWrench,  // the wrench on segment S_i at So_i seen by the root, from the measured
                      // torques (runtime::steps::estimated_wrench)
    TipPose,
    TipTwist,
    TipPoseInChainRoot
  } what = What::SegmentPose;
  int segment = 0;
  int data = 0;
};

struct AccelerationConstraint {
  std::string iri;
  int component = 0;  // 0..5 of the root-frame spatial acceleration of the tip (angular first)
  int energy = -1;    // scalar data: the constraint's value (beta)
  int level = 0;      // priority level (0 = highest)
  // One-sided: the error of the less-than/greater-than constraint whose
  // controller produces `energy`, and that constraint's tolerance. The
  // direction is constrained only while the quantity is beyond the bound
  // (runtime::steps::one_sided_engaged: by more than half the tolerance, until
  // back within a quarter of it); otherwise it moves freely. -1: always
  // constrained.
  int engaged_by = -1;
  double tolerance = 0.0;
};
struct CartesianForce {
  std::string iri;
  int segment = 0;  // the segment the wrench acts on
  int wrench = -1;  // wrench data: at the segment origin, as seen by the root
  int level = 0;
  // Attached to the chain's tip frame T (a tool fixed to the last segment,
  // `segment`): the wrench is at To, as seen by the root, and is moved to the
  // segment's origin each tick (runtime::steps::tip_wrench_at_segment_origin).
  bool at_tip = false;
};
struct JointForce {
  std::string iri;
  int joint = 0;
  int force = -1;  // scalar data
  int level = 0;
};

struct ArmSolver {
  std::string iri, name;
  std::string chain_iri, root_frame;
  // The chain as the solver sees it: rooted at root_frame (when that is not
  // the chain's own root, the constant mount pose is composed into the first
  // joint's placement).
  std::string mount_pose_iri;  // the constant pose used for that, if any
  runtime::Pose X_RB;          // that pose (identity without a mount)
  int port = 0;                // which arm of the robot (MeasuredState::arm[port]) it drives
  runtime::Chain chain{""};
  // The chain as its robot description has it, rooted at its own root: what
  // the simulator builds (mounted at X_RB). Not part of the IR's JSON.
  runtime::Chain robot_chain{""};
  // Where the acceleration constraints act: at the last segment's origin
  // (true), or at the chain's tip frame T, a tool fixed to that segment
  // (false: the drivers are attached to the tool).
  bool tip_is_last_segment = true;
  std::array<double, 3> gravity{};  // in the root frame [m/s^2]
  // mos-slv:GravityCompensated: the ACHD solve runs without gravity, so the
  // directions no driver controls keep their velocity; otherwise (the paper's
  // reading) they fall under `gravity`. The command realises the solved motion
  // under real gravity either way.
  bool gravity_compensated = false;
  // mos-slv:when-idle: what the arm does in the ticks no motion that drives it
  // runs. Unstated is allowed only for an arm no motion gates.
  enum class Idle : uint8_t { Unstated, BrakeAndHold, Float };
  Idle idle = Idle::Unstated;
  double idle_time_constant = 0.0;  // BrakeAndHold: every joint's velocity decays with it [s]
  SourceLoc idle_where;             // the when-idle statement, for messages
  std::vector<ArmOutput> outputs;
  std::vector<AccelerationConstraint> acceleration_constraints;  // column order
  std::vector<CartesianForce> cartesian_forces;
  std::vector<JointForce> joint_forces;
  std::vector<std::vector<std::string>> priority_levels;  // driver IRIs per level
  SourceLoc where;
};

// The KELO base: a force distribution solver (the platform wrench it
// distributes) and/or a velocity composition solver (the platform twist it
// measures); one geometry for both.
struct BaseSolver {
  std::string iri, name;  // the first of the two solvers the model has
  // The CastorDriveBase both solvers name (`configuration`) and its numbers:
  // geometry, drive weights and alignment weights (description::read_base).
  std::string configuration;
  runtime::KeloConfig config;
  int wrench = -1;  // platform wrench: at the platform origin, as seen by the platform
  int twist = -1;   // platform twist w.r.t. the floor, at the platform origin, seen by it
  SourceLoc where;
};

// One column of the per-tick log: the value of a datum after the tick (a flag
// or event as 0/1). Chosen by lowering: every constraint's measured value,
// error and satisfaction, every monitor, every motion's state, every
// controller's output, the bounds of bilateral constraints, and the platform
// wrench the base distributes.
struct LogColumn {
  std::string name;  // e.g. "cstr-dist-rightarm-shoulder-ee.error"
  std::string unit;  // QUDT local name, "" for flags
  int data = 0;
  int component = -1;  // for a twist or wrench: which of its 6 entries (angular first)
  // How a decimated log keeps it (robot::LogColumnKind): a monitor's flag and
  // every event are latched into the next logged row.
  robot::LogColumnKind kind = robot::LogColumnKind::Value;
};

struct Program;
// Per arm index of the robot (ArmSolver::port, 0 .. the largest port): the
// joint count of the arm the program drives there, 0 where it drives none.
std::vector<int> arm_joints(const Program& program);

// A step's kind as the IR's JSON and messages name it: the operator's name
// for an Operator step ("compose-pose"), the controller's for a Controller
// step ("pid"), else to_string(kind).
std::string_view kind_name(const Step& step);

struct Program {
  std::string app;  // the app model's IRI
  std::vector<Data> data;
  std::array<int, kDataTypes> slots{};  // number of slots per DataType
  std::vector<Step> steps;              // schedule order
  std::array<int, 2> states{};          // number of state slots per StateKind
  // Number of state slots per controller kind (controller_kinds() order; a
  // kind past the end has none).
  std::vector<int> controller_states;
  std::vector<ArmSolver> arms;
  std::optional<BaseSolver> base;
  std::vector<LogColumn> log;

  int count(DataType t) const { return slots[static_cast<int>(t)]; }
  int controller_state_count(int kind) const {
    return kind >= 0 && static_cast<size_t>(kind) < controller_states.size()
               ? controller_states[static_cast<size_t>(kind)]
               : 0;
  }
};

// The tolerance of a constraint a motion enforces when the model states none,
// by the constrained quantity's unit (QUDT local name): 1 mm, 0.01 rad, 0.5 N,
// ... (docs/simulation.md, "Default tolerances"); none for another unit.
std::optional<double> default_tolerance(std::string_view unit);

// A constraint's relation as the IR's JSON, the run summary and the report
// spell it: "equality", "less-than", "greater-than", "bilateral", "assignment".
std::string_view relation_name(runtime::ConstraintKind kind);
// The table itself, for the docs' test: (unit, tolerance, what it is).
struct DefaultTolerance {
  std::string_view unit;
  double tolerance;
  std::string_view kind;
};
std::span<const DefaultTolerance> default_tolerances();

// Most `when`, checked `while` or `until` guards one guarded motion may have.
inline constexpr int kMaxGuards = 16;

// Setup-time constants every back-end builds the same way:
// the arm's ACHD model: the chain with the solver's gravity (`physical`), or
// the task model of the ACHD solve (runtime::steps::arm_solve): the same,
// without gravity when the solver is GravityCompensated. The physical model's
// tip frame is the chain's (the tool, which the tip outputs and a force on the
// tool read); the task model's is the tool only when the acceleration
// constraints are attached to it, else the last segment's frame (X_NT =
// identity, tip_is_last_segment), so the constraints act at that origin.
runtime::AchdModel achd_model(const ArmSolver& arm, bool physical);
// The time constant of the arm's idle behaviour (runtime::steps::arm_hold):
// BrakeAndHold's, or kFloatTimeConstant for Float.
double idle_time_constant(const ArmSolver& arm);
// The base's KELO configuration: the numbers the model's configuration gives.
runtime::KeloConfig kelo_config(const BaseSolver& base);
// A constant pose from Data::value (R row-major, then p).
runtime::Pose constant_pose(const std::vector<double>& value);

// Checks the invariants the back-ends rely on: slots are dense per type and
// used once; every step reads data that exist, of the types its kind takes,
// and writes data of the types it gives; every datum has at most one producer
// (a step or the model's constant value); every input is produced (and, once
// scheduled, by an earlier step); views, guards, state slots, solvers and log
// columns are in range. Returns every problem (code "ir-invalid"), each
// located at the model entity of the step or datum involved (with `files`),
// saying what was expected and what the program has.
enum class Stage : uint8_t {
  Unscheduled,  // during lowering: steps in declaration order, inputs perhaps not yet produced
  Scheduled,    // the finished program: steps in a topological order
};
std::vector<Diagnostic> check(const Program& program, const SourceFiles* files = nullptr,
                              Stage stage = Stage::Scheduled);

class VerifyError : public Error {
 public:
  explicit VerifyError(std::vector<Diagnostic> diagnostics);
  const std::vector<Diagnostic>& diagnostics() const { return diagnostics_; }

 private:
  std::vector<Diagnostic> diagnostics_;
};
// check(); throws VerifyError with every problem when there is any.
void verify(const Program& program, const SourceFiles* files = nullptr);

// The program as deterministic JSON (fixed key order, %.17g numbers).
std::string to_json(const Program& program, const SourceFiles* files = nullptr);

}  // namespace mospec::ir
