// Hand-built IR programs for the code generator's tests: the same functions
// give the same Program every time, so the fixture writer (which generates and
// builds the project) and the tests (which run the interpreter beside the built
// library) see one program.
//
//   small_program()  no arm: a clock, constant poses and vectors, views, every
//                    operator kind, equality/less-than evaluations, a PID, level
//                    and edge monitors, a guarded motion, the KELO base (velocity
//                    composition, gated force distribution).
//   arm_program()    a 7-dof Kinova Gen3 arm (robots/kinova-gen3.jsonld):
//                    kinematics outputs, a tip acceleration constraint driven
//                    by a PID, a Cartesian force and a joint force, gated by a
//                    motion (the arm holds once it ends).
//   empty_program()  no data, no steps, no log.
//   hostile_program() names and IRIs no C++ name or comment may hold as they
//                    are: a trigraph, a lone U+202E, C macros (errno, assert,
//                    NULL, EOF, stdin, INFINITY, unix, linux), keywords,
//                    reserved spellings, "*/", line breaks, a trailing
//                    backslash; and two arm solvers, "r" and "r_task", whose
//                    members collided under the old naming (arm_r_task).
#pragma once

#include <algorithm>
#include <cmath>
#include <string>

#include "app/app.hpp"
#include "description/chain_rdf.hpp"
#include "ir/controllers.hpp"
#include "ir/ir.hpp"
#include "ir/operators.hpp"
#include "kelo_base.hpp"
#include "robot/interface.hpp"

namespace mospec::codegen::testing {

class ProgramBuilder {
 public:
  explicit ProgramBuilder(SourceFiles& files) {
    file_ = files.add("tests/codegen/programs.hpp");
    p.app = "https://mospec.example/tests/codegen/app";
  }

  int datum(const std::string& name, ir::DataType type, std::vector<double> value = {},
            const std::string& unit = "") {
    ir::Data d;
    d.iri = "https://mospec.example/tests/codegen/" + name;
    d.name = name;
    d.type = type;
    d.slot = p.slots[static_cast<std::size_t>(type)]++;
    d.unit = unit;
    d.value = std::move(value);
    d.where = {file_, static_cast<uint32_t>(p.data.size() + 1), 3};
    p.data.push_back(std::move(d));
    return static_cast<int>(p.data.size() - 1);
  }

  ir::Step& step(ir::StepKind kind, const std::string& name, std::vector<int> in,
                 std::vector<int> out) {
    ir::Step s;
    s.kind = kind;
    s.name = name;
    s.iri = "https://mospec.example/tests/codegen/" + name;
    s.in = std::move(in);
    s.out = std::move(out);
    s.where = {file_, static_cast<uint32_t>(100 + p.steps.size()), 5};
    p.steps.push_back(std::move(s));
    return p.steps.back();
  }

  // An operator step, by the registry's name of its kind ("compose-pose").
  ir::Step& op(std::string_view kind, const std::string& name, std::vector<int> in,
               std::vector<int> out) {
    ir::Step& s = step(ir::StepKind::Operator, name, std::move(in), std::move(out));
    s.op = ir::operator_index(kind);
    if (s.op < 0) throw std::logic_error("no operator kind '" + std::string(kind) + "'");
    return s;
  }

  int state(ir::StateKind kind) { return p.states[static_cast<std::size_t>(kind)]++; }

  // A controller step, by the registry's name of its kind ("pid"): its
  // parameters are the kind's defaults, then `values` by Spec field name; a
  // stateful kind gets the next state slot of its kind.
  ir::Step& controller(std::string_view kind, const std::string& name, std::vector<int> in,
                       std::vector<int> out,
                       const std::vector<std::pair<std::string, double>>& values = {}) {
    const int k = ir::controller_index(kind);
    if (k < 0) throw std::logic_error("no controller kind '" + std::string(kind) + "'");
    const ir::ControllerKind& ck = ir::controller_kinds()[static_cast<std::size_t>(k)];
    ir::Step& s = step(ir::StepKind::Controller, name, std::move(in), std::move(out));
    s.controller = k;
    s.parameters = ck.defaults();
    for (const auto& [member, v] : values) {
      const int f = ck.parameter(member);
      if (f < 0)
        throw std::logic_error("controller kind '" + std::string(kind) + "' has no " + member);
      s.parameters[static_cast<std::size_t>(f)] = v;
    }
    if (ck.has_state()) {
      p.controller_states.resize(ir::controller_kinds().size());
      s.state = p.controller_states[static_cast<std::size_t>(k)]++;
    }
    return s;
  }

  // A monitor's flag (level_flag) and every event are latched, as lowering does.
  void log(const std::string& name, int data, const std::string& unit = "",
           bool level_flag = false) {
    const bool event = p.data[static_cast<std::size_t>(data)].type == ir::DataType::Event;
    p.log.push_back({name, unit, data, -1,
                     event        ? robot::LogColumnKind::Event
                     : level_flag ? robot::LogColumnKind::Flag
                                  : robot::LogColumnKind::Value});
  }

  ir::Program p;

 private:
  uint32_t file_ = 0;
};

// A rotation about z by a (row-major) and a position: a constant pose's value.
inline std::vector<double> pose_value(double a, double x, double y, double z) {
  const double c = std::cos(a), s = std::sin(a);
  return {c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0, x, y, z};
}

inline ir::Program small_program(SourceFiles& files) {
  using T = ir::DataType;
  using K = ir::StepKind;
  ProgramBuilder b(files);
  const int time = b.datum("time", T::Scalar, {}, "SEC");
  const int X_WA = b.datum("X_WA", T::Pose, pose_value(0.3, 0.1, 0.2, 0.3));
  const int X_AB = b.datum("X_AB", T::Pose, pose_value(-0.7, 0.4, -0.1, 0.25));
  const int p_BoC = b.datum("p_BoC_W", T::Vector3, {0.0, 0.05, -0.02}, "M");
  const int x_axis = b.datum("x_axis", T::Vector3, {1.0, 0.0, 0.0});
  const int z_axis = b.datum("z_axis", T::Vector3, {0.0, 0.0, 1.0});
  const int F_bias = b.datum("F_bias", T::Wrench, {0.0, 0.0, 0.5, 1.0, -2.0, 0.0});
  const int V_A = b.datum("V_A", T::Twist, {0.1, -0.2, 0.3, 0.01, 0.02, -0.03});

  b.step(K::ReadClock, "clock", {}, {time});
  const int X_WB = b.datum("X_WB", T::Pose);
  b.op("compose-pose", "compose", {X_WA, X_AB}, {X_WB});
  const int height = b.datum("height", T::Scalar, {}, "M");
  b.step(K::ViewRead, "view_height", {X_WB}, {height}).views = {5};
  const int yaw = b.datum("yaw", T::Scalar, {}, "RAD");
  b.step(K::ViewRead, "view_yaw", {X_WB}, {yaw}).views = {2};
  const int distance = b.datum("distance", T::Scalar, {}, "M");
  b.op("pose-to-linear-distance", "distance_op", {X_WB}, {distance});
  const int d_WB = b.datum("d_WB", T::Vector3);
  b.op("pose-to-direction", "direction_op", {X_WB}, {d_WB});
  const int angle = b.datum("angle", T::Scalar, {}, "RAD");
  b.op("planar-angle-from-directions", "angle_op", {d_WB, x_axis, z_axis}, {angle});
  const int angle_inv = b.datum("angle_inv", T::Scalar, {}, "RAD");
  b.op("invert-angle", "invert_op", {angle}, {angle_inv});
  const int d_W = b.datum("d_W", T::Vector3);
  b.op("rotate-direction-to-proximal", "rotate_direction", {X_WA, d_WB}, {d_W});
  const int V_W = b.datum("V_W", T::Twist);
  b.op("rotate-twist-to-proximal", "rotate_twist", {X_WA, V_A}, {V_W});
  const int v_z = b.datum("v_z", T::Scalar, {}, "M-PER-SEC");
  b.step(K::ViewRead, "view_vz", {V_W}, {v_z}).views = {5};

  // height == 0.5 (tolerance 1 cm): the PID's error.
  const int height_ok = b.datum("height_ok", T::Flag);
  const int height_err = b.datum("height_err", T::Scalar, {}, "M");
  ir::Step& eq = b.step(K::Evaluate, "cstr_height", {height}, {height_ok, height_err});
  eq.constraint = {runtime::ConstraintKind::Equality, 0.5, 0.0, 0.0, 0.0, 0.01};
  eq.has_error_output = true;
  // time >= 0.05 s: the motion's until guard (level) and an event when it starts to hold.
  const int late = b.datum("late", T::Flag);
  const int late_err = b.datum("late_err", T::Scalar, {}, "SEC");
  ir::Step& gt = b.step(K::Evaluate, "cstr_time", {time}, {late, late_err});
  gt.constraint = {runtime::ConstraintKind::GreaterThan, 0.0, 0.05, 0.0, 0.0, 0.0};
  gt.has_error_output = true;
  const int timeout = b.datum("timeout", T::Flag);
  ir::Step& lm = b.step(K::LevelMonitor, "mon_timeout", {late_err}, {timeout});
  lm.constraint.tolerance = 0.0;
  lm.state = b.state(ir::StateKind::Monitor);
  const int timeout_event = b.datum("timeout_event", T::Event);
  ir::Step& em = b.step(K::EdgeMonitor, "mon_timeout_edge", {late_err}, {timeout_event});
  em.constraint.tolerance = 0.0;
  em.edges = runtime::Edges::Both;
  em.state = b.state(ir::StateKind::Monitor);
  // height == 0.5 within 1 cm stops holding: a falling edge.
  const int height_lost = b.datum("height_lost", T::Event);
  ir::Step& fm = b.step(K::EdgeMonitor, "mon_height_fall", {height_err}, {height_lost});
  fm.constraint.tolerance = 0.01;
  fm.edges = runtime::Edges::Falling;
  fm.state = b.state(ir::StateKind::Monitor);
  // time <= 0.03 s: the motion's checked per-condition.
  const int early = b.datum("early", T::Flag);
  const int early_err = b.datum("early_err", T::Scalar, {}, "SEC");
  ir::Step& lt = b.step(K::Evaluate, "cstr_early", {time}, {early, early_err});
  lt.constraint = {runtime::ConstraintKind::LessThan, 0.0, 0.03, 0.0, 0.0, 0.0};
  lt.has_error_output = true;
  const int approach = b.datum("approach", T::Flag);
  const int approach_ended = b.datum("approach_ended", T::Event);
  ir::Step& gm = b.step(K::GuardedMotion, "motion_approach", {early, height_ok, timeout},
                        {approach, approach_ended});
  gm.n_when = 0;   // starts at once
  gm.n_while = 1;  // early is checked; height_ok is a second until guard
  gm.state = b.state(ir::StateKind::Motion);
  const int force = b.datum("force", T::Scalar, {}, "N");
  b.controller("pid", "pid_height", {height_err, approach}, {force},
               {{"kp", 200.0},
                {"ki", 15.0},
                {"kd", 0.5},
                {"decay_rate", 0.99},
                {"output_min", -50.0},
                {"output_max", 50.0}});
  // A contact force: an assignment gated by the motion.
  const int push_ok = b.datum("push_ok", T::Flag);
  const int push = b.datum("push", T::Scalar, {}, "N");
  const int push_ref = b.datum("push_ref", T::Scalar, {}, "N");
  b.step(K::ReadClock, "clock_again", {}, {push_ref});  // a second reader of the clock
  ir::Step& as = b.step(K::Evaluate, "cstr_push", {push_ref, approach}, {push_ok, push});
  as.constraint = {runtime::ConstraintKind::Assignment, 20.0, 0.0, 0.0, 0.0, 0.0};

  const int F_force = b.datum("F_force", T::Wrench);
  b.op("wrench-from-position-direction-and-magnitude", "wrench_op", {p_BoC, d_W, force}, {F_force});
  const int F_push = b.datum("F_push", T::Wrench);
  b.step(K::ViewWrite, "view_push", {push, force}, {F_push}).views = {5, 3};
  const int F_sum = b.datum("F_sum", T::Wrench);
  b.op("add-wrench", "add_op", {F_force, F_push}, {F_sum});
  const int F_sum2 = b.datum("F_sum2", T::Wrench);
  b.op("add-wrench", "add_bias", {F_sum, F_bias}, {F_sum2});
  const int F_rot = b.datum("F_rot", T::Wrench);
  b.op("rotate-wrench-to-proximal", "rotate_wrench", {X_WA, F_sum2}, {F_rot});
  const int F_P = b.datum("F_P", T::Wrench);
  b.op("transform-wrench-to-proximal", "transform_wrench", {X_WA, F_rot}, {F_P});
  const int f_z = b.datum("f_z", T::Scalar, {}, "N");
  b.step(K::ViewRead, "view_fz", {F_P}, {f_z}).views = {5};

  ir::BaseSolver base;
  base.iri = "https://mospec.example/tests/codegen/base";
  base.name = "kelo";
  base.configuration = std::string(vocab::robots::kelo_base);
  base.config = ::mospec::testing::paper_base();
  base.wrench = F_P;
  const int V_P = b.datum("V_P", T::Twist);
  base.twist = V_P;
  b.p.base = base;
  b.step(K::BaseVelocityComposition, "base_velocity", {}, {V_P});
  // The distribution runs while `approach` runs; otherwise the base holds.
  b.step(K::BaseForceDistribution, "base_distribution", {F_P, approach}, {}).n_drivers = 1;

  for (int d : {time, height, yaw, distance, angle, angle_inv, v_z, height_err, late_err, force,
                push, f_z}) {
    b.log(b.p.data[static_cast<std::size_t>(d)].name, d,
          b.p.data[static_cast<std::size_t>(d)].unit);
  }
  for (int d : {height_ok, late, timeout_event, height_lost, approach, approach_ended, push_ok}) {
    b.log(b.p.data[static_cast<std::size_t>(d)].name, d);
  }
  b.log("timeout", timeout, "", true);
  // Components of a wrench and a twist.
  b.p.log.push_back({"F_P.f_x", "N", F_P, 3});
  b.p.log.push_back({"F_P.m_z", "N-M", F_P, 2});
  b.p.log.push_back({"V_W.w_x", "RAD-PER-SEC", V_W, 0});
  b.p.log.push_back({"V_P.v_x", "M-PER-SEC", V_P, 3});
  b.p.log.push_back({"V_P.w_z", "RAD-PER-SEC", V_P, 2});
  return b.p;
}

// Nothing to compute: every array is empty, the log has no columns.
inline ir::Program empty_program(SourceFiles& files) {
  ProgramBuilder b(files);
  return b.p;
}

// robots/kinova-gen3.jsonld's chain, read through mospec's own metamodels.
inline runtime::Chain gen3_chain() {
  app::LoadOptions options;
  options.maps.emplace_back("https://comp-rob2b.github.io/metamodels/",
                            std::string(MOSPEC_SOURCE_DIR) + "/metamodels");
  const app::LoadedModel model =
      app::load({std::string(MOSPEC_SOURCE_DIR) + "/robots/kinova-gen3.jsonld"}, options);
  return description::chain_from_rdf(model.flattened(),
                                     "https://mospec.example/robots/kinova-gen3/chain");
}

inline ir::Program arm_program(SourceFiles& files) {
  using T = ir::DataType;
  using K = ir::StepKind;
  ProgramBuilder b(files);
  ir::ArmSolver arm;
  arm.iri = "https://mospec.example/tests/codegen/right-arm-solver";
  arm.name = "right_arm";
  arm.chain_iri = "https://mospec.example/robots/kinova-gen3/chain";
  arm.root_frame = "https://mospec.example/robots/kinova-gen3/frame-base_link";
  arm.port = robot::kRightArm;
  arm.chain = gen3_chain();
  arm.gravity = {0.0, 0.0, -9.81};
  // A mount: the solver's root R carries the chain's root B at X_RB.
  arm.mount_pose_iri = "https://mospec.example/tests/codegen/mount";
  const std::vector<double> mount = pose_value(0.5, 0.1, -0.2, 0.9);
  arm.X_RB.R << mount[0], mount[1], mount[2], mount[3], mount[4], mount[5], mount[6], mount[7],
      mount[8];
  arm.X_RB.p = runtime::Vec3(mount[9], mount[10], mount[11]);
  const int n = arm.chain.size();

  const int time = b.datum("time", T::Scalar, {}, "SEC");
  const int X_BE = b.datum("X_BE", T::Pose);
  const int V_BE = b.datum("V_BE", T::Twist);
  const int X_B3 = b.datum("X_B3", T::Pose);
  const int X_C3 = b.datum("X_C3", T::Pose);  // w.r.t. the chain's own root
  // Joint quantities (mospec/joints, issue #16): joint 3's position,
  // velocity and measured torque.
  const int q_3 = b.datum("q_3", T::Scalar, {}, "RAD");
  const int qd_3 = b.datum("qd_3", T::Scalar, {}, "RAD-PER-SEC");
  const int tau_m_3 = b.datum("tau_m_3", T::Scalar, {}, "N-M");
  const int F_est = b.datum("F_est", T::Wrench);  // estimated from the measured torques
  arm.outputs = {{ir::ArmOutput::What::SegmentPose, n - 1, X_BE},
                 {ir::ArmOutput::What::SegmentTwist, n - 1, V_BE},
                 {ir::ArmOutput::What::SegmentPose, 3, X_B3},
                 {ir::ArmOutput::What::ChainRootPose, 3, X_C3},
                 {ir::ArmOutput::What::JointPosition, 3, q_3},
                 {ir::ArmOutput::What::JointVelocity, 3, qd_3},
                 {ir::ArmOutput::What::JointTorque, 3, tau_m_3},
                 {ir::ArmOutput::What::EstimatedWrench, n - 1, F_est}};
  b.step(K::ReadClock, "clock", {}, {time});
  ir::Step& kin = b.step(K::ArmKinematics, "right_arm_kinematics", {},
                         {X_BE, V_BE, X_B3, X_C3, q_3, qd_3, tau_m_3, F_est});
  kin.solver = 0;
  const int height = b.datum("ee_height", T::Scalar, {}, "M");
  b.step(K::ViewRead, "view_height", {X_BE}, {height}).views = {5};
  const int elbow_x = b.datum("elbow_x", T::Scalar, {}, "M");
  b.step(K::ViewRead, "view_elbow_x", {X_C3}, {elbow_x}).views = {3};
  const int vz = b.datum("ee_vz", T::Scalar, {}, "M-PER-SEC");
  b.step(K::ViewRead, "view_vz", {V_BE}, {vz}).views = {5};
  const int ok = b.datum("height_ok", T::Flag);
  const int err = b.datum("height_err", T::Scalar, {}, "M");
  ir::Step& ev = b.step(K::Evaluate, "cstr_height", {height}, {ok, err});
  ev.constraint = {runtime::ConstraintKind::Bilateral, 0.0, 0.0, 0.55, 0.65, 0.001};
  ev.has_error_output = true;
  const int acc = b.datum("acc_z", T::Scalar, {}, "N-M2-PER-SEC2");
  b.controller("pid", "pid_height", {err}, {acc}, {{"kp", 40.0}, {"ki", 2.0}, {"kd", 0.0}});
  // A one-sided row (issue #15): a less-than bound on the height drives the
  // tip's linear x only while it is violated (the push below acts along x
  // until then).
  const int low_ok = b.datum("low_ok", T::Flag);
  const int low_err = b.datum("low_err", T::Scalar, {}, "M");
  ir::Step& lt = b.step(K::Evaluate, "cstr_low", {height}, {low_ok, low_err});
  lt.constraint = {runtime::ConstraintKind::LessThan, 0.0, 0.84, 0.0, 0.0, 0.0};
  lt.has_error_output = true;
  const int acc_x = b.datum("acc_x", T::Scalar, {}, "N-M2-PER-SEC2");
  b.controller("pid", "pid_low", {low_err}, {acc_x}, {{"kp", 10.0}, {"ki", 0.0}, {"kd", 1.0}});
  const int push = b.datum("push", T::Scalar, {}, "N");
  const int push_ok = b.datum("push_ok", T::Flag);
  const int push_ref = b.datum("push_ref", T::Scalar, {0.0}, "N");
  ir::Step& as = b.step(K::Evaluate, "cstr_push", {push_ref}, {push_ok, push});
  as.constraint = {runtime::ConstraintKind::Assignment, 5.0, 0.0, 0.0, 0.0, 0.0};
  const int F_E = b.datum("F_E", T::Wrench);
  b.step(K::ViewWrite, "view_push", {push}, {F_E}).views = {3};
  const int F_E_B = b.datum("F_E_B", T::Wrench);
  b.op("rotate-wrench-to-proximal", "rotate_push", {X_BE, F_E}, {F_E_B});
  const int tau_1 = b.datum("tau_1", T::Scalar, {0.25}, "N-M");

  // The arm is driven while a motion runs (until t >= 1 s), then holds.
  const int late = b.datum("late", T::Flag);
  const int late_err = b.datum("late_err", T::Scalar, {}, "SEC");
  ir::Step& gt = b.step(K::Evaluate, "cstr_time", {time}, {late, late_err});
  gt.constraint = {runtime::ConstraintKind::GreaterThan, 0.0, 1.0, 0.0, 0.0, 0.0};
  const int reach = b.datum("reach", T::Flag);
  const int reach_ended = b.datum("reach_ended", T::Event);
  ir::Step& gm = b.step(K::GuardedMotion, "motion_reach", {late}, {reach, reach_ended});
  gm.n_when = 0;
  gm.state = b.state(ir::StateKind::Motion);

  arm.acceleration_constraints = {
      {"https://mospec.example/tests/codegen/acc-z", 5, acc, 0},
      {"https://mospec.example/tests/codegen/acc-x", 3, acc_x, 0, low_err}};
  arm.cartesian_forces = {{"https://mospec.example/tests/codegen/push", n - 1, F_E_B, 0}};
  arm.joint_forces = {{"https://mospec.example/tests/codegen/tau-1", 1, tau_1, 0}};
  b.p.arms.push_back(std::move(arm));
  const int degraded = b.datum("right_arm_degraded", T::Flag);
  ir::Step& solve = b.step(K::ArmSolve, "right_arm_solve",
                           {acc, acc_x, F_E_B, tau_1, low_err, reach}, {degraded});
  solve.solver = 0;
  solve.n_drivers = 5;

  for (int d : {time, height, elbow_x, vz, err, acc, low_err, acc_x, push, q_3, qd_3, tau_m_3}) {
    b.log(b.p.data[static_cast<std::size_t>(d)].name, d,
          b.p.data[static_cast<std::size_t>(d)].unit);
  }
  b.p.log.push_back({"F_est.f_z", "N", F_est, 5});
  b.log("height_ok", ok);
  b.log("reach", reach);
  b.log("right_arm_degraded", degraded, "", true);
  return b.p;
}

inline ir::Program hostile_program(SourceFiles& files) {
  using T = ir::DataType;
  using K = ir::StepKind;
  ProgramBuilder b(files);
  b.p.app = "https://mospec.example/tests/codegen/app*/\n#error injected ?\?/\n\xE2\x80\xAE";
  const std::string rlo = "\xE2\x80\xAE";  // U+202E RIGHT-TO-LEFT OVERRIDE, alone
  const int time = b.datum("?\?/", T::Scalar, {}, "SEC\\");  // its error's unit, hostile too
  b.step(K::ReadClock, "?\?/", {}, {time});
  const int ok = b.datum("assert", T::Flag);
  const int err = b.datum("errno", T::Scalar, {}, "SEC\\");
  ir::Step& ev = b.step(K::Evaluate, rlo, {time}, {ok, err});
  ev.constraint = {runtime::ConstraintKind::GreaterThan, 0.0, 0.2, 0.0, 0.0, 0.0};
  ev.has_error_output = true;
  ev.iri.append("*/\n#error injected\\");
  const int out = b.datum("NULL", T::Scalar, {}, "N-M");
  b.controller("pid", "switch", {err}, {out}, {{"kp", 2.0}, {"ki", 0.5}});
  const int level = b.datum("unix", T::Flag);
  ir::Step& lm = b.step(K::LevelMonitor, "EOF", {err}, {level});
  lm.constraint.tolerance = 0.01;
  lm.state = b.state(ir::StateKind::Monitor);
  const int edge = b.datum("linux", T::Event);
  ir::Step& em = b.step(K::EdgeMonitor, "stdin", {err}, {edge});
  em.constraint.tolerance = 0.01;
  em.state = b.state(ir::StateKind::Monitor);
  const int tau = b.datum("INFINITY", T::Scalar, {0.25}, "N-M");
  const int reserved = b.datum("__x", T::Scalar, {-0.125}, "N-M");
  const int capital = b.datum("_Capital", T::Scalar, {}, "M");
  const int keyword = b.datum("class", T::Scalar, {}, "M");
  const int x_first = b.datum("x_", T::Pose);
  const int x_second = b.datum("x5F", T::Pose);  // what "_" alone once became

  // Two arm solvers on the same chain, one per arm port.
  const runtime::Chain chain = gen3_chain();
  const int n = chain.size();
  const std::vector<std::pair<std::string, int>> solvers{{"r", robot::kRightArm},
                                                         {"r_task", robot::kLeftArm}};
  const std::vector<std::vector<int>> outputs{{x_first, capital}, {x_second, keyword}};
  const std::vector<int> forces{tau, reserved};
  for (std::size_t a = 0; a < solvers.size(); ++a) {
    ir::ArmSolver arm;
    arm.iri = "https://mospec.example/tests/codegen/" + solvers[a].first;
    arm.name = solvers[a].first;
    arm.chain_iri = "https://mospec.example/robots/kinova-gen3/chain";
    arm.root_frame = "https://mospec.example/robots/kinova-gen3/frame-base_link";
    arm.port = solvers[a].second;
    arm.chain = chain;
    arm.gravity = {0.0, 0.0, -9.81};
    arm.outputs = {{ir::ArmOutput::What::SegmentPose, n - 1, outputs[a][0]}};
    arm.joint_forces = {{"https://mospec.example/tests/codegen/tau?\?/", 1, forces[a], 0},
                        {"https://mospec.example/tests/codegen/pid", 2, out, 0}};
    arm.where = {1, static_cast<uint32_t>(200 + a), 1};
    b.p.arms.push_back(std::move(arm));
    ir::Step& kin = b.step(K::ArmKinematics, solvers[a].first + "_kinematics", {}, {outputs[a][0]});
    kin.solver = static_cast<int>(a);
    b.step(K::ViewRead, solvers[a].first + "_view", {outputs[a][0]}, {outputs[a][1]}).views = {5};
  }
  for (std::size_t a = 0; a < solvers.size(); ++a) {
    const int degraded = b.datum(solvers[a].first + "_degraded", T::Flag);
    ir::Step& solve =
        b.step(K::ArmSolve, solvers[a].first + "_solve", {forces[a], out}, {degraded});
    solve.solver = static_cast<int>(a);
  }
  b.log("?\?/", time, "SEC");
  b.log(rlo, err, "SEC\\");
  b.log("NULL \"quoted\" \\", out, "N-M");
  b.log("*/", capital, "M");
  b.log("class", keyword, "M");
  b.log("assert", ok);
  b.log("unix", level, "", true);
  b.log("linux", edge);
  return b.p;
}

// A synthetic measurement for tick k (1 kHz): smooth joint motion, pivots
// turning, a non-zero dt except on the first sample.
// Every operator kind of the registry (ir::operator_kinds()), each once, on
// constant inputs (a scalar input is the clock's time, so values change from
// tick to tick); every output is logged: a scalar as it is, a twist or wrench
// by component, a pose through six views, a vector as the force of a wrench.
// Then every controller kind (ir::controller_kinds()), each twice with the
// clock's time as every signal: once always running, once gated by a flag
// that turns off (so its reset runs too); its k-th model parameter is
// 0.25 (k + 1), the rest the runtime's defaults; the control signal is logged.
// A new operator or controller kind is in this program, and so in the
// interpreter == generated and allocation tests, without editing it.
inline ir::Program operators_program(SourceFiles& files) {
  using T = ir::DataType;
  using K = ir::StepKind;
  ProgramBuilder b(files);
  const int time = b.datum("time", T::Scalar, {}, "SEC");
  b.step(K::ReadClock, "clock", {}, {time});
  const int zero = b.datum("p_zero", T::Vector3, {0.0, 0.0, 0.0}, "M");
  const int one = b.datum("f_one", T::Scalar, {1.0}, "N");
  const auto kinds = ir::operator_kinds();
  for (std::size_t k = 0; k < kinds.size(); ++k) {
    const ir::OperatorKind& kind = kinds[k];
    const std::string prefix = "k" + std::to_string(k) + "_";
    std::vector<int> in;
    for (std::size_t i = 0; i < kind.in.size(); ++i) {
      const double a = 0.1 * static_cast<double>(k + 1) + 0.37 * static_cast<double>(i);
      const std::string name = prefix + "in" + std::to_string(i);
      switch (kind.in[i].type) {
        case T::Scalar:
          in.push_back(time);
          break;
        case T::Vector3:
          in.push_back(kind.in[i].source == ir::PortSource::Axis
                           ? b.datum(name, T::Vector3, {0.0, 0.0, 1.0})
                           : b.datum(name, T::Vector3, {std::cos(a), std::sin(a), 0.5}));
          break;
        case T::Pose:
          in.push_back(b.datum(name, T::Pose, pose_value(a, 0.2, -0.1 * a, 0.3)));
          break;
        case T::Twist:
        case T::Wrench:
          in.push_back(b.datum(name, kind.in[i].type, {a, -a, 0.5, 1.0 - a, 2.0 * a, -0.25}));
          break;
        case T::Inertia:  // a 1.5 kg body, its centre of mass off the reference point
          in.push_back(b.datum(name, T::Inertia,
                               {1.5, 0.03, -0.02, 0.15, 0.04, 0.05, 0.01, 0.001, -0.002, 0.003}));
          break;
        default:
          throw std::logic_error("operators_program: no constant for an input of " +
                                 std::string(kind.name));
      }
    }
    const std::string out_name = prefix + "out";
    const int out = b.datum(out_name, kind.out.type);
    b.op(kind.name, prefix + "op", in, {out});
    switch (kind.out.type) {
      case T::Scalar:
        b.log(out_name, out);
        break;
      case T::Twist:
      case T::Wrench:
        for (int c = 0; c < 6; ++c) {
          b.p.log.push_back({out_name + "." + std::to_string(c), "", out, c});
        }
        break;
      case T::Pose:
        for (int c = 0; c < 6; ++c) {
          const std::string view = out_name + "_view" + std::to_string(c);
          const int v = b.datum(view, T::Scalar);
          b.step(K::ViewRead, prefix + "read" + std::to_string(c), {out}, {v}).views = {c};
          b.log(view, v);
        }
        break;
      case T::Vector3: {
        const int F = b.datum(out_name + "_as_force", T::Wrench);
        b.op("wrench-from-position-direction-and-magnitude", prefix + "as_force", {zero, out, one},
             {F});
        for (int c = 3; c < 6; ++c) {
          b.p.log.push_back({out_name + "." + std::to_string(c - 3), "", F, c});
        }
        break;
      }
      default:
        throw std::logic_error("operators_program: cannot log the output of " +
                               std::string(kind.name));
    }
  }
  // The gate: "t < 0.1 s", which turns off during the tests' runs.
  const int gate = b.datum("gate_early", T::Flag);
  const int gate_err = b.datum("gate_early_err", T::Scalar, {}, "SEC");
  b.step(K::Evaluate, "gate_early_eval", {time}, {gate, gate_err}).constraint = {
      runtime::ConstraintKind::LessThan, 0.0, 0.1, 0.0, 0.0, 0.0};
  // Any of two motions' flags (a controller several handlers list): "t < 0.1 s"
  // or "t > 0.2 s" (thresholds met at equality), so off in between; one PID
  // runs under it.
  const int late = b.datum("gate_late", T::Flag);
  const int late_err = b.datum("gate_late_err", T::Scalar, {}, "SEC");
  b.step(K::Evaluate, "gate_late_eval", {time}, {late, late_err}).constraint = {
      runtime::ConstraintKind::GreaterThan, 0.0, 0.2, 0.0, 0.0, 0.0};
  const int either = b.datum("gate_either", T::Flag);
  b.step(K::AnyOf, "gate_either_any", {gate, late}, {either});
  b.log("gate_either", either);
  const auto ckinds = ir::controller_kinds();
  {
    const ir::ControllerKind& pid = *std::find_if(ckinds.begin(), ckinds.end(), [](const auto& k) {
      return k.name == std::string_view("pid");
    });
    std::vector<std::pair<std::string, double>> values;
    for (const ir::ControllerParameter& param : pid.parameters) {
      if (param.source != ir::ParameterSource::Fixed)
        values.emplace_back(std::string(param.member), 0.5);
    }
    const int out = b.datum("c_either_out", T::Scalar);
    std::vector<int> in(pid.in.size(), time);
    in.push_back(either);
    b.controller(pid.name, "c_either", in, {out}, values);
    b.log("c_either_out", out);
  }
  for (std::size_t k = 0; k < ckinds.size(); ++k) {
    const ir::ControllerKind& kind = ckinds[k];
    std::vector<std::pair<std::string, double>> values;
    double next = 0.0;
    for (const ir::ControllerParameter& param : kind.parameters) {
      if (param.source != ir::ParameterSource::Fixed)
        values.emplace_back(std::string(param.member), next += 0.25);
    }
    for (const bool gated : {false, true}) {
      // (Appended, not "c" + ...: GCC 12 warns falsely of overlapping memcpy there.)
      std::string name = "c";
      name.append(std::to_string(k)).append(gated ? "_gated" : "_free");
      const int out = b.datum(name + "_out", T::Scalar);
      std::vector<int> in(kind.in.size(), time);
      if (gated) in.push_back(gate);
      b.controller(kind.name, name, in, {out}, values);
      b.log(name + "_out", out);
    }
  }
  return b.p;
}

inline robot::MeasuredState measurement(std::uint64_t k) {
  robot::MeasuredState s = robot::make_state(robot::gen3_pair_shape());
  const double t = 0.001 * static_cast<double>(k);
  s.clock = {k, t, k == 0 ? 0.0 : 0.001};
  for (std::size_t a = 0; a < s.arm.size(); ++a) {
    for (std::size_t j = 0; j < s.arm[a].q.size(); ++j) {
      const double w = 0.5 + 0.1 * static_cast<double>(j) + 0.05 * static_cast<double>(a);
      s.arm[a].q[j] = 0.3 * std::sin(w * t + static_cast<double>(j)) + (j % 2 == 1 ? 0.4 : 0.0);
      s.arm[a].qd[j] = 0.3 * w * std::cos(w * t + static_cast<double>(j));
      // Measured torques, with a non-finite sample now and then (a joint
      // torque output keeps its last finite value).
      s.arm[a].tau[j] =
          k % 97 == 13 ? std::nan("") : 2.0 * std::cos(0.9 * t + static_cast<double>(j + a));
    }
  }
  for (std::size_t i = 0; i < s.pivot_q.size(); ++i) {
    s.pivot_q[i] = 0.2 * static_cast<double>(i) + 0.3 * std::sin(t + static_cast<double>(i));
  }
  for (std::size_t w = 0; w < s.wheel_qd.size(); ++w) {
    s.wheel_qd[w] = 0.5 * std::sin(0.7 * t + static_cast<double>(w));
  }
  return s;
}

}  // namespace mospec::codegen::testing
