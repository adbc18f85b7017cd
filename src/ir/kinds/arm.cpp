// arm-kinematics and arm-solve: an arm solver's forward kinematics into its
// outputs (ArmOutput), and its ACHD solve of the drivers into the joint
// torques (or, with no motion that drives it running, its hold).
#include "ir/kinds/kinds.hpp"

namespace mospec::ir {

Machine::Arm::Arm(const ArmSolver& s)
    : model(achd_model(s, true)),
      task_model(achd_model(s, false)),
      data(model),
      X_BR(s.X_RB.inverse()),
      ws(model, static_cast<int>(s.acceleration_constraints.size())) {
  for (size_t k = 0; k < s.acceleration_constraints.size(); ++k) {
    ws.alpha_To_B(s.acceleration_constraints[k].component, static_cast<Eigen::Index>(k)) = 1.0;
  }
}

namespace kinds {

namespace {

using What = ArmOutput::What;

void write_output(Machine& m, Machine::Arm& arm, const robot::ArmMeasurement& meas,
                  const ArmOutput& o) noexcept {
  namespace steps = runtime::steps;
  const size_t d = m.slot(o.data);
  switch (o.what) {
    case What::SegmentPose:
      m.s.poses[d] = steps::segment_pose(arm.data, o.segment);
      break;
    case What::ChainRootPose:
      m.s.poses[d] = steps::segment_pose_in_chain_root(arm.data, arm.X_BR, o.segment);
      break;
    case What::JointPosition:
      m.s.scalars[d] = steps::joint_position(arm.ws, o.segment);
      break;
    case What::JointVelocity:
      m.s.scalars[d] = steps::joint_velocity(arm.ws, o.segment);
      break;
    case What::JointTorque:
      m.s.scalars[d] = steps::joint_torque(arm.ws, meas.tau, o.segment);
      break;
    case What::EstimatedWrench:
      m.s.wrenches[d] = steps::estimated_wrench(arm.model, arm.data, arm.ws, meas.tau, o.segment);
      break;
    case What::TipPose:
      m.s.poses[d] = steps::tip_pose(arm.model, arm.data);
      break;
    case What::TipPoseInChainRoot:
      m.s.poses[d] = steps::tip_pose_in_chain_root(arm.model, arm.data, arm.X_BR);
      break;
    case What::TipTwist:
      m.s.twists[d] = steps::tip_twist(arm.model, arm.data);
      break;
    case What::SegmentTwist:
      m.s.twists[d] = steps::segment_twist(arm.data, o.segment);
      break;
  }
}

// The runtime call that computes one output, as generated C++.
std::string output_call(const ArmNames& n, int port, const ArmOutput& o) {
  const std::string segment = std::to_string(o.segment);
  const std::string tau = "state.arm[" + std::to_string(port) + "].tau";
  switch (o.what) {
    case What::SegmentPose:
      return "rt::steps::segment_pose(d." + n.arm + ", " + segment + ")";
    case What::ChainRootPose:
      return "rt::steps::segment_pose_in_chain_root(d." + n.arm + ", m." + n.X_BR + ", " + segment +
             ")";
    case What::JointPosition:
      return "rt::steps::joint_position(d." + n.ws + ", " + segment + ")";
    case What::JointVelocity:
      return "rt::steps::joint_velocity(d." + n.ws + ", " + segment + ")";
    case What::JointTorque:
      return "rt::steps::joint_torque(d." + n.ws + ", " + tau + ", " + segment + ")";
    case What::EstimatedWrench:
      return "rt::steps::estimated_wrench(m." + n.arm + ", d." + n.arm + ", d." + n.ws + ", " +
             tau + ", " + segment + ")";
    // The tip frame's, read with the physical model (its X_NT is the tool).
    case What::TipPose:
      return "rt::steps::tip_pose(m." + n.arm + ", d." + n.arm + ")";
    case What::TipPoseInChainRoot:
      return "rt::steps::tip_pose_in_chain_root(m." + n.arm + ", d." + n.arm + ", m." + n.X_BR +
             ")";
    case What::TipTwist:
      return "rt::steps::tip_twist(m." + n.arm + ", d." + n.arm + ")";
    case What::SegmentTwist:
      break;
  }
  return "rt::steps::segment_twist(d." + n.arm + ", " + segment + ")";
}

void put_arm(const EmitContext& ctx, const Step& st, mustache::Data& s) {
  const ArmNames& n = ctx.arm(st.solver);
  put(s, "arm", n.arm);
  put(s, "task", n.task);
  put(s, "workspace", n.ws);
  put(s, "port", std::to_string(ctx.program().arms[static_cast<size_t>(st.solver)].port));
}

// Each driver kind's entries of the solve's section.
mustache::Data forces(const EmitContext& ctx, const ArmSolver& a, const ArmNames& n) {
  mustache::Data forces = list();
  for (const CartesianForce& f : a.cartesian_forces) {
    mustache::Data e;
    put(e, "workspace", n.ws);
    put(e, "segment", std::to_string(f.segment));
    // A force on the tool: its wrench at To moved to the segment's origin.
    put(e, "source",
        f.at_tip ? "rt::steps::tip_wrench_at_segment_origin(m." + n.arm + ", d." + n.arm + ", " +
                       ctx.ref(f.wrench) + ")"
                 : ctx.ref(f.wrench));
    put(e, "iri", ctx.comment(f.iri));
    append(forces, std::move(e));
  }
  return forces;
}

mustache::Data joint_forces(const EmitContext& ctx, const ArmSolver& a, const ArmNames& n) {
  mustache::Data joint_forces = list();
  for (const JointForce& f : a.joint_forces) {
    mustache::Data e;
    put(e, "workspace", n.ws);
    put(e, "joint", std::to_string(f.joint));
    put(e, "source", ctx.ref(f.force));
    put(e, "iri", ctx.comment(f.iri));
    append(joint_forces, std::move(e));
  }
  return joint_forces;
}

mustache::Data betas(const EmitContext& ctx, const ArmSolver& a, const ArmNames& n) {
  mustache::Data betas = list();
  for (size_t c = 0; c < a.acceleration_constraints.size(); ++c) {
    const AccelerationConstraint& ac = a.acceleration_constraints[c];
    mustache::Data e;
    put(e, "workspace", n.ws);
    put(e, "column", std::to_string(c));
    put(e, "source", ctx.ref(ac.energy));
    put(e, "iri", ctx.comment(ac.iri));
    if (ac.engaged_by >= 0) {
      put(e, "engaged_by", ctx.ref(ac.engaged_by));
      put(e, "engaged_tolerance", ctx.number(ac.tolerance));
    }
    append(betas, std::move(e));
  }
  return betas;
}

}  // namespace

void interpret_arm_kinematics(Machine& m, const Step& st, size_t, const robot::MeasuredState& state,
                              robot::Command&) noexcept {
  const ArmSolver& solver = m.program.arms[static_cast<size_t>(st.solver)];
  Machine::Arm& arm = *m.arms[static_cast<size_t>(st.solver)];
  const robot::ArmMeasurement& meas = state.arm[static_cast<size_t>(solver.port)];
  runtime::steps::arm_kinematics(arm.model, arm.data, arm.ws, meas.q, meas.qd);
  for (const ArmOutput& o : solver.outputs) write_output(m, arm, meas, o);
}

void emit_arm_kinematics(const EmitContext& ctx, const Step& st, size_t, mustache::Data& s) {
  put_arm(ctx, st, s);
  const ArmSolver& a = ctx.program().arms[static_cast<size_t>(st.solver)];
  mustache::Data outputs = list();
  for (const ArmOutput& o : a.outputs) {
    mustache::Data e;
    put(e, "target", ctx.ref(o.data));
    put(e, "call", output_call(ctx.arm(st.solver), a.port, o));
    append(outputs, std::move(e));
  }
  put(s, "outputs", std::move(outputs));
}

// in[0, drivers) are the drivers' data; the rest gate the solve: the running
// flags of the motions that drive this arm (none running: hold).
void interpret_arm_solve(Machine& m, const Step& st, size_t, const robot::MeasuredState&,
                         robot::Command& command) noexcept {
  namespace steps = runtime::steps;
  const ArmSolver& solver = m.program.arms[static_cast<size_t>(st.solver)];
  Machine::Arm& arm = *m.arms[static_cast<size_t>(st.solver)];
  auto& tau = command.arm_tau[static_cast<size_t>(solver.port)];
  bool driven = st.in.size() == st.drivers();  // no gates: always
  for (size_t k = st.drivers(); k < st.in.size(); ++k)
    driven = driven || m.s.flags[m.slot(st.in[k])] != 0;
  if (!driven) {
    steps::arm_hold(arm.model, arm.data, arm.ws, idle_time_constant(solver), tau);
    m.s.flags[m.slot(st.out[0])] = false;
    return;
  }
  arm.ws.F_ext.fill(runtime::Vec6::Zero());
  for (const CartesianForce& f : solver.cartesian_forces) {
    const runtime::Vec6& w = m.s.wrenches[m.slot(f.wrench)];
    arm.ws.F_ext[static_cast<size_t>(f.segment)] +=
        f.at_tip ? steps::tip_wrench_at_segment_origin(arm.model, arm.data, w) : w;
  }
  arm.ws.tau_ff.setZero();
  for (const JointForce& f : solver.joint_forces)
    arm.ws.tau_ff[f.joint] += m.s.scalars[m.slot(f.force)];
  for (size_t k = 0; k < solver.acceleration_constraints.size(); ++k) {
    const AccelerationConstraint& ac = solver.acceleration_constraints[k];
    arm.ws.beta[static_cast<Eigen::Index>(k)] = m.s.scalars[m.slot(ac.energy)];
    if (ac.engaged_by >= 0)
      arm.ws.engaged[k] = steps::one_sided_engaged(
          arm.ws.engaged[k], m.s.scalars[m.slot(ac.engaged_by)], ac.tolerance);
  }
  steps::arm_solve(arm.task_model, arm.model, arm.data, arm.ws, tau);
  m.s.flags[m.slot(st.out[0])] = arm.ws.status == runtime::Status::ConstraintsDegraded;
}

void emit_arm_solve(const EmitContext& ctx, const Step& st, size_t, mustache::Data& s) {
  put_arm(ctx, st, s);
  const ArmSolver& a = ctx.program().arms[static_cast<size_t>(st.solver)];
  const ArmNames& n = ctx.arm(st.solver);
  put(s, "degraded", ctx.out(st, 0));
  const std::string gates = join_inputs(ctx, st, st.drivers(), st.in.size(), " || ");
  put(s, "gated", !gates.empty());
  put(s, "gates", gates);
  put(s, "idle_time_constant",
      a.idle == ArmSolver::Idle::BrakeAndHold ? ctx.number(a.idle_time_constant)
                                              : std::string("rt::steps::kFloatTimeConstant"));
  put(s, "indent", gates.empty() ? "  " : "    ");
  put(s, "forces", forces(ctx, a, n));
  put(s, "joint_forces", joint_forces(ctx, a, n));
  put(s, "betas", betas(ctx, a, n));
}

Signature signature_arm_kinematics(const Step&, const Program&) {
  return {{}, {}, true};
}

void verify_arm_solver(const Step& st, const Program& p, Findings& f) {
  if (st.solver < 0 || static_cast<size_t>(st.solver) >= p.arms.size())
    f.step(st, "names arm solver " + std::to_string(st.solver) + "; the program has " +
                   std::to_string(p.arms.size()));
}

Signature signature_arm_solve(const Step&, const Program&) {
  Signature s{{}, {DataType::Flag}, true};
  s.variadic_out = false;
  return s;
}

void verify_arm_solve(const Step& st, const Program& p, Findings& f) {
  verify_arm_solver(st, p, f);
  verify_gates(st, p, f);
}

void print_drivers(const Step& st, StepJson& j) {
  j.e["drivers"] = st.drivers();
}

void log_arm_solve(const Program& p, const Step& st, std::vector<LogColumn>& log) {
  log.push_back(step_column(p, st, ".degraded", st.out[0], robot::LogColumnKind::Flag));
}

}  // namespace kinds
}  // namespace mospec::ir
