#include "ir/lower.hpp"

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>
#include <unordered_map>

#include "description/chain_rdf.hpp"
#include "ir/controllers.hpp"
#include "ir/graph.hpp"
#include "ir/operators.hpp"
#include "vocab/metamodels.hpp"
#include "vocab/w3c.hpp"

namespace mospec::ir {

std::map<std::string, int> LowerOptions::default_ports() {
  return {{std::string(vocab::robots::kinova_gen3_chain), 0},
          {std::string(vocab::robots::kinova_gen3_left_chain), 1}};
}

namespace {

std::string join_lines(const std::vector<Diagnostic>& ds) {
  std::string out;
  for (size_t i = 0; i < ds.size(); ++i) {
    if (i) out.push_back('\n');
    out.append(format(ds[i]));
  }
  return out;
}

}  // namespace

LowerError::LowerError(std::vector<Diagnostic> diagnostics)
    : Error("lowering-failed", join_lines(diagnostics)), diagnostics_(std::move(diagnostics)) {}

std::string content_hash(const std::string& text) {
  uint64_t h = 1469598103934665603ULL;
  for (unsigned char c : text) {
    h ^= c;
    h *= 1099511628211ULL;
  }
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
  return buf;
}

namespace {

using rdf::TermId;

std::string vocab(std::string_view domain, std::string_view local) {
  return mospec::vocab::metamodel_term(domain, local);
}
const std::string kXsd(mospec::vocab::xsd::ns);
const std::string kQudt(mospec::vocab::qudt::ns);

std::string local_name(std::string_view iri) {
  const size_t k = iri.find_last_of("#/");
  return std::string(k == std::string_view::npos ? iri : iri.substr(k + 1));
}

std::string identifier(std::string_view s) {
  std::string out;
  for (char c : s) out.push_back(std::isalnum(static_cast<unsigned char>(c)) ? c : '_');
  if (out.empty() || std::isdigit(static_cast<unsigned char>(out[0]))) out.insert(0, "q_");
  return out;
}

class Lowerer {
 public:
  Lowerer(const app::LoadedModel& model, const LowerOptions& options)
      : model_(model), g_(model.dataset()), options_(options) {}

  Program run();

 private:
  // --- graph access (ir/graph.hpp) ---------------------------------------
  TermId term(const std::string& iri) const { return g_.term(iri); }
  static bool absent(TermId t) { return t.is_any(); }
  std::string str(TermId t) const { return std::string(g_.str(t)); }
  std::vector<TermId> objects(TermId s, const std::string& p) const {
    return g_.objects(s, term(p));
  }
  std::optional<TermId> object(TermId s, const std::string& p) const {
    return g_.object(s, term(p));
  }
  bool has_type(TermId s, const std::string& type) const { return g_.has_type(s, term(type)); }
  std::vector<TermId> instances(const std::string& type) const { return g_.instances(term(type)); }
  bool defined(TermId s) const { return g_.defined(s); }
  SourceLoc where(TermId s) const { return g_.where(s); }
  SourceLoc where(TermId s, const std::string& p, TermId o) const {
    return g_.where(s, term(p), o);
  }
  // Whether `q` is the time some clock gives (mospec/time).
  bool is_clock_time(TermId q) const {
    for (TermId c : g_.subjects(term(vocab("mospec/time", "time")), q)) {
      if (has_type(c, vocab("mospec/time", "Clock"))) return true;
    }
    return false;
  }
  std::vector<TermId> list(TermId head) const { return g_.list(head); }
  std::optional<double> number(TermId lit) const { return g_.number(lit); }
  // The literal as messages quote it: "+1e400"^^xsd:double.
  std::string literal_text(TermId lit) const {
    const rdf::Term& t = g_.terms()[lit];
    std::string dt(g_.terms()[t.datatype].value);
    if (dt.rfind(kXsd, 0) == 0) dt = "xsd:" + dt.substr(kXsd.size());
    return "\"" + std::string(t.value) + "\"^^" + dt;
  }
  std::optional<double> number(TermId s, const std::string& p) const {
    return g_.number(s, term(p));
  }

  // The graph of the file that describes a chain: other files' poses between
  // the robot's frames (task quantities) are not part of its structure.
  rdf::Dataset chain_graph(const std::string& chain_iri) const {
    return g_.graphs_describing(term(chain_iri));
  }

  // --- diagnostics --------------------------------------------------------
  void error(SourceLoc loc, std::string code, std::string message) {
    Diagnostic d;
    d.severity = Severity::Error;
    if (loc.known()) {
      d.file = model_.files().path(loc.file);
      d.line = loc.line;
      d.column = loc.column;
    }
    d.code = std::move(code);
    d.message = std::move(message);
    errors_.push_back(std::move(d));
  }
  void error(TermId at, std::string code, std::string message) {
    error(where(at), std::move(code), std::move(message));
  }

  // --- data ---------------------------------------------------------------
  std::optional<DataType> type_of(TermId e) const;
  int datum(TermId e, DataType expected, TermId referenced_by, const std::string& role);
  int synthetic(const std::string& iri, const std::string& name, DataType type, SourceLoc loc,
                const std::string& unit = {});
  std::string unique_name(const std::string& base, std::set<std::string>& used) {
    std::string n = identifier(base);
    std::string candidate = n;
    for (int k = 2; used.count(candidate); ++k) candidate = n + "_" + std::to_string(k);
    used.insert(candidate);
    return candidate;
  }
  void fill_constant(Data& d, TermId e);

  // --- steps --------------------------------------------------------------
  // A step asked for by model entity `e`, named and located by it.
  Step step_for(StepKind kind, TermId e) const {
    Step s;
    s.kind = kind;
    s.iri = str(e);
    s.name = local_name(s.iri);
    s.where = where(e);
    return s;
  }
  int add_step(Step step) {
    step.name = unique_name(step.name, step_names_);
    const int index = static_cast<int>(steps_.size());
    for (int d : step.out) produce(d, index);
    steps_.push_back(std::move(step));
    return index;
  }
  void produce(int d, int step) {
    if (!prog_.data[static_cast<size_t>(d)].value.empty()) {
      const Data& dd = prog_.data[static_cast<size_t>(d)];
      error(dd.where, "produced-constant",
            "'" + dd.iri + "' has a fixed value in the model, but '" + pending_iri_ +
                "' also writes it");
      return;
    }
    auto [it, fresh] = producer_.emplace(d, step);
    if (!fresh) {
      const Data& dd = prog_.data[static_cast<size_t>(d)];
      std::string msg = "'";
      msg.append(dd.iri)
          .append("' is produced twice: by '")
          .append(steps_[static_cast<size_t>(it->second)].iri)
          .append("' and by '")
          .append(pending_iri_)
          .append("'");
      error(dd.where, "produced-twice", msg);
    }
  }
  bool produced(int d) const {
    return producer_.count(d) || !prog_.data[static_cast<size_t>(d)].value.empty();
  }

 public:
  // Lowering's passes (kPasses).
  void lower_clocks();
  void lower_arms();
  void lower_arm(TermId solver);
  void lower_operators();
  int axis_constant(TermId e, const OperatorKind& kind, const OperatorPort& port, TermId axis);
  void check_frames(TermId e, const OperatorKind& kind, const Step& s);
  void refuse_unknown_properties(TermId e, const OperatorKind& kind);
  void lower_accumulated_wrenches();
  std::string frame_origin(const std::string& frame) const;
  void lower_planar_angles();
  void lower_evaluators();
  void lower_monitors();
  void lower_handlers();
  void lower_controllers();
  void lower_base();
  void lower_views();
  void gate_arm_solves();
  void check_inputs();
  void schedule();
  void build_log();

 private:
  const app::LoadedModel& model_;
  Graph g_;  // the model's flattened union, read in place
  const LowerOptions& options_;
  Program prog_;
  std::vector<Diagnostic> errors_;
  std::unordered_map<uint32_t, int> data_of_;  // entity term index -> data
  std::set<std::string> data_names_, step_names_;
  std::vector<Step> steps_;                          // unscheduled
  std::map<int, int> producer_;                      // data -> step
  std::string pending_iri_;                          // the entity being lowered (for messages)
  std::map<uint32_t, int> evaluator_of_constraint_;  // constraint term -> step
  std::map<uint32_t, int> active_of_controller_;     // controller term -> active flag data
  std::map<uint32_t, int> active_of_evaluator_;      // evaluator term -> active flag data
  std::map<uint32_t, int> evaluate_step_of_evaluator_;
  std::map<int, std::pair<int, int>>
      bounds_of_satisfied_;  // bilateral: satisfied flag -> lower, upper data
};

std::optional<DataType> Lowerer::type_of(TermId e) const {
  if (has_type(e, vocab("geometry/spatial-relations", "Pose")) ||
      has_type(e, vocab("geometry/coordinates", "PoseCoordinate")))
    return DataType::Pose;
  if (has_type(e, vocab("geometry/spatial-relations", "VelocityTwist")) ||
      has_type(e, vocab("geometry/coordinates", "VelocityTwistCoordinate")))
    return DataType::Twist;
  if (has_type(e, vocab("newtonian-rigid-body-dynamics/structural-entities", "Wrench")) ||
      has_type(e, vocab("newtonian-rigid-body-dynamics/coordinates", "WrenchCoordinate")))
    return DataType::Wrench;
  if (has_type(e, vocab("geometry/coordinates", "DirectionCoordinate")) ||
      has_type(e, vocab("geometry/spatial-relations", "Position")) ||
      has_type(e, vocab("geometry/coordinates", "PositionCoordinate")))
    return DataType::Vector3;
  if (has_type(e, kQudt + "Quantity") ||
      has_type(e, vocab("geometry/spatial-relations", "LinearDistance")) ||
      !objects(e, kQudt + "hasQuantityKind").empty())
    return DataType::Scalar;
  return std::nullopt;
}

void Lowerer::fill_constant(Data& d, TermId e) {
  const std::string gc = "geometry/coordinates";
  switch (d.type) {
    case DataType::Scalar:
      if (auto v = number(e, kQudt + "value")) d.value = {*v};
      break;
    case DataType::Vector3: {
      auto x = number(e, vocab(gc, "x")), y = number(e, vocab(gc, "y")),
           z = number(e, vocab(gc, "z"));
      if (x && y && z) d.value = {*x, *y, *z};
      break;
    }
    case DataType::Pose: {
      auto x = number(e, vocab(gc, "x")), y = number(e, vocab(gc, "y")),
           z = number(e, vocab(gc, "z"));
      std::array<std::vector<double>, 3> cols;
      bool ok = x && y && z;
      const char* names[3] = {"direction-cosine-x", "direction-cosine-y", "direction-cosine-z"};
      for (int c = 0; c < 3 && ok; ++c) {
        auto head = object(e, vocab(gc, names[c]));
        if (!head) {
          ok = false;
          break;
        }
        for (TermId t : list(*head)) {
          if (auto v = number(t)) cols[static_cast<size_t>(c)].push_back(*v);
        }
        ok = cols[static_cast<size_t>(c)].size() == 3;
      }
      if (!ok) break;
      // direction-cosine-x is the x axis of the distal frame seen by the
      // proximal one: the first column of R.
      runtime::Mat3 R;
      for (int c = 0; c < 3; ++c)
        for (int r = 0; r < 3; ++r) R(r, c) = cols[static_cast<size_t>(c)][static_cast<size_t>(r)];
      if (!((R.transpose() * R - runtime::Mat3::Identity()).cwiseAbs().maxCoeff() < 1e-6) ||
          R.determinant() < 0) {
        error(e, "invalid-pose",
              "the direction cosines of '" + d.iri +
                  "' are not a rotation (orthonormal, right-handed to 1e-6)");
        break;
      }
      // Direction cosines are written to a few digits: use the nearest
      // rotation (polar decomposition), so composed poses stay rigid.
      {
        Eigen::JacobiSVD<runtime::Mat3> svd(R, Eigen::ComputeFullU | Eigen::ComputeFullV);
        R = svd.matrixU() * svd.matrixV().transpose();
      }
      d.value = {R(0, 0), R(0, 1), R(0, 2), R(1, 0), R(1, 1), R(1, 2),
                 R(2, 0), R(2, 1), R(2, 2), *x,      *y,      *z};
      break;
    }
    default:
      break;
  }
}

int Lowerer::datum(TermId e, DataType expected, TermId referenced_by, const std::string& role) {
  if (auto it = data_of_.find(e.index); it != data_of_.end()) {
    const Data& d = prog_.data[static_cast<size_t>(it->second)];
    if (d.type != expected) {
      std::string msg = "'";
      msg.append(str(referenced_by))
          .append("' uses '")
          .append(d.iri)
          .append("' as its ")
          .append(role)
          .append(", which must be a ")
          .append(to_string(expected))
          .append(", but it is a ")
          .append(to_string(d.type));
      error(referenced_by, "type-mismatch", msg);
    }
    return it->second;
  }
  Data d;
  d.iri = str(e);
  d.type = expected;
  d.where = where(e);
  if (!defined(e)) {
    std::string msg = "'";
    msg.append(str(referenced_by))
        .append("' names '")
        .append(d.iri)
        .append("' as its ")
        .append(role)
        .append(", but no model file defines it");
    error(where(referenced_by), "undefined-quantity", msg);
  } else if (auto t = type_of(e); t && *t != expected) {
    std::string msg = "'";
    msg.append(str(referenced_by))
        .append("' uses '")
        .append(d.iri)
        .append("' as its ")
        .append(role)
        .append(", which must be a ")
        .append(to_string(expected))
        .append(", but it is a ")
        .append(to_string(*t));
    error(referenced_by, "type-mismatch", msg);
  }
  const std::string gr = "geometry/spatial-relations";
  if (auto o = object(e, vocab(gr, "of"))) d.of = str(*o);
  if (auto o = object(e, vocab(gr, "with-respect-to"))) d.with_respect_to = str(*o);
  if (auto o = object(e, vocab(gr, "reference-point"))) d.reference_point = str(*o);
  if (auto o =
          object(e, vocab("newtonian-rigid-body-dynamics/structural-entities", "reference-point")))
    d.reference_point = str(*o);
  if (auto o = object(e, vocab("geometry/coordinates", "as-seen-by"))) d.as_seen_by = str(*o);
  if (auto o = object(e, vocab("newtonian-rigid-body-dynamics/coordinates", "as-seen-by")))
    d.as_seen_by = str(*o);
  std::vector<std::string> kinds, units;
  for (TermId k : objects(e, kQudt + "hasQuantityKind")) kinds.push_back(local_name(str(k)));
  for (TermId u : objects(e, kQudt + "unit")) units.push_back(local_name(str(u)));
  for (size_t i = 0; i < kinds.size(); ++i) d.quantity_kind.append(i ? "," : "").append(kinds[i]);
  for (size_t i = 0; i < units.size(); ++i) d.unit.append(i ? "," : "").append(units[i]);
  fill_constant(d, e);
  d.name = unique_name(local_name(d.iri), data_names_);
  d.slot = prog_.slots[static_cast<size_t>(d.type)]++;
  const int index = static_cast<int>(prog_.data.size());
  prog_.data.push_back(std::move(d));
  data_of_[e.index] = index;
  return index;
}

int Lowerer::synthetic(const std::string& iri, const std::string& name, DataType type,
                       SourceLoc loc, const std::string& unit) {
  Data d;
  d.iri = iri;
  d.type = type;
  d.where = loc;
  d.unit = unit;
  d.name = unique_name(name, data_names_);
  d.slot = prog_.slots[static_cast<size_t>(type)]++;
  prog_.data.push_back(std::move(d));
  return static_cast<int>(prog_.data.size()) - 1;
}

// ---------------------------------------------------------------------------
void Lowerer::lower_clocks() {
  for (TermId c : instances(vocab("mospec/time", "Clock"))) {
    pending_iri_ = str(c);
    auto t = object(c, vocab("mospec/time", "time"));
    if (!t) {
      error(c, "missing-property", "the clock '" + str(c) + "' names no `time` quantity");
      continue;
    }
    Step s = step_for(StepKind::ReadClock, c);
    s.out = {datum(*t, DataType::Scalar, c, "time")};
    if (prog_.data[static_cast<size_t>(s.out[0])].unit != "SEC")
      error(*t, "wrong-unit", "the clock's time '" + str(*t) + "' must be in SEC");
    add_step(std::move(s));
  }
}

void Lowerer::lower_arm(TermId solver) {
  const std::string slv = "task/solver-specification";
  pending_iri_ = str(solver);
  ArmSolver arm;
  arm.iri = str(solver);
  arm.name = identifier(local_name(arm.iri));
  arm.where = where(solver);
  auto chain_t = object(solver, vocab(slv, "kinematic-chain"));
  if (!chain_t) {
    error(solver, "missing-property", "the solver '" + arm.iri + "' names no kinematic-chain");
    return;
  }
  arm.chain_iri = str(*chain_t);
  description::ChainFrames frames;
  try {
    description::ChainDescription described =
        description::describe_chain(chain_graph(arm.chain_iri), arm.chain_iri);
    arm.chain = std::move(described.chain);
    frames = std::move(described.frames);
  } catch (const Error& e) {
    error(where(solver, vocab(slv, "kinematic-chain"), *chain_t), "invalid-chain",
          "the solver '" + arm.iri + "': " + e.diagnostic().message);
    return;
  }
  if (auto it = options_.ports.find(arm.chain_iri); it != options_.ports.end()) {
    arm.port = it->second;
  } else {
    error(
        solver, "unbound-chain",
        "no robot arm is bound to the chain '" + arm.chain_iri +
            "' (mospec's robot has a right and a left Gen3; bind it with --bind CHAIN=right|left)");
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
  const std::string chain_root_frame = frames.root.frame;
  const std::string chain_root_link = frames.root.body;
  if (auto root = object(solver, vocab(slv, "root"))) {
    arm.root_frame = str(*root);
  } else {
    error(solver, "missing-property", "the solver '" + arm.iri + "' names no root");
    arm.root_frame = chain_root_frame;
  }
  if (arm.root_frame != chain_root_frame) {
    // A solver rooted at, e.g., the platform: the chain hangs from it by a
    // constant mount pose, which becomes part of the first joint's placement.
    std::optional<runtime::Pose> X_RB;
    for (TermId p : instances(vocab("geometry/spatial-relations", "Pose"))) {
      auto of = object(p, vocab("geometry/spatial-relations", "of"));
      auto wrt = object(p, vocab("geometry/spatial-relations", "with-respect-to"));
      auto seen = object(p, vocab("geometry/coordinates", "as-seen-by"));
      if (!of || !wrt || !seen || str(*of) != chain_root_frame || str(*wrt) != arm.root_frame ||
          str(*seen) != arm.root_frame)
        continue;
      const int d = datum(p, DataType::Pose, solver, "mount pose");
      if (prog_.data[static_cast<size_t>(d)].value.empty()) continue;
      X_RB = constant_pose(prog_.data[static_cast<size_t>(d)].value);
      arm.mount_pose_iri = str(p);
      arm.X_RB = *X_RB;
      break;
    }
    if (!X_RB) {
      error(solver, "unsupported-root",
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
  if (auto grav = object(solver, vocab(slv, "gravity"))) {
    const std::string gc = "geometry/coordinates";
    auto x = number(*grav, vocab(gc, "x")), y = number(*grav, vocab(gc, "y")),
         z = number(*grav, vocab(gc, "z"));
    std::string seen;
    if (auto s = object(*grav, vocab(gc, "as-seen-by"))) seen = str(*s);
    if (auto s = object(*grav, vocab("newtonian-rigid-body-dynamics/coordinates", "as-seen-by")))
      seen = str(*s);
    std::string unit;
    if (auto u = object(*grav, kQudt + "unit")) unit = local_name(str(*u));
    if (!x || !y || !z) {
      error(*grav, "missing-property", "the gravity '" + str(*grav) + "' needs x, y and z");
    } else if (seen != arm.root_frame) {
      error(*grav, "frame-mismatch",
            "the gravity '" + str(*grav) + "' is seen by '" + seen + "', but the solver '" +
                arm.iri + "' needs it in its root frame '" + arm.root_frame + "'");
    } else if (unit != "M-PER-SEC2") {
      error(*grav, "wrong-unit",
            "the gravity '" + str(*grav) + "' must be in M-PER-SEC2, not '" + unit + "'");
    } else {
      arm.gravity = {*x, *y, *z};
    }
  } else {
    error(solver, "missing-property", "the solver '" + arm.iri + "' names no gravity");
  }
  const int arm_index = static_cast<int>(prog_.arms.size());
  // Outputs.
  Step kin;
  kin.kind = StepKind::ArmKinematics;
  kin.iri = arm.iri;
  kin.name = arm.name + "_kinematics";
  kin.where = arm.where;
  kin.solver = arm_index;
  for (TermId o : objects(solver, vocab(slv, "output"))) {
    const auto t = type_of(o);
    if (t == DataType::Pose) {
      const int d = datum(o, DataType::Pose, solver, "output");
      const Data& dd = prog_.data[static_cast<size_t>(d)];
      const int seg = segment_by(dd.of, frame_of);
      const bool in_root = dd.with_respect_to == arm.root_frame && dd.as_seen_by == arm.root_frame;
      const bool in_chain_root = arm.root_frame != chain_root_frame &&
                                 dd.with_respect_to == chain_root_frame &&
                                 dd.as_seen_by == chain_root_frame;
      if (seg < 0 || !(in_root || in_chain_root)) {
        error(o, "unsupported-output",
              "the solver '" + arm.iri +
                  "' outputs poses of the chain's segment frames w.r.t. and seen by its root '" +
                  arm.root_frame + "' (or the chain's root '" + chain_root_frame + "'); '" +
                  dd.iri + "' is of '" + dd.of + "' w.r.t. '" + dd.with_respect_to + "' seen by '" +
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
      const int d = datum(o, DataType::Twist, solver, "output");
      const Data& dd = prog_.data[static_cast<size_t>(d)];
      int seg = segment_by(dd.of, link_of);
      if (seg < 0) seg = segment_by(dd.of, frame_of);
      const bool wrt_root = (!chain_root_link.empty() && dd.with_respect_to == chain_root_link) ||
                            dd.with_respect_to == chain_root_frame ||
                            dd.with_respect_to == arm.root_frame;
      if (seg < 0 || !wrt_root || dd.as_seen_by != arm.root_frame || dd.reference_point.empty() ||
          dd.reference_point != origin_of(seg)) {
        error(o, "unsupported-output",
              "the solver '" + arm.iri +
                  "' outputs twists of a segment w.r.t. the root, at the segment's origin, seen by "
                  "the root '" +
                  arm.root_frame + "'; '" + dd.iri + "' does not fit");
        continue;
      }
      arm.outputs.push_back({ArmOutput::What::SegmentTwist, seg, d});
      kin.out.push_back(d);
    } else {
      error(o, "unsupported-output",
            "the solver '" + arm.iri + "' cannot output '" + str(o) + "' (poses and twists only)");
    }
  }
  // Motion drivers and their priority levels.
  auto drivers = object(solver, vocab(slv, "motion-drivers"));
  Step solve;
  solve.kind = StepKind::ArmSolve;
  solve.iri = arm.iri;
  solve.name = arm.name + "_solve";
  solve.where = arm.where;
  solve.solver = arm_index;
  // The link of the last segment, as the robot model relates it to its frame.
  const std::string last_link = frames.segments.empty() ? "" : frames.segments.back().body;
  if (!drivers) {
    error(solver, "missing-property", "the solver '" + arm.iri + "' names no motion-drivers");
  } else {
    std::map<uint32_t, int> level_of;
    int level = 0;
    for (TermId head : objects(*drivers, vocab(slv, "prioritization-hierarchy"))) {
      for (TermId lv : list(head)) {
        std::vector<std::string> names;
        for (TermId d : objects(lv, vocab(slv, "motion-drivers"))) {
          level_of[d.index] = level;
          names.push_back(str(d));
        }
        arm.priority_levels.push_back(names);
        ++level;
      }
    }
    const auto level_for = [&](TermId spec) {
      auto it = level_of.find(spec.index);
      if (it == level_of.end()) {
        if (!arm.priority_levels.empty())
          error(spec, "unprioritised-driver",
                "the motion driver '" + str(spec) + "' is in no prioritization level of '" +
                    str(*drivers) + "'");
        return 0;
      }
      return it->second;
    };
    for (TermId spec : objects(*drivers, vocab(slv, "acceleration-constraint"))) {
      pending_iri_ = str(spec);
      const int lv = level_for(spec);
      if (lv != 0) {
        error(spec, "unsupported-priority",
              "acceleration constraints must be in the highest priority level: one ACHD solve "
              "honours one level of constraints; '" +
                  str(spec) + "' is in level " + std::to_string(lv + 1));
      }
      auto link = object(spec, vocab(slv, "attached-to"));
      if (last_link.empty() && !frames.segments.empty()) {
        error(spec, "unsupported-attachment",
              "ACHD constrains the chain's last segment, but no link of the robot model holds its "
              "frame '" +
                  frames.segments.back().frame +
                  "' (state the link's `simplices`: its frame and origin point, as "
                  "robots/kinova-gen3.jsonld does); '" +
                  str(spec) + "' is attached to '" + (link ? str(*link) : std::string("nothing")) +
                  "'");
      } else if (!link || str(*link) != last_link) {
        error(spec, "unsupported-attachment",
              "ACHD constrains the chain's last segment '" + last_link + "'; '" + str(spec) +
                  "' is attached to '" + (link ? str(*link) : std::string("nothing")) + "'");
      }
      for (TermId c : objects(spec, vocab(slv, "constraints"))) {
        AccelerationConstraint ac;
        ac.iri = str(c);
        ac.level = lv;
        auto sub = object(c, vocab(slv, "subspace"));
        auto axis = object(c, vocab(slv, "axis"));
        const std::string sn = sub ? local_name(str(*sub)) : "",
                          an = axis ? local_name(str(*axis)) : "";
        const int base = sn == "angular-acceleration" ? 0 : sn == "linear-acceleration" ? 3 : -1;
        const int ax = an == "x" ? 0 : an == "y" ? 1 : an == "z" ? 2 : -1;
        if (base < 0 || ax < 0) {
          error(c, "invalid-constraint",
                "the acceleration constraint '" + ac.iri +
                    "' needs subspace linear-/angular-acceleration and axis x, y or z");
          continue;
        }
        ac.component = base + ax;
        auto energy = object(c, vocab(slv, "acceleration-energy"));
        if (!energy) {
          error(c, "missing-property",
                "the acceleration constraint '" + ac.iri + "' names no acceleration-energy");
          continue;
        }
        ac.energy = datum(*energy, DataType::Scalar, c, "acceleration-energy");
        solve.in.push_back(ac.energy);
        arm.acceleration_constraints.push_back(ac);
      }
    }
    if (arm.acceleration_constraints.size() > static_cast<size_t>(runtime::kMaxConstraints)) {
      error(solver, "too-many-constraints",
            "the solver '" + arm.iri + "' has more than 6 acceleration constraints");
    }
    for (TermId spec : objects(*drivers, vocab(slv, "cartesian-force"))) {
      pending_iri_ = str(spec);
      CartesianForce cf;
      cf.iri = str(spec);
      cf.level = level_for(spec);
      auto link = object(spec, vocab(slv, "attached-to"));
      auto force = object(spec, vocab(slv, "force"));
      if (!link || !force) {
        error(spec, "missing-property",
              "the Cartesian force '" + cf.iri + "' needs `force` and `attached-to`");
        continue;
      }
      cf.segment = segment_by(str(*link), link_of);
      if (cf.segment < 0) {
        error(spec, "unknown-link",
              "'" + cf.iri + "' is attached to '" + str(*link) + "', which is no moving link of '" +
                  arm.chain_iri + "'");
        continue;
      }
      cf.wrench = datum(*force, DataType::Wrench, spec, "force");
      const Data& w = prog_.data[static_cast<size_t>(cf.wrench)];
      const std::string origin = origin_of(cf.segment);
      if (w.reference_point != origin || w.as_seen_by != arm.root_frame) {
        error(*force, "frame-mismatch",
              "the wrench '" + w.iri + "' drives '" + str(*link) + "' through '" + cf.iri +
                  "', so ACHD needs it at that link's origin '" + origin +
                  "' and seen by the root '" + arm.root_frame + "'; it is at '" +
                  w.reference_point + "' seen by '" + w.as_seen_by +
                  "' (transform it with TransformWrenchToProximal/RotateWrenchToProximalWithPose)");
      }
      solve.in.push_back(cf.wrench);
      arm.cartesian_forces.push_back(cf);
    }
    for (TermId spec : objects(*drivers, vocab(slv, "joint-force"))) {
      error(spec, "unsupported-driver",
            "joint-force motion drivers ('" + str(spec) + "') are not supported yet");
    }
  }
  // Drivers a level lists but the solver's drivers do not.
  pending_iri_ = arm.iri;
  prog_.arms.push_back(std::move(arm));
  add_step(std::move(kin));
  add_step(std::move(solve));
}

// Every operator kind of the registry (operators.hpp) that maps its class's
// properties onto its ports: one step per instance, its inputs and output the
// quantities the properties name, and the kind's frame rules checked.
void Lowerer::lower_operators() {
  const auto kinds = operator_kinds();
  for (size_t k = 0; k < kinds.size(); ++k) {
    const OperatorKind& kind = kinds[k];
    if (!kind.generic_lowering) continue;
    for (TermId e : instances(kind.class_iri())) {
      pending_iri_ = str(e);
      Step s = step_for(StepKind::Operator, e);
      s.op = static_cast<int>(k);
      bool ok = true;
      const auto port_datum = [&](const OperatorPort& port) {
        const std::vector<TermId> values = objects(e, kind.property_iri(port.property));
        if (values.size() > 1) {
          error(e, "several-values",
                "the " + std::string(kind.type) + " '" + s.iri + "' names " +
                    std::to_string(values.size()) + " values for `" + std::string(port.property) +
                    "` ('" + str(values[0]) + "', '" + str(values[1]) + "'" +
                    (values.size() > 2 ? ", ..." : "") + "); an operator reads exactly one");
          ok = false;
          return -1;
        }
        auto o = values.empty() ? std::optional<TermId>() : std::optional<TermId>(values[0]);
        if (!o) {
          error(e, "missing-property",
                "the " + std::string(kind.type) + " '" + s.iri + "' names no `" +
                    std::string(port.property) + "`");
          ok = false;
          return -1;
        }
        if (port.source == PortSource::Axis) return axis_constant(e, kind, port, *o);
        return datum(*o, port.type, e, std::string(port.property));
      };
      for (const OperatorPort& port : kind.in) s.in.push_back(port_datum(port));
      const int out = port_datum(kind.out);
      refuse_unknown_properties(e, kind);
      if (!ok) continue;
      s.out.push_back(out);
      check_frames(e, kind, s);
      add_step(std::move(s));
    }
  }
}

// A property of the operator's vocabulary that the kind does not read (e.g.
// TransformWrenchToProximal's `at-index` into an array of wrenches) would be
// ignored: refuse it instead.
void Lowerer::refuse_unknown_properties(TermId e, const OperatorKind& kind) {
  std::set<std::string> seen;
  for (const Graph::Statement& st : g_.statements(e)) {
    const std::string p = str(st.predicate);
    if (!p.starts_with(kind.vocabulary)) continue;
    const std::string_view local = std::string_view(p).substr(kind.vocabulary.size());
    if (kind.port(local) >= 0 || !seen.insert(p).second) continue;
    std::string ports;
    for (const OperatorPort& port : kind.in) ports.append(port.property).append(", ");
    ports.append(kind.out.property);
    error(st.where.known() ? st.where : where(e), "unsupported-property",
          "the " + std::string(kind.type) + " '" + str(e) + "' states `" + std::string(local) +
              "`, which mospec's " + std::string(kind.name) +
              " does not implement (it reads only " + ports +
              "); remove it or model the "
              "computation another way");
  }
}

// An axis the model names (geom-op:x, y or z): a unit-vector constant.
int Lowerer::axis_constant(TermId e, const OperatorKind& kind, const OperatorPort& port,
                           TermId axis) {
  const std::string name = local_name(str(axis));
  const int index = str(axis) == kind.property_iri("x")   ? 0
                    : str(axis) == kind.property_iri("y") ? 1
                    : str(axis) == kind.property_iri("z") ? 2
                                                          : -1;
  if (index < 0) {
    error(where(e, kind.property_iri(port.property), axis), "invalid-axis",
          "the " + std::string(kind.type) + " '" + str(e) + "' names `" +
              std::string(port.property) + "` '" + str(axis) + "'; it must be one of " +
              kind.property_iri("x") + ", y or z");
    // A placeholder constant, so the refusal is reported once.
    const int d = synthetic(str(e) + "#" + std::string(port.property),
                            local_name(str(e)) + "_" + std::string(port.property),
                            DataType::Vector3, where(e), "UNITLESS");
    prog_.data[static_cast<size_t>(d)].value = {0.0, 0.0, 0.0};
    return d;
  }
  const int d = synthetic(str(e) + "#" + std::string(port.property),
                          local_name(str(e)) + "_" + std::string(port.property) + "_" + name,
                          DataType::Vector3, where(e), "UNITLESS");
  std::vector<double> v(3, 0.0);
  v[static_cast<size_t>(index)] = 1.0;
  prog_.data[static_cast<size_t>(d)].value = std::move(v);
  return d;
}

// The frame rules of an operator kind, on the quantities a step relates: a
// rule whose two sides are both stated must hold; a side the model leaves
// unstated is not checked (the shapes decide what must be stated).
void Lowerer::check_frames(TermId e, const OperatorKind& kind, const Step& s) {
  const auto quantity = [&](int port) -> const Data& {
    const int d = port < static_cast<int>(s.in.size()) ? s.in[static_cast<size_t>(port)] : s.out[0];
    return prog_.data[static_cast<size_t>(d)];
  };
  const auto field = [](const Data& d, FrameField f) -> const std::string& {
    switch (f) {
      case FrameField::Of:
        return d.of;
      case FrameField::WithRespectTo:
        return d.with_respect_to;
      case FrameField::ReferencePoint:
        return d.reference_point;
      case FrameField::AsSeenBy:
        break;
    }
    return d.as_seen_by;
  };
  for (const FrameRule& rule : kind.frames) {
    const Data& lhs = quantity(rule.lhs_port);
    const Data& rhs = quantity(rule.rhs_port);
    const std::string& got = field(lhs, rule.lhs_field);
    std::string expected = field(rhs, rule.rhs_field);
    if (rule.rhs_origin && !expected.empty()) expected = frame_origin(expected);
    if (got.empty() || expected.empty() || got == expected) continue;
    const std::string lhs_port(kind.port_at(rule.lhs_port).property);
    const std::string rhs_port(kind.port_at(rule.rhs_port).property);
    std::string msg = "the ";
    msg.append(kind.type)
        .append(" '")
        .append(str(e))
        .append("' needs ")
        .append(rule.text)
        .append(": `")
        .append(lhs_port)
        .append("` '")
        .append(lhs.iri)
        .append("' has ")
        .append(to_string(rule.lhs_field))
        .append(" '")
        .append(got)
        .append("', expected '")
        .append(expected)
        .append("' (")
        .append(rule.rhs_origin ? "the origin of " : "")
        .append("the ")
        .append(to_string(rule.rhs_field))
        .append(" of `")
        .append(rhs_port)
        .append("` '")
        .append(rhs.iri)
        .append("')");
    error(where(e, kind.property_iri(lhs_port), term(lhs.iri)), "frame-mismatch", msg);
  }
}

// The origin point of a frame, by the model's `origin` relation ("" if it
// states none).
std::string Lowerer::frame_origin(const std::string& frame) const {
  const TermId f = term(frame);
  if (absent(f)) return {};
  auto o = object(f, vocab("geometry/structural-entities", "origin"));
  return o ? str(*o) : std::string();
}

// AccumulateWrench: every instance that names one `aggregate` adds its
// `element` to it, so the aggregate is the sum of all their elements, added in
// the order of the elements' IRIs (the same sum, to the bit, every time): a
// copy of the first (assign-wrench), then one add-wrench step per other element.
void Lowerer::lower_accumulated_wrenches() {
  const std::string dop = "newtonian-rigid-body-dynamics/operators";
  const std::string prefix = vocab(dop, "");
  struct Term {
    std::string element;
    TermId entity, element_term;
  };
  std::map<std::string, std::vector<Term>> by_aggregate;
  std::map<std::string, TermId> aggregate_term;
  for (TermId e : instances(vocab(dop, "AccumulateWrench"))) {
    pending_iri_ = str(e);
    auto aggregate = object(e, vocab(dop, "aggregate"));
    auto element = object(e, vocab(dop, "element"));
    for (const Graph::Statement& st : g_.statements(e)) {
      const std::string p = str(st.predicate);
      if (!p.starts_with(prefix) || p == vocab(dop, "aggregate") || p == vocab(dop, "element"))
        continue;
      const TermId o = st.object;
      if (p == vocab(dop, "number-of-wrenches") && number(o) == 1.0) continue;
      error(st.where.known() ? st.where : where(e), "unsupported-property",
            "the AccumulateWrench '" + str(e) + "' states `" + p.substr(prefix.size()) +
                "`, which mospec does not implement (it accumulates one wrench per instance: "
                "aggregate, element, and number-of-wrenches 1 at most)");
    }
    if (!aggregate || !element) {
      error(e, "missing-property",
            "the AccumulateWrench '" + str(e) + "' names no `" +
                (aggregate ? "element" : "aggregate") + "`");
      continue;
    }
    by_aggregate[str(*aggregate)].push_back({str(*element), e, *element});
    aggregate_term.emplace(str(*aggregate), *aggregate);
  }
  const int assign = operator_index("assign-wrench"), add = operator_index("add-wrench");
  for (auto& [aggregate_iri, terms] : by_aggregate) {
    std::sort(terms.begin(), terms.end(), [&](const Term& a, const Term& b) {
      return a.element != b.element ? a.element < b.element : str(a.entity) < str(b.entity);
    });
    pending_iri_ = str(terms.front().entity);
    const int aggregate = datum(aggregate_term.at(aggregate_iri), DataType::Wrench,
                                terms.front().entity, "aggregate");
    int sum = -1;
    for (size_t k = 0; k < terms.size(); ++k) {
      const Term& t = terms[k];
      pending_iri_ = str(t.entity);
      const int element = datum(t.element_term, DataType::Wrench, t.entity, "element");
      const Data& a = prog_.data[static_cast<size_t>(aggregate)];
      const Data& el = prog_.data[static_cast<size_t>(element)];
      if (el.reference_point != a.reference_point || el.as_seen_by != a.as_seen_by) {
        error(where(t.entity, vocab(dop, "element"), t.element_term), "frame-mismatch",
              "the AccumulateWrench '" + str(t.entity) + "' adds '" + el.iri + "' (about '" +
                  el.reference_point + "', seen by '" + el.as_seen_by + "') to '" + a.iri +
                  "' (about '" + a.reference_point + "', seen by '" + a.as_seen_by +
                  "'): both must be about one point and seen by one frame");
      }
      const std::string unit = a.unit;  // synthetic() may move prog_.data
      const bool last = k + 1 == terms.size();
      const int target =
          last ? aggregate
               : synthetic(aggregate_iri + "#partial-" + std::to_string(k + 1),
                           local_name(aggregate_iri) + "_partial_" + std::to_string(k + 1),
                           DataType::Wrench, where(t.entity), unit);
      Step s = step_for(StepKind::Operator, t.entity);
      if (k == 0) {
        s.op = assign;
        s.in = {element};
      } else {
        s.op = add;
        s.in = {sum, element};
      }
      s.out = {target};
      add_step(std::move(s));
      sum = target;
    }
  }
}

// PlanarAngleFromDirections: the signed angle from the first to the second
// direction in the xy-plane of the frame both are seen by (about its z axis).
// The vocabulary's from-directions must then be ordered: an RDF list.
void Lowerer::lower_planar_angles() {
  const std::string gop = "geometry/spatial-operators";
  for (TermId e : instances(vocab(gop, "PlanarAngleFromDirections"))) {
    pending_iri_ = str(e);
    Step s = step_for(StepKind::Operator, e);
    s.op = operator_index("planar-angle-from-directions");
    auto dirs = objects(e, vocab(gop, "from-directions"));
    std::vector<TermId> ordered;
    if (dirs.size() == 1) ordered = list(dirs.front());
    auto angle = object(e, vocab(gop, "angle"));
    if (ordered.size() != 2 || !angle) {
      error(e, "unordered-directions",
            "PlanarAngleFromDirections '" + s.iri +
                "' needs `from-directions` as an ordered list of two "
                "directions (\"@list\" in JSON-LD: the angle's sign depends on their order) and an "
                "`angle`");
      continue;
    }
    const int d1 = datum(ordered[0], DataType::Vector3, e, "from-directions");
    const int d2 = datum(ordered[1], DataType::Vector3, e, "from-directions");
    const Data& a = prog_.data[static_cast<size_t>(d1)];
    const Data& b = prog_.data[static_cast<size_t>(d2)];
    if (a.as_seen_by != b.as_seen_by || a.as_seen_by.empty()) {
      error(e, "frame-mismatch",
            "PlanarAngleFromDirections '" + s.iri + "' needs both directions seen by one frame; '" +
                a.iri + "' is seen by '" + a.as_seen_by + "', '" + b.iri + "' by '" + b.as_seen_by +
                "'");
      continue;
    }
    const int normal = synthetic(s.iri + "#normal", local_name(s.iri) + "_normal",
                                 DataType::Vector3, s.where, "UNITLESS");
    prog_.data[static_cast<size_t>(normal)].value = {0.0, 0.0, 1.0};
    prog_.data[static_cast<size_t>(normal)].as_seen_by = a.as_seen_by;
    s.in = {d1, d2, normal};
    s.out = {datum(*angle, DataType::Scalar, e, "angle")};
    add_step(std::move(s));
  }
}

void Lowerer::lower_evaluators() {
  const std::string ch = "task/constraint-handler";
  const std::string cs = "task/constraint";
  std::vector<TermId> evals = instances(vocab(ch, "ErrorEvaluator"));
  for (TermId a : instances(vocab(ch, "AssignmentEvaluator"))) evals.push_back(a);
  for (TermId e : evals) {
    pending_iri_ = str(e);
    const bool assignment = has_type(e, vocab(ch, "AssignmentEvaluator"));
    auto c = object(e, vocab(ch, "constraint"));
    if (!c) {
      error(e, "missing-property", "the evaluator '" + str(e) + "' names no constraint");
      continue;
    }
    if (!defined(*c)) {
      error(where(e, vocab(ch, "constraint"), *c), "undefined-constraint",
            "the evaluator '" + str(e) + "' evaluates '" + str(*c) +
                "', which no model file defines");
      continue;
    }
    auto q = object(*c, vocab(cs, "quantity"));
    if (!q) {
      error(*c, "missing-property", "the constraint '" + str(*c) + "' names no quantity");
      continue;
    }
    Step s = step_for(StepKind::Evaluate, e);
    const int quantity = datum(*q, DataType::Scalar, *c, "quantity");
    const std::string unit = prog_.data[static_cast<size_t>(quantity)].unit;
    // A threshold/reference: a constant with the quantity's unit.
    const auto constant = [&](const std::string& prop) -> std::optional<double> {
      auto t = object(*c, vocab(cs, prop));
      if (!t) return std::nullopt;
      const int d = datum(*t, DataType::Scalar, *c, prop);
      const Data& dd = prog_.data[static_cast<size_t>(d)];
      if (dd.value.empty()) {
        const auto lit = object(*t, kQudt + "value");
        if (lit && g_.terms()[*lit].is_literal()) {
          error(where(*t, kQudt + "value", *lit), "invalid-number",
                "the " + prop + " '" + dd.iri + "' of '" + str(*c) + "' has the value " +
                    literal_text(*lit) + ", which is not a finite number of its datatype");
        } else {
          error(*t, "not-a-constant",
                "the " + prop + " '" + dd.iri + "' of '" + str(*c) + "' has no value");
        }
        return std::nullopt;
      }
      if (dd.unit != unit) {
        error(*t, "wrong-unit",
              "the " + prop + " '" + dd.iri + "' is in '" + dd.unit +
                  "' but the constrained quantity '" +
                  prog_.data[static_cast<size_t>(quantity)].iri + "' is in '" + unit + "'");
      }
      return dd.value[0];
    };
    runtime::ConstraintSpec spec;
    std::optional<int> reference_datum;
    if (has_type(*c, vocab(cs, "BilateralConstraint"))) {
      spec.kind = runtime::ConstraintKind::Bilateral;
      auto lo = constant("lower-threshold"), hi = constant("upper-threshold");
      if (!lo || !hi) {
        // An invalid threshold has been reported by constant(); only a
        // missing one is reported here.
        if (!object(*c, vocab(cs, "lower-threshold")) || !object(*c, vocab(cs, "upper-threshold")))
          error(*c, "missing-property",
                "the bilateral constraint '" + str(*c) + "' needs a lower and an upper threshold");
        continue;
      }
      spec.lower = *lo;
      spec.upper = *hi;
      if (!(spec.lower < spec.upper)) {
        error(*c, "invalid-constraint",
              "the bilateral constraint '" + str(*c) + "' needs lower < upper");
        continue;
      }
    } else if (has_type(*c, vocab(cs, "GreaterThanConstraint")) ||
               has_type(*c, vocab(cs, "LessThanConstraint"))) {
      spec.kind = has_type(*c, vocab(cs, "GreaterThanConstraint"))
                      ? runtime::ConstraintKind::GreaterThan
                      : runtime::ConstraintKind::LessThan;
      auto t = constant("threshold");
      if (!t) {
        if (!object(*c, vocab(cs, "threshold")))
          error(*c, "missing-property", "the constraint '" + str(*c) + "' needs a threshold");
        continue;
      }
      spec.threshold = *t;
      // A timeout: a threshold on a clock's time, which starts at 0 and only
      // grows. A threshold <= 0 s is decided before the first tick (a
      // greater-than constraint holds at once, a less-than never does).
      if (!(spec.threshold > 0.0) && is_clock_time(*q)) {
        const TermId th = *object(*c, vocab(cs, "threshold"));
        const auto lit = object(th, kQudt + "value");
        error(lit ? where(th, kQudt + "value", *lit) : where(th), "invalid-timeout",
              "the timeout '" + str(th) + "' of '" + str(*c) + "' is " +
                  exact_number(spec.threshold) + " s; a threshold on the clock's time '" + str(*q) +
                  "' must be > 0 s");
        continue;
      }
    } else if (has_type(*c, vocab(cs, "EqualityConstraint"))) {
      spec.kind =
          assignment ? runtime::ConstraintKind::Assignment : runtime::ConstraintKind::Equality;
      auto r = constant("reference-value");
      if (!r) {
        if (!object(*c, vocab(cs, "reference-value")))
          error(*c, "missing-property",
                "the equality constraint '" + str(*c) + "' needs a reference-value");
        continue;
      }
      spec.reference = *r;
      if (auto t = object(*c, vocab(cs, "reference-value")))
        reference_datum = data_of_.at(t->index);
    } else {
      error(
          *c, "unsupported-constraint",
          "'" + str(*c) + "' is not an equality, bilateral, greater-than or less-than constraint");
      continue;
    }
    if (assignment && spec.kind != runtime::ConstraintKind::Assignment) {
      error(e, "invalid-evaluator",
            "the assignment evaluator '" + str(e) + "' needs an equality constraint");
      continue;
    }
    s.constraint = spec;
    const int satisfied = synthetic(str(*c) + "#satisfied", local_name(str(*c)) + "_satisfied",
                                    DataType::Flag, where(*c));
    if (spec.kind == runtime::ConstraintKind::Bilateral) {
      bounds_of_satisfied_[satisfied] = {
          data_of_.at(object(*c, vocab(cs, "lower-threshold"))->index),
          data_of_.at(object(*c, vocab(cs, "upper-threshold"))->index)};
    }
    if (assignment) {
      // The quantity is what the evaluator writes: the reference value.
      s.in = {*reference_datum};
      s.out = {satisfied, quantity};
    } else {
      int err = -1;
      if (auto eo = object(e, vocab(ch, "error"))) {
        err = datum(*eo, DataType::Scalar, e, "error");
        s.has_error_output = true;
      } else {
        err = synthetic(str(e) + "#error", local_name(str(e)) + "_error", DataType::Scalar,
                        where(e), unit);
      }
      s.in = {quantity};
      s.out = {satisfied, err};
    }
    const int index = add_step(std::move(s));
    if (evaluator_of_constraint_.count(c->index)) {
      error(e, "evaluated-twice", "the constraint '" + str(*c) + "' has two evaluators");
    }
    evaluator_of_constraint_[c->index] = index;
    evaluate_step_of_evaluator_[e.index] = index;
  }
}

void Lowerer::lower_monitors() {
  const std::string ch = "task/constraint-handler";
  for (const bool edge : {false, true}) {
    for (TermId m : instances(vocab(ch, edge ? "EdgeTriggeredMonitor" : "LevelTriggeredMonitor"))) {
      pending_iri_ = str(m);
      auto err = object(m, vocab(ch, "error"));
      auto out = object(m, vocab(ch, edge ? "event" : "flag"));
      if (!err || !out) {
        error(m, "missing-property",
              std::string("the monitor '") + str(m) + "' needs `error` and `" +
                  (edge ? "event" : "flag") + "`");
        continue;
      }
      Step s;
      s.kind = edge ? StepKind::EdgeMonitor : StepKind::LevelMonitor;
      s.iri = str(m);
      s.name = local_name(s.iri);
      s.where = where(m);
      s.in = {datum(*err, DataType::Scalar, m, "error")};
      // The watched constraint's tolerance (via the evaluator producing the error).
      for (const auto& [eval_term, step] : evaluate_step_of_evaluator_) {
        const Step& ev = steps_[static_cast<size_t>(step)];
        if (ev.out.size() > 1 && ev.out[1] == s.in[0]) s.constraint = ev.constraint;
      }
      const int d = synthetic(str(*out), local_name(str(*out)),
                              edge ? DataType::Event : DataType::Flag, where(*out));
      data_of_[out->index] = d;
      s.out = {d};
      s.state = prog_.states[static_cast<int>(StateKind::Monitor)]++;
      add_step(std::move(s));
    }
  }
}

void Lowerer::lower_handlers() {
  const std::string ch = "task/constraint-handler";
  const std::string mot = "task/motion-specification";
  std::map<uint32_t, int> active_of_motion;
  for (TermId h : instances(vocab(ch, "ConstraintHandler"))) {
    pending_iri_ = str(h);
    auto m = object(h, vocab(ch, "motion"));
    if (!m) continue;
    int active = -1;
    if (auto it = active_of_motion.find(m->index); it != active_of_motion.end()) {
      active = it->second;
    } else {
      Step s = step_for(StepKind::GuardedMotion, *m);
      const auto guards = [&](const std::string& prop) {
        std::vector<int> flags;
        for (TermId c : objects(*m, vocab(mot, prop))) {
          auto it = evaluator_of_constraint_.find(c.index);
          if (it == evaluator_of_constraint_.end()) {
            error(where(*m, vocab(mot, prop), c), "unevaluated-constraint",
                  "the motion '" + str(*m) + "' lists '" + str(c) + "' in `" + prop +
                      "`, but no evaluator evaluates it");
            continue;
          }
          if (prop != "while") flags.push_back(steps_[static_cast<size_t>(it->second)].out[0]);
        }
        return flags;
      };
      const std::vector<int> when = guards("when");
      guards("while");
      const std::vector<int> until = guards("until");
      s.in = when;
      s.in.insert(s.in.end(), until.begin(), until.end());
      s.n_when = static_cast<int>(when.size());
      if (when.size() > static_cast<size_t>(kMaxGuards) ||
          until.size() > static_cast<size_t>(kMaxGuards)) {
        error(*m, "too-many-guards",
              "the motion '" + str(*m) + "' has more than 16 when or until guards");
        continue;
      }
      active = synthetic(str(*m) + "#running", local_name(str(*m)) + "_running", DataType::Flag,
                         where(*m));
      s.out = {active};
      s.state = prog_.states[static_cast<int>(StateKind::Motion)]++;
      add_step(std::move(s));
      active_of_motion[m->index] = active;
    }
    for (TermId c : objects(h, vocab(ch, "controllers"))) active_of_controller_[c.index] = active;
    for (TermId e : objects(h, vocab(ch, "evaluators"))) active_of_evaluator_[e.index] = active;
  }
  // Assignments write only while their motion runs.
  for (auto& [eval, step] : evaluate_step_of_evaluator_) {
    Step& s = steps_[static_cast<size_t>(step)];
    if (s.constraint.kind != runtime::ConstraintKind::Assignment) continue;
    if (auto it = active_of_evaluator_.find(eval); it != active_of_evaluator_.end())
      s.in.push_back(it->second);
  }
}

void Lowerer::lower_controllers() {
  const std::string ch = "task/constraint-handler";
  for (TermId c : instances(vocab(ch, "ProportionalIntegralDerivative"))) {
    pending_iri_ = str(c);
    auto err = object(c, vocab(ch, "error-signal"));
    auto sig = object(c, vocab(ch, "control-signal"));
    if (!err || !sig) {
      error(c, "missing-property",
            "the controller '" + str(c) + "' needs an error-signal and a control-signal");
      continue;
    }
    Step s = step_for(StepKind::Controller, c);
    s.controller = controller_index("pid");
    const ControllerKind& kind = controller_kinds()[static_cast<size_t>(s.controller)];
    s.parameters = kind.defaults();
    const auto set = [&](std::string_view member, double v) {
      s.parameters[static_cast<size_t>(kind.parameter(member))] = v;
    };
    const auto gain = [&](const std::string& p, bool required) {
      const auto lit = object(c, vocab(ch, p));
      auto v = lit ? number(*lit) : std::nullopt;
      if (!v && required && lit && g_.terms()[*lit].is_literal()) {
        error(where(c, vocab(ch, p), *lit), "invalid-number",
              "the controller '" + str(c) + "' has " + p + " " + literal_text(*lit) +
                  ", which is not a finite number of its datatype (xsd:double: e.g. 100, "
                  "+100.0, -1.5e2)");
      } else if (!v && required) {
        error(c, "missing-property", "the controller '" + str(c) + "' needs a numeric " + p);
      }
      return v.value_or(0.0);
    };
    set("kp", gain("proportional-gain", true));
    set("ki", gain("integral-gain", true));
    set("kd", gain("derivative-gain", true));
    if (has_type(c, vocab(ch, "DecayingIntegralTerm")))
      set("decay_rate", gain("decay-rate", true));
    try {
      kind.instantiate(s.parameters, s.iri.c_str());
    } catch (const Error& e) {
      error(c, "invalid-controller", e.diagnostic().message);
    }
    s.in = {datum(*err, DataType::Scalar, c, "error-signal")};
    if (auto it = active_of_controller_.find(c.index); it != active_of_controller_.end())
      s.in.push_back(it->second);
    s.out = {datum(*sig, DataType::Scalar, c, "control-signal")};
    prog_.controller_states.resize(controller_kinds().size());
    s.state = prog_.controller_states[static_cast<size_t>(s.controller)]++;
    add_step(std::move(s));
  }
}

void Lowerer::lower_base() {
  const std::string slv = "task/solver-specification";
  const auto forces = instances(vocab(slv, "ForceDistributionSolver"));
  const auto velocities = instances(vocab(slv, "VelocityCompositionSolver"));
  if (forces.size() > 1)
    error(forces[1], "too-many-bases",
          "mospec's robot has one base; a second force distribution solver '" + str(forces[1]) +
              "' has nothing to drive");
  if (velocities.size() > 1)
    error(velocities[1], "too-many-bases",
          "mospec's robot has one base; a second velocity composition solver '" +
              str(velocities[1]) + "' has nothing to measure");
  if (forces.empty() && velocities.empty()) return;
  BaseSolver base;
  const TermId first = forces.empty() ? velocities.front() : forces.front();
  base.iri = str(first);
  base.name = identifier(local_name(base.iri));
  base.where = where(first);
  base.geometry = runtime::KeloGeometry::paper();
  // A platform quantity must be at the origin of the frame it is seen by.
  const auto at_frame_origin = [&](const Data& q) {
    std::string origin;
    if (auto frame = term(q.as_seen_by); !absent(frame)) {
      if (auto o = object(frame, vocab("geometry/structural-entities", "origin"))) origin = str(*o);
    }
    return !origin.empty() && q.reference_point == origin;
  };
  // One platform quantity per solver: the twist it composes, the wrench it
  // distributes; each at the origin of the frame it is seen by (the platform's).
  std::vector<Step> new_steps;
  const auto platform_step = [&](TermId solver, const char* property, DataType type, StepKind kind,
                                 int& field) {
    pending_iri_ = str(solver);
    auto q = object(solver, vocab(slv, property));
    if (!q) {
      error(solver, "missing-property", "the solver '" + str(solver) + "' names no " + property);
      return;
    }
    field = datum(*q, type, solver, property);
    const Data& d = prog_.data[static_cast<size_t>(field)];
    if (!at_frame_origin(d)) {
      error(*q, "frame-mismatch",
            "the platform " + std::string(to_string(type)) + " '" + d.iri +
                "' must be at the origin of the frame it is seen by (the platform's); it is at '" +
                d.reference_point + "' seen by '" + d.as_seen_by + "'");
    }
    Step s = step_for(kind, solver);
    (kind == StepKind::BaseVelocityComposition ? s.out : s.in) = {field};
    new_steps.push_back(std::move(s));
  };
  if (!velocities.empty()) {
    platform_step(velocities.front(), "velocity", DataType::Twist,
                  StepKind::BaseVelocityComposition, base.twist);
  }
  if (!forces.empty()) {
    platform_step(forces.front(), "force", DataType::Wrench, StepKind::BaseForceDistribution,
                  base.wrench);
  }
  prog_.base = std::move(base);
  for (Step& s : new_steps) add_step(std::move(s));
}

void Lowerer::lower_views() {
  const std::string map = "task/map";
  struct ViewInfo {
    TermId view, super, sub;
    int index = 0;
    DataType super_type = DataType::Pose;
  };
  std::vector<ViewInfo> views;
  for (TermId v : instances(vocab(map, "View"))) {
    auto super = object(v, vocab(map, "superobject"));
    auto sub = object(v, vocab(map, "subobject"));
    auto space = object(v, vocab(map, "subspace"));
    auto axis = object(v, vocab(map, "axis"));
    if (!super || !sub || !space || !axis) {
      error(v, "missing-property",
            "the view '" + str(v) + "' needs superobject, subobject, subspace and axis");
      continue;
    }
    ViewInfo info{v, *super, *sub};
    const std::string sp = local_name(str(*space)), ax = local_name(str(*axis));
    const int a = ax == "x" ? 0 : ax == "y" ? 1 : ax == "z" ? 2 : -1;
    int base = -1;
    if (has_type(v, vocab(map, "PoseCoordinateView"))) {
      info.super_type = DataType::Pose;
      base = sp == "orientation" || sp == "rotation" ? 0 : sp == "position" ? 3 : -1;
    } else if (has_type(v, vocab(map, "VelocityTwistCoordinateView"))) {
      info.super_type = DataType::Twist;
      base = sp == "angular-velocity" ? 0 : sp == "linear-velocity" ? 3 : -1;
    } else if (has_type(v, vocab(map, "WrenchCoordinateView"))) {
      info.super_type = DataType::Wrench;
      base = sp == "torque" || sp == "moment" ? 0 : sp == "force" ? 3 : -1;
    }
    if (base < 0 || a < 0) {
      error(v, "invalid-view",
            "the view '" + str(v) + "' has subspace '" + sp + "' and axis '" + ax +
                "', which mospec cannot read");
      continue;
    }
    info.index = base + a;
    views.push_back(info);
  }
  // Direction: a view reads when its superobject is produced, writes when its
  // subobject is. Writes into one superobject become one step.
  std::vector<char> done(views.size(), 0);
  for (bool progress = true; progress;) {
    progress = false;
    std::map<uint32_t, std::vector<size_t>> writes;
    for (size_t i = 0; i < views.size(); ++i) {
      if (done[i]) continue;
      const ViewInfo& v = views[i];
      pending_iri_ = str(v.view);
      const int super = datum(v.super, v.super_type, v.view, "superobject");
      const int sub = datum(v.sub, DataType::Scalar, v.view, "subobject");
      if (produced(super)) {
        Step s;
        s.kind = StepKind::ViewRead;
        s.iri = str(v.view);
        s.name = local_name(s.iri);
        s.where = where(v.view);
        s.in = {super};
        s.out = {sub};
        s.views = {v.index};
        add_step(std::move(s));
        done[i] = 1;
        progress = true;
      } else if (produced(sub) && v.super_type != DataType::Pose) {
        writes[v.super.index].push_back(i);
      }
    }
    for (auto& [super_term, list] : writes) {
      Step s;
      s.kind = StepKind::ViewWrite;
      const ViewInfo& first = views[list.front()];
      s.iri = str(first.super);
      s.name = "assemble_" + local_name(s.iri);
      s.where = where(first.view);
      for (size_t i : list) {
        s.in.push_back(datum(views[i].sub, DataType::Scalar, views[i].view, "subobject"));
        s.views.push_back(views[i].index);
        done[i] = 1;
      }
      s.out = {datum(first.super, first.super_type, first.view, "superobject")};
      add_step(std::move(s));
      progress = true;
    }
  }
  for (size_t i = 0; i < views.size(); ++i) {
    if (done[i]) continue;
    error(views[i].view, "unproduced-quantity",
          "the view '" + str(views[i].view) + "': nothing produces its superobject '" +
              str(views[i].super) + "' or its subobject '" + str(views[i].sub) + "'");
    done[i] = 1;
  }
}

// Which motions drive each arm and the base: the running flags gating the controllers and
// assignments whose outputs reach the arm's drivers, through any operators.
void Lowerer::gate_arm_solves() {
  for (Step& solve : steps_) {
    if (solve.kind != StepKind::ArmSolve && solve.kind != StepKind::BaseForceDistribution) continue;
    solve.n_drivers = static_cast<int>(solve.in.size());
    std::set<int> gates, seen_data;
    std::vector<int> todo(solve.in.begin(), solve.in.end());
    while (!todo.empty()) {
      const int d = todo.back();
      todo.pop_back();
      if (!seen_data.insert(d).second) continue;
      auto it = producer_.find(d);
      if (it == producer_.end() || it->second < 0) continue;
      const Step& p = steps_[static_cast<size_t>(it->second)];
      const bool gated =
          (p.kind == StepKind::Controller && p.in.size() == 2) ||
          (p.kind == StepKind::Evaluate &&
           p.constraint.kind == runtime::ConstraintKind::Assignment && p.in.size() == 2);
      if (gated) gates.insert(p.in[1]);
      if (p.kind == StepKind::GuardedMotion || p.kind == StepKind::ArmKinematics ||
          p.kind == StepKind::BaseVelocityComposition)
        continue;
      for (size_t k = 0; k < p.in.size(); ++k) {
        if (gated && k == 1) continue;
        todo.push_back(p.in[k]);
      }
    }
    solve.in.insert(solve.in.end(), gates.begin(), gates.end());
  }
}

void Lowerer::check_inputs() {
  for (const Step& s : steps_) {
    for (int d : s.in) {
      if (produced(d)) continue;
      const Data& dd = prog_.data[static_cast<size_t>(d)];
      std::string msg = "nothing produces '";
      msg.append(dd.iri).append("', which '").append(s.iri).append("' needs");
      error(dd.where.known() ? dd.where : s.where, "unproduced-quantity", msg);
      producer_.emplace(d, -1);  // report once
    }
  }
}

void Lowerer::schedule() {
  const size_t n = steps_.size();
  std::vector<std::vector<size_t>> next(n);
  std::vector<int> waiting(n, 0);
  for (size_t i = 0; i < n; ++i) {
    for (int d : steps_[i].in) {
      auto it = producer_.find(d);
      if (it == producer_.end() || it->second < 0) continue;
      next[static_cast<size_t>(it->second)].push_back(i);
      ++waiting[i];
    }
  }
  // Kahn's algorithm, always taking the earliest-declared ready step: the
  // order is a function of the model only.
  std::set<size_t> ready;
  for (size_t i = 0; i < n; ++i) {
    if (waiting[i] == 0) ready.insert(i);
  }
  std::vector<size_t> order;
  while (!ready.empty()) {
    const size_t i = *ready.begin();
    ready.erase(ready.begin());
    order.push_back(i);
    for (size_t j : next[i]) {
      if (--waiting[j] == 0) ready.insert(j);
    }
  }
  if (order.size() != n) {
    for (size_t i = 0; i < n; ++i) {
      if (waiting[i] > 0) {
        error(steps_[i].where, "cycle",
              "'" + steps_[i].iri + "' (" + std::string(kind_name(steps_[i])) +
                  ") is on a dependency cycle: each quantity on it needs another one of them in "
                  "the same tick");
      }
    }
    return;
  }
  for (size_t i : order) prog_.steps.push_back(steps_[i]);
}

void Lowerer::build_log() {
  for (const Step& s : prog_.steps) {
    const auto add = [&](const std::string& suffix, int d) {
      const Data& dd = prog_.data[static_cast<size_t>(d)];
      std::string name = local_name(s.iri);
      if (s.kind == StepKind::Evaluate) name = local_name(dd.iri.substr(0, dd.iri.find('#')));
      prog_.log.push_back({name + suffix, dd.unit, d});
    };
    switch (s.kind) {
      case StepKind::Evaluate: {
        const bool assignment = s.constraint.kind == runtime::ConstraintKind::Assignment;
        const Data& sat = prog_.data[static_cast<size_t>(s.out[0])];
        const std::string cname = local_name(sat.iri.substr(0, sat.iri.find('#')));
        const Data& value = prog_.data[static_cast<size_t>(assignment ? s.out[1] : s.in[0])];
        prog_.log.push_back({cname + ".value", value.unit, assignment ? s.out[1] : s.in[0]});
        if (!assignment)
          prog_.log.push_back(
              {cname + ".error", prog_.data[static_cast<size_t>(s.out[1])].unit, s.out[1]});
        prog_.log.push_back({cname + ".satisfied", "", s.out[0]});
        if (auto it = bounds_of_satisfied_.find(s.out[0]); it != bounds_of_satisfied_.end()) {
          prog_.log.push_back({cname + ".lower", value.unit, it->second.first});
          prog_.log.push_back({cname + ".upper", value.unit, it->second.second});
        }
        break;
      }
      case StepKind::BaseVelocityComposition: {
        // The platform's measured planar twist [v_x, v_y, w_z].
        const std::string base = local_name(s.iri);
        prog_.log.push_back({base + ".vx", "M-PER-SEC", s.out[0], 3});
        prog_.log.push_back({base + ".vy", "M-PER-SEC", s.out[0], 4});
        prog_.log.push_back({base + ".wz", "RAD-PER-SEC", s.out[0], 2});
        break;
      }
      case StepKind::BaseForceDistribution: {
        // The platform wrench [f_x, f_y, m_z] the drives are to exert.
        const std::string base = local_name(s.iri);
        prog_.log.push_back({base + ".fx", "N", s.in[0], 3});
        prog_.log.push_back({base + ".fy", "N", s.in[0], 4});
        prog_.log.push_back({base + ".mz", "N-M", s.in[0], 2});
        break;
      }
      case StepKind::LevelMonitor:
        add(".flag", s.out[0]);
        break;
      case StepKind::EdgeMonitor:
        add(".event", s.out[0]);
        break;
      case StepKind::GuardedMotion:
        add(".running", s.out[0]);
        break;
      case StepKind::Controller:
        add(".output", s.out[0]);
        break;
      default:
        break;
    }
  }
}

using Pass = void (Lowerer::*)();
struct PassInfo {
  std::string_view name;
  Pass run;
};

// Lowering's passes, in order: what each lowers is in its name.
const PassInfo kPasses[] = {
    {"clocks", &Lowerer::lower_clocks},
    {"arm-solvers", &Lowerer::lower_arms},
    {"operators", &Lowerer::lower_operators},
    {"accumulated-wrenches", &Lowerer::lower_accumulated_wrenches},
    {"planar-angles", &Lowerer::lower_planar_angles},
    {"base", &Lowerer::lower_base},
    {"evaluators", &Lowerer::lower_evaluators},
    {"monitors", &Lowerer::lower_monitors},
    {"handlers", &Lowerer::lower_handlers},
    {"controllers", &Lowerer::lower_controllers},
    {"views", &Lowerer::lower_views},
    {"motion-gates", &Lowerer::gate_arm_solves},
    {"producers", &Lowerer::check_inputs},
    {"schedule", &Lowerer::schedule},
    {"log", &Lowerer::build_log},
};

Program Lowerer::run() {
  for (const app::ModelFile& f : model_.model_files()) {
    if (f.is_app) {
      prog_.app = f.iri;
      break;
    }
  }
  for (const PassInfo& pass : kPasses) {
    (this->*pass.run)();
    if (!errors_.empty()) {
      // Later passes would only report what follows from these problems,
      // except that every missing producer is worth knowing at once.
      if (pass.name == "schedule" || pass.name == "producers" || pass.name == "log") break;
      continue;
    }
    // Until "schedule" orders them, the steps so far are in steps_, in
    // declaration order: lend them to the program for the check.
    const bool ordered = pass.name == "schedule" || pass.name == "log";
    if (!ordered) std::swap(prog_.steps, steps_);
    auto problems = check(prog_, &model_.files(), ordered ? Stage::Scheduled : Stage::Unscheduled);
    if (options_.after_pass) options_.after_pass(pass.name, prog_);
    if (!ordered) std::swap(prog_.steps, steps_);
    if (!problems.empty()) {
      for (Diagnostic& d : problems)
        d.message = "after lowering pass '" + std::string(pass.name) + "': " + d.message;
      throw VerifyError(std::move(problems));
    }
  }
  if (!errors_.empty()) throw LowerError(std::move(errors_));
  return std::move(prog_);
}

void Lowerer::lower_arms() {
  for (TermId s : instances(vocab("task/solver-specification", "SolverWithInputAndOutput")))
    lower_arm(s);
}

}  // namespace

Program lower(const app::LoadedModel& model, const LowerOptions& options) {
  return Lowerer(model, options).run();
}

}  // namespace mospec::ir

namespace mospec::ir {

std::span<const std::string_view> lowering_passes() {
  static const std::vector<std::string_view> names = [] {
    std::vector<std::string_view> out;
    for (const PassInfo& p : kPasses) out.push_back(p.name);
    return out;
  }();
  return names;
}

}  // namespace mospec::ir
