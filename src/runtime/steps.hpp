// The kernels of the IR's steps (src/ir/ir.hpp): one function per step kind
// that isn't a single operator call, so the interpreter and the generated code
// execute literally the same code and produce bit-identical logs. Everything
// here is noexcept and allocation-free; the arrays are sized at setup.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>

#include "runtime/achd.hpp"
#include "runtime/controllers.hpp"
#include "runtime/evaluators.hpp"
#include "runtime/kelo.hpp"
#include "runtime/model.hpp"
#include "runtime/monitors.hpp"
#include "runtime/operators.hpp"

namespace mospec::runtime::steps {

// ---------------------------------------------------------------------------
// Arms. One ArmWorkspace per ACHD solver, built at setup.
struct ArmWorkspace {
  explicit ArmWorkspace(const AchdModel& model, int constraints);
  JointVector q, qd, tau_ff;
  // The measured joint torques the task reads (joint_torque): each entry's
  // last finite sample.
  JointVector tau_measured;
  JointVector tau_bias;  // estimated_wrench: h(q, qd), gravity and velocity products
  std::array<Vec6, kMaxJoints> F_ext{};
  ConstraintMatrix alpha_To_B;  // 6 x nc, filled at setup (unit columns)
  ConstraintVector beta;        // nc, filled every tick from the drivers
  // Which columns constrain this tick (filled with beta). A column driven from
  // a one-sided (less-than/greater-than) constraint is engaged only while its
  // quantity is beyond the bound (one_sided_engaged); a disengaged column
  // leaves its direction to the least-constrained motion, as if the column
  // were not there. Kept from tick to tick (its hysteresis).
  std::array<bool, kMaxConstraints> engaged{};
  ConstraintMatrix alpha_engaged;  // the engaged columns, packed left (setup-sized)
  ConstraintVector beta_engaged;
  JointVector tau_command;  // what is sent to the arm
  Status status = Status::Ok;
  bool input_fault = false;  // the last sample had a non-finite q or qd
  bool any_valid = false;    // a complete finite sample has been seen
};

// Reads q, qd from the measured arm (the first nq joints) and runs the forward
// velocity sweep: data.X_PS, X_BS, X_BT and the segment twists data.V (in S_i
// at So_i). A non-finite entry sets input_fault and keeps that joint's last
// finite value (so nothing downstream jumps); while input_fault is set the
// solve step holds the arm instead of driving it.
void arm_kinematics(const AchdModel& model, AchdData& data, ArmWorkspace& ws,
                    std::span<const double> q_measured,
                    std::span<const double> qd_measured) noexcept;

// The pose of segment S_i w.r.t. the root, as seen by the root.
inline const Pose& segment_pose(const AchdData& data, int segment) noexcept {
  return data.X_BS[static_cast<std::size_t>(segment)];
}
// The pose of S_i w.r.t. the chain's own root B when the solver's root R
// carries it at the constant X_RB: X_BS = X_RB^-1 X_RS.
inline Pose segment_pose_in_chain_root(const AchdData& data, const Pose& X_BR,
                                       int segment) noexcept {
  return X_BR * data.X_BS[static_cast<std::size_t>(segment)];
}
// The twist of S_i w.r.t. the root at So_i, as seen by the root.
inline Vec6 segment_twist(const AchdData& data, int segment) noexcept {
  return rotate_twist_to_proximal(data.X_BS[static_cast<std::size_t>(segment)],
                                  data.V[static_cast<std::size_t>(segment)]);
}

// The chain's tip frame T (a tool fixed to the last segment N, at model.X_NT):
// read from N's kinematics as arm_kinematics left them, with `model` the one
// that carries the tool (the physical model: its X_NT is the chain's tip).
// T's pose w.r.t. the root, as seen by the root: X_BN X_NT.
inline Pose tip_pose(const AchdModel& model, const AchdData& data) noexcept {
  return data.X_BS[static_cast<std::size_t>(model.nq - 1)] * model.X_NT;
}
// The same w.r.t. the chain's own root B (see segment_pose_in_chain_root).
inline Pose tip_pose_in_chain_root(const AchdModel& model, const AchdData& data,
                                   const Pose& X_BR) noexcept {
  return X_BR * tip_pose(model, data);
}
// T's twist w.r.t. the root at To, as seen by the root. The tool moves with N,
// so it is N's twist moved to To: the same angular velocity, and the linear
// velocity of the point To, v_No + w x p_NoTo.
inline Vec6 tip_twist(const AchdModel& model, const AchdData& data) noexcept {
  const auto k = static_cast<std::size_t>(model.nq - 1);
  const Vec6& V_N = data.V[k];  // in N, at No
  Vec6 V_To_N;
  V_To_N << V_N.head<3>(), V_N.tail<3>() + V_N.head<3>().cross(model.X_NT.p);
  return rotate_twist_to_proximal(data.X_BS[k], V_To_N);
}
// A wrench acting at To (seen by the root) as the same wrench at the last
// segment's origin No, where ACHD takes a segment's external wrench:
// n_No = n_To + p_NoTo x f.
inline Vec6 tip_wrench_at_segment_origin(const AchdModel& model, const AchdData& data,
                                         const Vec6& F_To_B) noexcept {
  const Vec3 p_NoTo_B = data.X_BS[static_cast<std::size_t>(model.nq - 1)].R * model.X_NT.p;
  Vec6 F = F_To_B;
  F.head<3>() += p_NoTo_B.cross(F_To_B.tail<3>());
  return F;
}

// Joint i's position q_i [rad] and velocity qd_i [rad/s] as arm_kinematics
// read them this tick (a non-finite sample keeps the last finite value).
inline double joint_position(const ArmWorkspace& ws, int joint) noexcept {
  return ws.q[joint];
}
inline double joint_velocity(const ArmWorkspace& ws, int joint) noexcept {
  return ws.qd[joint];
}
// Joint i's measured torque [N·m] (the arm's torque sensors): a non-finite
// sample, or none, keeps the last finite value (0 before the first).
inline double joint_torque(ArmWorkspace& ws, std::span<const double> tau_measured,
                           int joint) noexcept {
  const auto k = static_cast<std::size_t>(joint);
  if (k < tau_measured.size() && std::isfinite(tau_measured[k]))
    ws.tau_measured[joint] = tau_measured[k];
  return ws.tau_measured[joint];
}

// The wrench the environment exerts on segment S_i, at So_i and seen by the
// root, estimated from the measured joint torques (quasi-static):
//   the arm's dynamics M(q) qdd + h(q, qd) = tau + J_i(q)^T F,
//   with qdd taken as 0:  J_i^T F = h(q, qd) - tau_measured,
//   F = (J_i J_i^T + lambda^2 I)^-1 J_i (h - tau_measured),
// J_i the 6 x n Jacobian of S_i's twist at So_i seen by the root (angular rows
// first; the joints after i are zero columns), h from `physical_model` (the
// solver's gravity), lambda^2 = kWrenchEstimateDamping2. Limits: the arm's
// acceleration, friction and the rotors' inertia show up as force (at the
// Gen3's accelerations, tenths of a newton); a wrench in the null space of
// J_i^T (a chain with fewer than six joints up to S_i, or a singular
// configuration) is not seen (damped: it reads as ~0, never as a jump); the
// estimate is only as good as the model's inertias. Measured torques are read
// as joint_torque reads them (last finite sample).
Vec6 estimated_wrench(const AchdModel& physical_model, AchdData& data, ArmWorkspace& ws,
                      std::span<const double> tau_measured, int segment) noexcept;
// lambda^2 above [1 in the units of J J^T: m^2 for the force rows]: small
// enough to leave a regular configuration's estimate unchanged to ~1e-6.
inline constexpr double kWrenchEstimateDamping2 = 1e-9;

// Solves ACHD with the workspace's drivers (F_ext, tau_ff, alpha, beta; the
// engaged columns only) in `task_model` and computes the joint torques to
// send. `task_model` carries the solver's gravity (directions no driver
// controls fall, the paper's least-constrained motion) or none
// (mos-slv:GravityCompensated: they keep their velocity); either way the
// command realises the solved motion on the real robot, where the drivers'
// wrenches are virtual and gravity is real:
//   tau_command = rne(q, qd, qdd) in `physical_model` (with the solver's
//   gravity) and without F_ext.
// On a sensor fault (input_fault) it holds the arm (arm_hold) on the last
// valid sample; zero torque when the solver fails or no valid sample was seen.
void arm_solve(const AchdModel& task_model, const AchdModel& physical_model, AchdData& data,
               ArmWorkspace& ws, std::span<double> tau_out) noexcept;

// The arm when no motion drives it (the model's mos-slv:when-idle): it brakes
// to a stop and then holds, gravity-compensated: tau = rne(q, qd, -qd /
// time_constant) with the solver's gravity (every joint's velocity decays with
// that time constant on the model). An infinite time constant is the Float
// behaviour: gravity compensation alone, the joints keep their velocity. Zero
// torque before the first complete finite sample.
void arm_hold(const AchdModel& physical_model, AchdData& data, ArmWorkspace& ws,
              double time_constant, std::span<double> tau_out) noexcept;
// How arm_solve reacts to a sensor fault (a non-finite q or qd): the hold
// above with this time constant, whatever the model's idle behaviour, since
// the task's quantities cannot be computed. A safety reaction of the runtime,
// not a task behaviour.
inline constexpr double kFaultHoldTimeConstant = 0.1;  // [s]
// The Float behaviour's time constant.
inline constexpr double kFloatTimeConstant = std::numeric_limits<double>::infinity();

// Whether a one-sided row is engaged this tick, given whether it was in the
// last and its inequality's error (0 inside the bound) and tolerance: engaged
// once the quantity is beyond the bound by more than kEngageBeyond of the
// tolerance, released once back within kReleaseWithin of it. The controller
// on the error drives the quantity towards the bound itself, which a PD
// reaches only asymptotically: released short of it, the direction is free
// again, so a force into the feasible side moves the quantity away from the
// bound. Engaging at half the tolerance, not at its edge, keeps a force that
// pushes out (a row that engages and releases, tick after tick) within the
// band the constraint is satisfied in, overshoot included. A tolerance of 0:
// engaged while the error is not 0. A NaN error: engaged (the solve then
// faults on its NaN output).
inline constexpr double kEngageBeyond = 0.5;
inline constexpr double kReleaseWithin = 0.25;
inline bool one_sided_engaged(bool engaged, double error, double tolerance) noexcept {
  const double beyond = std::abs(error);
  if (std::isnan(beyond)) return true;
  return beyond > (engaged ? kReleaseWithin : kEngageBeyond) * tolerance;
}

// ---------------------------------------------------------------------------
// Views (1D <-> 3D).
inline double view_pose(const Pose& X, int index) noexcept {
  return view(X, View{index < 3 ? Part::Angular : Part::Linear, static_cast<Axis>(index % 3)});
}
inline double view_vec6(const Vec6& v, int index) noexcept {
  return v[index];
}

// ---------------------------------------------------------------------------
// Constraint evaluation. `active` gates an assignment (its output is 0 while
// the motion it belongs to is not running); error evaluators always measure.
// Writes the satisfaction and the error (or the assignment's output).
inline void evaluate(const ConstraintEvaluator& evaluator, double measured, bool active,
                     bool& satisfied, double& error_or_output) noexcept {
  const Evaluation e = evaluator.evaluate(measured);
  satisfied = e.satisfied;
  if (evaluator.spec().kind == ConstraintKind::Assignment) {
    error_or_output = active ? e.output : 0.0;
  } else {
    error_or_output = e.error;
  }
}

// ---------------------------------------------------------------------------
// Monitors watch an error signal: the watched constraint is satisfied while
// the error is within `tolerance` of 0 (exactly 0 for inequalities inside their
// feasible set; an equality's tolerance is the model's, mos-grd:tolerance). A
// monitor that constraint handlers list reports for their motions: `running`
// is whether one of them runs after this tick, and the monitor reports in
// every tick one of them runs, the tick it ends included (a post-condition's
// event, or the violated per-condition's, is seen). It watches the constraint
// in every tick, so an edge is a change of the constraint, never the motion
// starting. A monitor no handler lists always reports (`running` is true).
inline bool monitor_reports(MonitorState& state, bool running) noexcept {
  const bool reports = running || state.was_running;
  state.was_running = running;
  return reports;
}
inline bool level_monitor(MonitorState& state, double error, double tolerance,
                          bool running) noexcept {
  const bool satisfied = LevelMonitor::update(state, std::abs(error) <= tolerance);
  return monitor_reports(state, running) && satisfied;
}
// An edge-triggered monitor: the edge of the watched constraint's
// satisfaction in this tick, as an event code (Event: 0 none, 1 the constraint
// became satisfied, 2 it stopped being satisfied), or 0 when the monitor does
// not report that edge (`edges`) or does not report in this tick. Before the
// first tick the constraint counts as not satisfied: one satisfied at the
// first tick is a rising edge.
inline std::uint8_t edge_monitor(MonitorState& state, double error, double tolerance, Edges edges,
                                 bool running) noexcept {
  const bool before = state.satisfied;
  const bool after = LevelMonitor::update(state, std::abs(error) <= tolerance);
  if (!monitor_reports(state, running) || before == after) return 0;
  const auto e = static_cast<std::uint8_t>(after ? Event::Rising : Event::Falling);
  return (static_cast<std::uint8_t>(edges) & e) != 0 ? e : 0;
}

// ---------------------------------------------------------------------------
// Guarded motions (paper Sec. II-D): Idle -> Running when every `when` holds
// (at once when there is none). While Running, every tick (the one it starts
// in included):
//   - Running -> Done as soon as any `until` holds (the motion ends normally);
//   - else Running -> Aborted when any checked per-condition (`while`) does
//     not hold.
// `ended` is the motion's end event: a MotionEnd code in the tick it ends, 0
// in every other. Returns whether the motion is running after this tick.
enum class MotionState : uint8_t { Idle = 0, Running = 1, Done = 2, Aborted = 3 };
enum class MotionEnd : uint8_t { None = 0, Until = 1, WhileViolated = 2 };
inline bool guarded_motion(MotionState& state, std::span<const bool> when,
                           std::span<const bool> whiles, std::span<const bool> until,
                           std::uint8_t& ended) noexcept {
  ended = static_cast<std::uint8_t>(MotionEnd::None);
  if (state == MotionState::Idle) {
    bool all = true;
    for (bool w : when) all = all && w;
    if (all) state = MotionState::Running;
  }
  if (state != MotionState::Running) return false;
  for (bool u : until) {
    if (u) {
      state = MotionState::Done;
      ended = static_cast<std::uint8_t>(MotionEnd::Until);
      return false;
    }
  }
  for (bool w : whiles) {
    if (!w) {
      state = MotionState::Aborted;
      ended = static_cast<std::uint8_t>(MotionEnd::WhileViolated);
      return false;
    }
  }
  return true;
}

// ---------------------------------------------------------------------------
// Controllers run while their motion runs; otherwise their output is 0 and
// their state is reset (a motion that starts later starts from a clean
// integral).
template <class Controller, class State>
inline double gated_step(const Controller& controller, State& state, double error, double dt,
                         bool active) noexcept {
  if (!active) {
    Controller::reset(state);
    return 0.0;
  }
  controller.step(state, error, dt);
  return state.output;
}

inline double pid(const Pid& controller, PidState& state, double error, double dt,
                  bool active) noexcept {
  return gated_step(controller, state, error, dt, active);
}

// A damping controller (stateless): the force opposing `velocity`.
inline double damping(const Damping& controller, double velocity, bool active) noexcept {
  return active ? controller.force(velocity) : 0.0;
}

// An impedance controller: as pid() (inactive: 0, state reset).
inline double impedance(const Impedance& controller, ImpedanceState& state, double error, double dt,
                        bool active) noexcept {
  return gated_step(controller, state, error, dt, active);
}

// ---------------------------------------------------------------------------
// Base: the platform wrench F_Po_P (at the platform origin, seen by P)
// distributed to the drives (paper Eq. 2-3) from the measured pivot angles.
// Non-finite inputs give zero hub torques.
void base_force_distribution(const KeloModel& model, KeloData& data,
                             std::span<const double> pivot_q, const Vec6& F_Po_P,
                             std::span<double> wheel_tau) noexcept;

// The base when no motion drives it: it brakes to a stop and stays there,
// with a platform wrench opposing its measured planar twist,
// F_p = -[c_lin vx, c_lin vy, c_rot wz], distributed like any other.
inline constexpr double kBaseHoldLinearDamping = 400.0;  // [N·s/m]: ~0.2 s for the ~80 kg platform
inline constexpr double kBaseHoldAngularDamping = 40.0;  // [N·m·s/rad]
void base_hold(const KeloModel& model, KeloData& data, std::span<const double> pivot_q,
               std::span<const double> wheel_qd, std::span<double> wheel_tau) noexcept;

// The base's velocity composition: the platform twist (w.r.t. the floor, at
// the platform origin, seen by the platform; angular first) from the measured
// pivot angles and wheel rates, by weighted least squares over the drives.
// Non-finite measurements give a zero twist.
void base_velocity(const KeloModel& model, KeloData& data, std::span<const double> pivot_q,
                   std::span<const double> wheel_qd, Vec6& twist) noexcept;

}  // namespace mospec::runtime::steps
