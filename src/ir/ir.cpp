#include "ir/ir.hpp"

#include <nlohmann/json.hpp>

#include "ir/operators.hpp"

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
  }
  return "?";
}

std::string_view to_string(StepKind k) {
  switch (k) {
    case StepKind::ReadClock:
      return "read-clock";
    case StepKind::ArmKinematics:
      return "arm-kinematics";
    case StepKind::ViewRead:
      return "view-read";
    case StepKind::ViewWrite:
      return "view-write";
    case StepKind::Operator:
      return "operator";
    case StepKind::Evaluate:
      return "evaluate";
    case StepKind::LevelMonitor:
      return "level-monitor";
    case StepKind::EdgeMonitor:
      return "edge-monitor";
    case StepKind::GuardedMotion:
      return "guarded-motion";
    case StepKind::Pid:
      return "pid";
    case StepKind::ArmSolve:
      return "arm-solve";
    case StepKind::BaseForceDistribution:
      return "base-force-distribution";
    case StepKind::BaseVelocityComposition:
      return "base-velocity-composition";
  }
  return "?";
}

std::string_view kind_name(const Step& step) {
  if (step.kind == StepKind::Operator) {
    const auto kinds = operator_kinds();
    if (step.op >= 0 && static_cast<size_t>(step.op) < kinds.size())
      return kinds[static_cast<size_t>(step.op)].name;
  }
  return to_string(step.kind);
}

runtime::AchdModel achd_model(const ArmSolver& arm, bool physical) {
  const runtime::Vec3 g = physical ? runtime::Vec3(arm.gravity[0], arm.gravity[1], arm.gravity[2])
                                   : runtime::Vec3::Zero();
  runtime::AchdModel model(arm.chain, g);
  if (arm.tip_is_last_segment) model.X_NT = runtime::Pose{};
  return model;
}

runtime::KeloConfig kelo_config(const BaseSolver& base) {
  runtime::KeloConfig c;
  c.geometry = base.geometry;
  return c;
}

runtime::Pose constant_pose(const std::vector<double>& v) {
  runtime::Pose X;
  if (v.size() != 12) return X;
  X.R << v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7], v[8];
  X.p = runtime::Vec3(v[9], v[10], v[11]);
  return X;
}

namespace {

[[noreturn]] void invalid(const Step& step, const std::string& what) {
  std::string msg = "IR step '";
  msg.append(step.name)
      .append("' (")
      .append(kind_name(step))
      .append(", from '")
      .append(step.iri)
      .append("'): ")
      .append(what);
  throw Error("ir-invalid", msg);
}

// The data types each step kind takes and gives; empty = checked elsewhere.
struct Signature {
  std::vector<DataType> in, out;
  bool variadic_in = false;
};

Signature signature(const Step& st, const Program& p) {
  using T = DataType;
  switch (st.kind) {
    case StepKind::ReadClock:
      return {{}, {T::Scalar}};
    case StepKind::Operator: {
      const auto kinds = operator_kinds();
      if (st.op < 0 || static_cast<size_t>(st.op) >= kinds.size())
        invalid(st, "names no operator kind");
      const OperatorKind& k = kinds[static_cast<size_t>(st.op)];
      Signature s{{}, {k.out.type}};
      for (const OperatorPort& port : k.in) s.in.push_back(port.type);
      return s;
    }
    case StepKind::LevelMonitor:
      return {{T::Scalar}, {T::Flag}};
    case StepKind::EdgeMonitor:
      return {{T::Scalar}, {T::Event}};
    case StepKind::Evaluate:
      if (st.in.size() == 2) return {{T::Scalar, T::Flag}, {T::Flag, T::Scalar}};
      return {{T::Scalar}, {T::Flag, T::Scalar}};
    case StepKind::Pid:
      if (st.in.size() == 2) return {{T::Scalar, T::Flag}, {T::Scalar}};
      return {{T::Scalar}, {T::Scalar}};
    case StepKind::GuardedMotion: {
      Signature s{std::vector<T>(st.in.size(), T::Flag), {T::Flag}};
      return s;
    }
    case StepKind::ViewRead: {
      const T super = st.in.empty() ? T::Pose : p.data[static_cast<size_t>(st.in[0])].type;
      if (super != T::Pose && super != T::Twist && super != T::Wrench)
        invalid(st, "a view reads a pose, twist or wrench");
      return {{super}, {T::Scalar}};
    }
    case StepKind::ViewWrite: {
      const T super = st.out.empty() ? T::Wrench : p.data[static_cast<size_t>(st.out[0])].type;
      if (super != T::Twist && super != T::Wrench) invalid(st, "a view writes a twist or wrench");
      return {std::vector<T>(st.in.size(), T::Scalar), {super}};
    }
    case StepKind::ArmKinematics:
    case StepKind::ArmSolve:
      return {{}, {}, true};
    case StepKind::BaseForceDistribution: {
      Signature s{{T::Wrench}, {}};
      for (size_t k = 1; k < st.in.size(); ++k) s.in.push_back(T::Flag);
      return s;
    }
    case StepKind::BaseVelocityComposition:
      return {{}, {T::Twist}};
  }
  return {};
}

}  // namespace

void verify(const Program& p) {
  // Slots: dense per type, each used once.
  std::array<std::vector<char>, kDataTypes> used;
  for (int t = 0; t < kDataTypes; ++t)
    used[static_cast<size_t>(t)].assign(static_cast<size_t>(p.slots[static_cast<size_t>(t)]), 0);
  for (const Data& d : p.data) {
    auto& u = used[static_cast<size_t>(d.type)];
    if (d.slot < 0 || static_cast<size_t>(d.slot) >= u.size() || u[static_cast<size_t>(d.slot)]) {
      std::string msg = "datum '";
      msg.append(d.name)
          .append("' has slot ")
          .append(std::to_string(d.slot))
          .append(", which is out of range or shared");
      throw Error("ir-invalid", msg);
    }
    u[static_cast<size_t>(d.slot)] = 1;
  }
  std::vector<char> available(p.data.size(), 0);
  for (size_t i = 0; i < p.data.size(); ++i) available[i] = !p.data[i].value.empty();
  const auto check_index = [&](const Step& st, int d) {
    if (d < 0 || static_cast<size_t>(d) >= p.data.size()) invalid(st, "refers to no datum");
  };
  const auto consume = [&](const Step& st, int d) {
    check_index(st, d);
    if (!available[static_cast<size_t>(d)]) {
      std::string msg = "reads '";
      msg.append(p.data[static_cast<size_t>(d)].name).append("' before any step produces it");
      invalid(st, msg);
    }
  };
  const auto produce = [&](const Step& st, int d) {
    check_index(st, d);
    if (available[static_cast<size_t>(d)]) {
      std::string msg = "writes '";
      msg.append(p.data[static_cast<size_t>(d)].name).append("', which is already produced");
      invalid(st, msg);
    }
    available[static_cast<size_t>(d)] = 1;
  };
  for (const Step& st : p.steps) {
    const Signature sig = signature(st, p);
    if (!sig.variadic_in) {
      if (sig.in.size() != st.in.size() || sig.out.size() != st.out.size())
        invalid(st, "wrong number of inputs or outputs");
      for (size_t k = 0; k < st.in.size(); ++k) {
        check_index(st, st.in[k]);
        if (p.data[static_cast<size_t>(st.in[k])].type != sig.in[k])
          invalid(st, "input of the wrong type");
      }
      for (size_t k = 0; k < st.out.size(); ++k) {
        check_index(st, st.out[k]);
        if (p.data[static_cast<size_t>(st.out[k])].type != sig.out[k])
          invalid(st, "output of the wrong type");
      }
    }
    if ((st.kind == StepKind::ViewRead && st.views.size() != 1) ||
        (st.kind == StepKind::ViewWrite && st.views.size() != st.in.size()))
      invalid(st, "one view component per scalar");
    for (int v : st.views) {
      if (v < 0 || v > 5) invalid(st, "view component out of range");
    }
    if (st.kind == StepKind::GuardedMotion &&
        (st.n_when > kMaxGuards || static_cast<int>(st.in.size()) - st.n_when > kMaxGuards))
      invalid(st, "too many guards");
    if (st.kind == StepKind::ArmKinematics || st.kind == StepKind::ArmSolve) {
      if (st.solver < 0 || static_cast<size_t>(st.solver) >= p.arms.size())
        invalid(st, "no such arm solver");
    }
    if ((st.kind == StepKind::BaseForceDistribution ||
         st.kind == StepKind::BaseVelocityComposition) &&
        !p.base)
      invalid(st, "no base solver");
    if (st.kind == StepKind::ArmSolve) {
      if (st.drivers() > st.in.size()) invalid(st, "bad driver count");
      for (size_t k = st.drivers(); k < st.in.size(); ++k) {
        check_index(st, st.in[k]);
        if (p.data[static_cast<size_t>(st.in[k])].type != DataType::Flag)
          invalid(st, "a motion gate must be a flag");
      }
    }
    for (int d : st.in) consume(st, d);
    for (int d : st.out) produce(st, d);
  }
  for (const ArmSolver& a : p.arms) {
    for (const AccelerationConstraint& c : a.acceleration_constraints) {
      if (c.component < 0 || c.component > 5)
        throw Error("ir-invalid", "acceleration constraint component out of range");
    }
    if (a.acceleration_constraints.size() > static_cast<size_t>(runtime::kMaxConstraints))
      throw Error("ir-invalid", "more acceleration constraints than ACHD supports");
  }
  for (const LogColumn& c : p.log) {
    if (c.data < 0 || static_cast<size_t>(c.data) >= p.data.size())
      throw Error("ir-invalid", "log column '" + c.name + "' refers to no datum");
    const DataType t = p.data[static_cast<size_t>(c.data)].type;
    if (c.component >= 0 && (c.component > 5 || (t != DataType::Twist && t != DataType::Wrench)))
      throw Error("ir-invalid",
                  "log column '" + c.name + "': a component of a twist or wrench only");
  }
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

std::string to_json(const Program& p, const SourceFiles* files) {
  Json j;
  j["mospec-ir"] = 1;
  j["app"] = p.app;
  Json slots;
  for (int t = 0; t < kDataTypes; ++t)
    slots[std::string(to_string(static_cast<DataType>(t)))] = p.slots[static_cast<size_t>(t)];
  j["slots"] = slots;
  Json data = Json::array();
  for (size_t i = 0; i < p.data.size(); ++i) {
    const Data& d = p.data[i];
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
    data.push_back(std::move(e));
  }
  j["data"] = std::move(data);
  Json arms = Json::array();
  for (const ArmSolver& a : p.arms) {
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
      const char* what = o.what == ArmOutput::What::SegmentPose     ? "segment-pose"
                         : o.what == ArmOutput::What::ChainRootPose ? "segment-pose-in-chain-root"
                                                                    : "segment-twist";
      outs.push_back({{"what", what}, {"segment", o.segment}, {"data", o.data}});
    }
    e["outputs"] = std::move(outs);
    Json acc = Json::array();
    for (const AccelerationConstraint& c : a.acceleration_constraints) {
      acc.push_back(
          {{"iri", c.iri}, {"component", c.component}, {"energy", c.energy}, {"level", c.level}});
    }
    e["acceleration-constraints"] = std::move(acc);
    Json frc = Json::array();
    for (const CartesianForce& c : a.cartesian_forces) {
      frc.push_back(
          {{"iri", c.iri}, {"segment", c.segment}, {"wrench", c.wrench}, {"level", c.level}});
    }
    e["cartesian-forces"] = std::move(frc);
    Json jf = Json::array();
    for (const JointForce& c : a.joint_forces) {
      jf.push_back({{"iri", c.iri}, {"joint", c.joint}, {"force", c.force}, {"level", c.level}});
    }
    e["joint-forces"] = std::move(jf);
    e["priority-levels"] = a.priority_levels;
    e["where"] = location(a.where, files);
    arms.push_back(std::move(e));
  }
  j["arms"] = std::move(arms);
  if (p.base) {
    Json b;
    b["name"] = p.base->name;
    b["iri"] = p.base->iri;
    Json drives = Json::array();
    for (const auto& d : p.base->geometry.p_PoAi_P) drives.push_back({d.x(), d.y()});
    b["drive-positions"] = std::move(drives);
    b["wheel-diameter"] = p.base->geometry.wheel_diameter;
    b["wheel-distance"] = p.base->geometry.wheel_distance;
    b["castor-offset"] = p.base->geometry.castor_offset;
    b["wrench"] = p.base->wrench;
    b["twist"] = p.base->twist;
    b["where"] = location(p.base->where, files);
    j["base"] = std::move(b);
  } else {
    j["base"] = nullptr;
  }
  Json steps = Json::array();
  for (const Step& st : p.steps) {
    Json e;
    e["kind"] = kind_name(st);
    e["name"] = st.name;
    e["iri"] = st.iri;
    e["in"] = st.in;
    e["out"] = st.out;
    if (st.solver >= 0) e["solver"] = st.solver;
    if (st.kind == StepKind::ArmSolve || st.kind == StepKind::BaseForceDistribution)
      e["drivers"] = st.drivers();
    if (!st.views.empty()) e["views"] = st.views;
    if (st.kind == StepKind::Evaluate || st.kind == StepKind::LevelMonitor ||
        st.kind == StepKind::EdgeMonitor) {
      static constexpr const char* kKinds[] = {"equality", "less-than", "greater-than", "bilateral",
                                               "assignment"};
      Json c;
      c["relation"] = kKinds[static_cast<int>(st.constraint.kind)];
      c["reference"] = st.constraint.reference;
      c["threshold"] = st.constraint.threshold;
      c["lower"] = st.constraint.lower;
      c["upper"] = st.constraint.upper;
      c["tolerance"] = st.constraint.tolerance;
      e["constraint"] = std::move(c);
    }
    if (st.kind == StepKind::GuardedMotion) e["when"] = st.n_when;
    if (st.kind == StepKind::Pid) {
      e["pid"] = {{"kp", st.pid.kp},
                  {"ki", st.pid.ki},
                  {"kd", st.pid.kd},
                  {"decay-rate", st.pid.decay_rate}};
    }
    if (st.state >= 0) e["state"] = st.state;
    e["where"] = location(st.where, files);
    steps.push_back(std::move(e));
  }
  j["schedule"] = std::move(steps);
  Json log = Json::array();
  for (const LogColumn& c : p.log) {
    Json e = {{"name", c.name}, {"unit", c.unit}, {"data", c.data}};
    if (c.component >= 0) e["component"] = c.component;
    log.push_back(std::move(e));
  }
  j["log"] = std::move(log);
  return j.dump(2) + "\n";
}

}  // namespace mospec::ir
