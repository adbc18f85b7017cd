#include "ir/interpreter.hpp"

#include <array>
#include <cmath>

#include "ir/operators.hpp"
#include "runtime/model.hpp"

namespace mospec::ir {

using runtime::Pose;
using runtime::Vec3;
using runtime::Vec6;

struct Interpreter::Arm {
  explicit Arm(const ArmSolver& s)
      : model(achd_model(s, true)),
        task_model(achd_model(s, false)),
        data(model),
        X_BR(s.X_RB.inverse()),
        ws(model, static_cast<int>(s.acceleration_constraints.size())) {
    for (size_t k = 0; k < s.acceleration_constraints.size(); ++k) {
      ws.alpha_To_B(s.acceleration_constraints[k].component, static_cast<Eigen::Index>(k)) = 1.0;
    }
  }
  runtime::AchdModel model;       // with gravity: kinematics and the command
  runtime::AchdModel task_model;  // the ACHD solve's (no gravity when compensated)
  runtime::AchdData data;
  runtime::Pose X_BR;  // the chain's root in the solver's root (mount inverse)
  runtime::steps::ArmWorkspace ws;
};

struct Interpreter::Base {
  explicit Base(const BaseSolver& s) : model(kelo_config(s)), data(model) {}
  runtime::KeloModel model;
  runtime::KeloData data;
};

Interpreter::Interpreter(Program program) : program_(std::move(program)) {
  verify(program_);
  s_.scalars.assign(static_cast<size_t>(program_.count(DataType::Scalar)), 0.0);
  s_.vec3s.assign(static_cast<size_t>(program_.count(DataType::Vector3)), Vec3::Zero());
  s_.poses.assign(static_cast<size_t>(program_.count(DataType::Pose)), Pose{});
  s_.twists.assign(static_cast<size_t>(program_.count(DataType::Twist)), Vec6::Zero());
  s_.wrenches.assign(static_cast<size_t>(program_.count(DataType::Wrench)), Vec6::Zero());
  s_.flags.assign(static_cast<size_t>(program_.count(DataType::Flag)), 0);
  s_.events.assign(static_cast<size_t>(program_.count(DataType::Event)), 0);
  s_.inertias.assign(static_cast<size_t>(program_.count(DataType::Inertia)), {});
  for (const Data& d : program_.data) {
    if (d.value.empty()) continue;
    const auto s = static_cast<size_t>(d.slot);
    switch (d.type) {
      case DataType::Scalar:
        s_.scalars[s] = d.value[0];
        break;
      case DataType::Vector3:
        s_.vec3s[s] = Vec3(d.value[0], d.value[1], d.value[2]);
        break;
      case DataType::Pose:
        s_.poses[s] = constant_pose(d.value);
        break;
      case DataType::Twist:
      case DataType::Wrench: {
        Vec6 v;
        for (int i = 0; i < 6; ++i) v[i] = d.value[static_cast<size_t>(i)];
        (d.type == DataType::Twist ? s_.twists : s_.wrenches)[s] = v;
        break;
      }
      case DataType::Flag:
        s_.flags[s] = d.value[0] != 0.0;
        break;
      case DataType::Event:
        break;
      case DataType::Inertia:
        s_.inertias[s] =
            runtime::rigid_body_inertia(std::span<const double, 10>(d.value.data(), 10));
        break;
    }
  }
  monitor_states_.resize(
      static_cast<size_t>(program_.states[static_cast<int>(StateKind::Monitor)]));
  motion_states_.assign(static_cast<size_t>(program_.states[static_cast<int>(StateKind::Motion)]),
                        runtime::steps::MotionState::Idle);
  operator_slot_offset_.assign(program_.steps.size(), 0);
  for (size_t i = 0; i < program_.steps.size(); ++i) {
    const Step& st = program_.steps[i];
    if (st.kind != StepKind::Operator) continue;
    operator_slot_offset_[i] = operator_slots_.size();
    for (int d : st.in) operator_slots_.push_back(static_cast<int>(slot(d)));
  }
  evaluators_.resize(program_.steps.size());
  controllers_.resize(program_.steps.size());
  for (size_t i = 0; i < program_.steps.size(); ++i) {
    const Step& st = program_.steps[i];
    if (st.kind == StepKind::Evaluate) {
      evaluators_[i] =
          std::make_unique<runtime::ConstraintEvaluator>(st.constraint, st.name.c_str());
    } else if (st.kind == StepKind::Controller) {
      controllers_[i] = controller_kinds()[static_cast<size_t>(st.controller)].instantiate(
          st.parameters, st.name.c_str());
    }
  }
  for (const ArmSolver& a : program_.arms) arms_.push_back(std::make_unique<Arm>(a));
  if (program_.base) base_ = std::make_unique<Base>(*program_.base);
  for (const LogColumn& c : program_.log) {
    column_names_.push_back(c.name);
    column_units_.push_back(c.unit);
  }
  for (size_t i = 0; i < column_names_.size(); ++i) {
    columns_.push_back({column_names_[i].c_str(), column_units_[i].c_str(), program_.log[i].kind});
  }
  arm_joints_ = ir::arm_joints(program_);
}

Interpreter::~Interpreter() = default;

void Interpreter::tick(const robot::MeasuredState& state, robot::Command& command) noexcept {
  robot::zero(command);
  command.tick = state.clock.tick;
  std::fill(s_.events.begin(), s_.events.end(), 0);
  for (size_t i = 0; i < program_.steps.size(); ++i) execute(program_.steps[i], i, state, command);
}

void Interpreter::execute(const Step& st, size_t index, const robot::MeasuredState& state,
                          robot::Command& command) noexcept {
  namespace rt = runtime;
  namespace steps = runtime::steps;
  const auto in = [&](size_t k) { return slot(st.in[k]); };
  const auto out = [&](size_t k) { return slot(st.out[k]); };
  switch (st.kind) {
    case StepKind::ReadClock:
      s_.scalars[out(0)] = state.clock.t;
      break;
    case StepKind::ArmKinematics: {
      const ArmSolver& solver = program_.arms[static_cast<size_t>(st.solver)];
      Arm& arm = *arms_[static_cast<size_t>(st.solver)];
      const robot::ArmMeasurement& m = state.arm[static_cast<size_t>(solver.port)];
      steps::arm_kinematics(arm.model, arm.data, arm.ws, m.q, m.qd);
      for (const ArmOutput& o : solver.outputs) {
        if (o.what == ArmOutput::What::SegmentPose) {
          s_.poses[slot(o.data)] = steps::segment_pose(arm.data, o.segment);
        } else if (o.what == ArmOutput::What::ChainRootPose) {
          s_.poses[slot(o.data)] = steps::segment_pose_in_chain_root(arm.data, arm.X_BR, o.segment);
        } else if (o.what == ArmOutput::What::JointPosition) {
          s_.scalars[slot(o.data)] = steps::joint_position(arm.ws, o.segment);
        } else if (o.what == ArmOutput::What::JointVelocity) {
          s_.scalars[slot(o.data)] = steps::joint_velocity(arm.ws, o.segment);
        } else if (o.what == ArmOutput::What::JointTorque) {
          s_.scalars[slot(o.data)] = steps::joint_torque(arm.ws, m.tau, o.segment);
        } else if (o.what == ArmOutput::What::EstimatedWrench) {
          s_.wrenches[slot(o.data)] =
              steps::estimated_wrench(arm.model, arm.data, arm.ws, m.tau, o.segment);
        } else if (o.what == ArmOutput::What::TipPose) {
          s_.poses[slot(o.data)] = steps::tip_pose(arm.model, arm.data);
        } else if (o.what == ArmOutput::What::TipPoseInChainRoot) {
          s_.poses[slot(o.data)] = steps::tip_pose_in_chain_root(arm.model, arm.data, arm.X_BR);
        } else if (o.what == ArmOutput::What::TipTwist) {
          s_.twists[slot(o.data)] = steps::tip_twist(arm.model, arm.data);
        } else {
          s_.twists[slot(o.data)] = steps::segment_twist(arm.data, o.segment);
        }
      }
      break;
    }
    case StepKind::ViewRead: {
      const Data& super = program_.data[static_cast<size_t>(st.in[0])];
      const int v = st.views[0];
      if (super.type == DataType::Pose) {
        s_.scalars[out(0)] = steps::view_pose(s_.poses[in(0)], v);
      } else {
        s_.scalars[out(0)] = steps::view_vec6(
            super.type == DataType::Twist ? s_.twists[in(0)] : s_.wrenches[in(0)], v);
      }
      break;
    }
    case StepKind::ViewWrite: {
      Vec6& target = program_.data[static_cast<size_t>(st.out[0])].type == DataType::Twist
                         ? s_.twists[out(0)]
                         : s_.wrenches[out(0)];
      target.setZero();
      for (size_t k = 0; k < st.in.size(); ++k) target[st.views[k]] = s_.scalars[in(k)];
      break;
    }
    case StepKind::Operator: {
      const OperatorKind& k = operator_kinds()[static_cast<size_t>(st.op)];
      k.interpret(s_, operator_slots_.data() + operator_slot_offset_[index],
                  static_cast<int>(out(0)));
      break;
    }
    case StepKind::Evaluate: {
      bool satisfied = false;
      const bool active = st.in.size() < 2 || s_.flags[in(1)] != 0;
      steps::evaluate(*evaluators_[index], s_.scalars[in(0)], active, satisfied,
                      s_.scalars[out(1)]);
      s_.flags[out(0)] = satisfied;
      break;
    }
    case StepKind::LevelMonitor:
    case StepKind::EdgeMonitor: {
      // Gated by the running flag after the error, if a handler lists it.
      const bool running = st.in.size() < 2 || s_.flags[in(1)] != 0;
      runtime::MonitorState& m = monitor_states_[static_cast<size_t>(st.state)];
      if (st.kind == StepKind::LevelMonitor)
        s_.flags[out(0)] =
            steps::level_monitor(m, s_.scalars[in(0)], st.constraint.tolerance, running);
      else
        s_.events[out(0)] = static_cast<char>(
            steps::edge_monitor(m, s_.scalars[in(0)], st.constraint.tolerance, st.edges, running));
      break;
    }
    case StepKind::GuardedMotion: {
      std::array<bool, kMaxGuards> when{}, whiles{}, until{};
      const auto n_when = static_cast<size_t>(st.n_when);
      const auto n_while = static_cast<size_t>(st.n_while);
      const size_t n_until = st.in.size() - n_when - n_while;
      for (size_t k = 0; k < n_when; ++k) when[k] = s_.flags[in(k)] != 0;
      for (size_t k = 0; k < n_while; ++k) whiles[k] = s_.flags[in(n_when + k)] != 0;
      for (size_t k = 0; k < n_until; ++k) until[k] = s_.flags[in(n_when + n_while + k)] != 0;
      std::uint8_t ended = 0;
      s_.flags[out(0)] = steps::guarded_motion(motion_states_[static_cast<size_t>(st.state)],
                                               std::span<const bool>(when.data(), n_when),
                                               std::span<const bool>(whiles.data(), n_while),
                                               std::span<const bool>(until.data(), n_until), ended);
      s_.events[out(1)] = static_cast<char>(ended);
      break;
    }
    case StepKind::AnyOf: {
      bool any = false;
      for (size_t k = 0; k < st.in.size(); ++k) any = any || s_.flags[in(k)] != 0;
      s_.flags[out(0)] = any;
      break;
    }
    case StepKind::Controller: {
      // The kind's kernel on its signals (at most kMaxControllerSignals), gated by
      // the running flag after them, if any.
      const size_t n = controller_kinds()[static_cast<size_t>(st.controller)].in.size();
      std::array<double, kMaxControllerSignals> signals{};
      for (size_t k = 0; k < n; ++k) signals[k] = s_.scalars[in(k)];
      const bool active = st.in.size() <= n || s_.flags[in(n)] != 0;
      s_.scalars[out(0)] = controllers_[index]->step(signals.data(), state.clock.dt, active);
      break;
    }
    case StepKind::ArmSolve: {
      const ArmSolver& solver = program_.arms[static_cast<size_t>(st.solver)];
      Arm& arm = *arms_[static_cast<size_t>(st.solver)];
      bool driven = st.in.size() == st.drivers();  // no gates: always
      for (size_t k = st.drivers(); k < st.in.size(); ++k) driven = driven || s_.flags[in(k)] != 0;
      if (!driven) {
        steps::arm_hold(arm.model, arm.data, arm.ws, idle_time_constant(solver),
                        command.arm_tau[static_cast<size_t>(solver.port)]);
        s_.flags[out(0)] = false;
        break;
      }
      arm.ws.F_ext.fill(Vec6::Zero());
      for (const CartesianForce& f : solver.cartesian_forces) {
        arm.ws.F_ext[static_cast<size_t>(f.segment)] +=
            f.at_tip ? steps::tip_wrench_at_segment_origin(arm.model, arm.data,
                                                           s_.wrenches[slot(f.wrench)])
                     : s_.wrenches[slot(f.wrench)];
      }
      arm.ws.tau_ff.setZero();
      for (const JointForce& f : solver.joint_forces)
        arm.ws.tau_ff[f.joint] += s_.scalars[slot(f.force)];
      for (size_t k = 0; k < solver.acceleration_constraints.size(); ++k) {
        const AccelerationConstraint& ac = solver.acceleration_constraints[k];
        arm.ws.beta[static_cast<Eigen::Index>(k)] = s_.scalars[slot(ac.energy)];
        if (ac.engaged_by >= 0)
          arm.ws.engaged[k] = steps::one_sided_engaged(
              arm.ws.engaged[k], s_.scalars[slot(ac.engaged_by)], ac.tolerance);
      }
      steps::arm_solve(arm.task_model, arm.model, arm.data, arm.ws,
                       command.arm_tau[static_cast<size_t>(solver.port)]);
      s_.flags[out(0)] = arm.ws.status == runtime::Status::ConstraintsDegraded;
      break;
    }
    case StepKind::BaseForceDistribution: {
      bool driven = st.in.size() == st.drivers();  // no gates: always
      for (size_t k = st.drivers(); k < st.in.size(); ++k) driven = driven || s_.flags[in(k)] != 0;
      if (!driven) {
        steps::base_hold(base_->model, base_->data, state.pivot_q, state.wheel_qd,
                         command.wheel_tau);
      } else {
        steps::base_force_distribution(base_->model, base_->data, state.pivot_q, s_.wrenches[in(0)],
                                       command.wheel_tau);
      }
      break;
    }
    case StepKind::BaseVelocityComposition:
      steps::base_velocity(base_->model, base_->data, state.pivot_q, state.wheel_qd,
                           s_.twists[out(0)]);
      break;
  }
}

double Interpreter::value(int data) const noexcept {
  const Data& d = program_.data[static_cast<size_t>(data)];
  const auto s = static_cast<size_t>(d.slot);
  switch (d.type) {
    case DataType::Scalar:
      return s_.scalars[s];
    case DataType::Flag:
      return s_.flags[s] ? 1.0 : 0.0;
    case DataType::Event:
      return static_cast<double>(static_cast<unsigned char>(s_.events[s]));
    default:
      return std::nan("");
  }
}

void Interpreter::log_values(std::span<double> out) const noexcept {
  for (size_t i = 0; i < out.size() && i < program_.log.size(); ++i) {
    const LogColumn& c = program_.log[i];
    const Data& d = program_.data[static_cast<size_t>(c.data)];
    if (c.component >= 0 && (d.type == DataType::Twist || d.type == DataType::Wrench)) {
      out[i] = (d.type == DataType::Twist ? s_.twists
                                          : s_.wrenches)[static_cast<size_t>(d.slot)][c.component];
    } else {
      out[i] = value(c.data);
    }
  }
}

}  // namespace mospec::ir
