#include "description/chain_rdf.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "support/diagnostics.hpp"
#include "vocab/metamodels.hpp"
#include "vocab/w3c.hpp"

namespace mospec::description {

using namespace mospec::runtime;

namespace {

constexpr std::string_view kRdf = vocab::rdf::ns;
constexpr std::string_view kUnit = vocab::qudt_unit::ns;

std::string iri(std::string_view ns, std::string_view local) {
  return vocab::term(ns, local);
}

// The vocabulary terms a chain is read through, each looked up once per
// Reader (Reader::id) instead of spelled and looked up per statement read.
enum class V : uint8_t {
  type,
  first,
  rest,
  nil,
  unit,  // rdf, qudt
  KinematicChain,
  joints,
  RevoluteJoint,
  PrismaticJoint,  // mospec/joints
  between_attachments,
  common_axis,  // kc
  Pose,
  Position,
  of,
  with_respect_to,  // geom-rel
  x,
  y,
  z,
  direction_cosine_x,
  direction_cosine_y,
  direction_cosine_z,  // geom-coord
  origin,
  simplices,  // geom-ent
  RotationalInertia,
  about,
  of_body,
  Mass,  // dyn-ent
  as_seen_by,
  ixx,
  ixy,
  ixz,
  iyy,
  iyz,
  izz,
  mass,  // dyn-coord
  count
};
constexpr size_t kVocabSize = static_cast<size_t>(V::count);

const std::string& text(V v) {
  static const std::array<std::string, kVocabSize> iris = [] {
    std::array<std::string, kVocabSize> a;
    const auto set = [&](V k, std::string_view ns, std::string_view local) {
      a[static_cast<size_t>(k)] = iri(ns, local);
    };
    set(V::type, kRdf, "type");
    set(V::first, kRdf, "first");
    set(V::rest, kRdf, "rest");
    set(V::nil, kRdf, "nil");
    set(V::unit, vocab::qudt::ns, "unit");
    set(V::KinematicChain, vocab::kc_ent::ns, "KinematicChain");
    set(V::joints, vocab::kc_ent::ns, "joints");
    set(V::RevoluteJoint, vocab::kc_ent::ns, "RevoluteJoint");
    set(V::PrismaticJoint, vocab::mospec_joints::ns, "PrismaticJoint");
    set(V::between_attachments, vocab::kc_ent::ns, "between-attachments");
    set(V::common_axis, vocab::kc_ent::ns, "common-axis");
    set(V::Pose, vocab::geom_rel::ns, "Pose");
    set(V::Position, vocab::geom_rel::ns, "Position");
    set(V::of, vocab::geom_rel::ns, "of");
    set(V::with_respect_to, vocab::geom_rel::ns, "with-respect-to");
    set(V::x, vocab::geom_coord::ns, "x");
    set(V::y, vocab::geom_coord::ns, "y");
    set(V::z, vocab::geom_coord::ns, "z");
    set(V::direction_cosine_x, vocab::geom_coord::ns, "direction-cosine-x");
    set(V::direction_cosine_y, vocab::geom_coord::ns, "direction-cosine-y");
    set(V::direction_cosine_z, vocab::geom_coord::ns, "direction-cosine-z");
    set(V::origin, vocab::geom_ent::ns, "origin");
    set(V::simplices, vocab::geom_ent::ns, "simplices");
    set(V::RotationalInertia, vocab::dyn_ent::ns, "RotationalInertia");
    set(V::about, vocab::dyn_ent::ns, "about");
    set(V::of_body, vocab::dyn_ent::ns, "of-body");
    set(V::Mass, vocab::dyn_ent::ns, "Mass");
    set(V::as_seen_by, vocab::dyn_coord::ns, "as-seen-by");
    set(V::ixx, vocab::dyn_coord::ns, "ixx");
    set(V::ixy, vocab::dyn_coord::ns, "ixy");
    set(V::ixz, vocab::dyn_coord::ns, "ixz");
    set(V::iyy, vocab::dyn_coord::ns, "iyy");
    set(V::iyz, vocab::dyn_coord::ns, "iyz");
    set(V::izz, vocab::dyn_coord::ns, "izz");
    set(V::mass, vocab::dyn_coord::ns, "mass");
    return a;
  }();
  return iris[static_cast<size_t>(v)];
}

// Reads a chain from a dataset: all of it, or (filtered) only the union of
// some of its graphs as a set of triples, read in place: a triple stated in
// several of those graphs counts once, at its first statement.
class Reader {
 public:
  explicit Reader(const rdf::Dataset& g) : g_(g) {}
  Reader(const rdf::Dataset& g, std::span<const rdf::TermId> graphs)
      : g_(g), graphs_(graphs.begin(), graphs.end()), filtered_(true) {}

  std::string name(rdf::TermId t) const {
    const auto& term = g_.terms()[t];
    return term.is_iri() ? std::string(term.value) : "_:" + std::string(term.value);
  }
  rdf::TermId id(std::string_view iri_text) const { return g_.terms().find_iri(iri_text); }
  rdf::TermId id(V v) const {
    rdf::TermId& t = ids_[static_cast<size_t>(v)];
    if (t == kUnknown) t = id(text(v));
    return t;
  }

  std::vector<rdf::TermId> objects(rdf::TermId s, V p) const {
    std::vector<rdf::TermId> out;
    const rdf::TermId pid = id(p);
    if (pid.is_any()) return out;
    g_.scan(s, pid, rdf::TermId::any(), rdf::TermId::any(), [&](const rdf::Quad& q, uint32_t) {
      if (!filtered_) {
        out.push_back(q.object);
      } else if (read(q) && std::find(out.begin(), out.end(), q.object) == out.end()) {
        out.push_back(q.object);
      }
      return true;
    });
    return out;
  }
  std::vector<rdf::TermId> subjects(V p, rdf::TermId o) const {
    std::vector<rdf::TermId> out;
    const rdf::TermId pid = id(p);
    if (pid.is_any()) return out;
    g_.scan(rdf::TermId::any(), pid, o, rdf::TermId::any(), [&](const rdf::Quad& q, uint32_t) {
      if (!filtered_) {
        out.push_back(q.subject);
      } else if (read(q) && std::find(out.begin(), out.end(), q.subject) == out.end()) {
        out.push_back(q.subject);
      }
      return true;
    });
    return out;
  }
  bool has_type(rdf::TermId s, V type) const {
    const rdf::TermId p = id(V::type), t = id(type);
    if (p.is_any() || t.is_any()) return false;
    if (!filtered_) return g_.count(s, p, t, rdf::TermId::any(), 1) > 0;
    for (rdf::TermId g : graphs_)
      if (g_.count(s, p, t, g, 1) > 0) return true;
    return false;
  }
  rdf::TermId one(rdf::TermId s, V p) const {
    const auto os = objects(s, p);
    if (os.size() != 1) {
      throw Error("invalid-robot-model", name(s) + ": expected exactly one <" + text(p) +
                                             ">, found " + std::to_string(os.size()));
    }
    return os.front();
  }
  double number(rdf::TermId s, V p) const { return to_double(s, p, one(s, p)); }
  double to_double(rdf::TermId s, V p, rdf::TermId o) const {
    const auto& term = g_.terms()[o];
    double v = 0.0;
    if (term.is_literal()) {
      const auto r = std::from_chars(term.value.data(), term.value.data() + term.value.size(), v);
      if (r.ec == std::errc() && r.ptr == term.value.data() + term.value.size()) return v;
    }
    throw Error("invalid-robot-model", name(s) + ": <" + text(p) + "> is not a number");
  }
  std::vector<double> number_list(rdf::TermId s, V p) const {
    std::vector<double> out;
    const rdf::TermId nil = id(V::nil);
    for (rdf::TermId node = one(s, p); node != nil; node = one(node, V::rest)) {
      out.push_back(to_double(s, p, one(node, V::first)));
      if (out.size() > 16) break;
    }
    return out;
  }
  // The QUDT units of `s` must be exactly `want` (a set).
  void require_units(rdf::TermId s, std::vector<std::string_view> want) const {
    std::vector<std::string> got;
    for (rdf::TermId u : objects(s, V::unit)) got.push_back(name(u));
    std::sort(got.begin(), got.end());
    std::vector<std::string> expected;
    for (auto w : want) expected.push_back(iri(kUnit, w));
    std::sort(expected.begin(), expected.end());
    expected.erase(std::unique(expected.begin(), expected.end()), expected.end());
    if (got != expected) {
      std::string g;
      for (const auto& u : got) g += (g.empty() ? "" : ", ") + u;
      std::string e;
      for (const auto& u : expected) e += (e.empty() ? "" : ", ") + u;
      throw Error("invalid-robot-model",
                  name(s) + ": unit must be {" + e + "}, got {" + (g.empty() ? "none" : g) + "}");
    }
  }

  Pose pose(rdf::TermId p) const {
    require_units(p, {"UNITLESS", "M"});
    Pose X;
    const char* keys[] = {"direction-cosine-x", "direction-cosine-y", "direction-cosine-z"};
    const V columns[] = {V::direction_cosine_x, V::direction_cosine_y, V::direction_cosine_z};
    for (int c = 0; c < 3; ++c) {
      const auto col = number_list(p, columns[c]);
      if (col.size() != 3) {
        throw Error("invalid-robot-model", name(p) + ": " + keys[c] + " must have 3 entries, got " +
                                               std::to_string(col.size()));
      }
      X.R.col(c) = Vec3(col[0], col[1], col[2]);
    }
    X.p = Vec3(number(p, V::x), number(p, V::y), number(p, V::z));
    return X;
  }

  // The Pose node "of" frame f, if any.
  std::optional<rdf::TermId> pose_of(rdf::TermId f) const {
    for (rdf::TermId s : subjects(V::of, f)) {
      if (has_type(s, V::Pose)) return s;
    }
    return std::nullopt;
  }

  // Inertia of the link whose frame is `frame`: the RotationalInertia seen by
  // it, about a point whose Position (seen by the frame) is the CoM, plus the
  // Mass of the same body. No inertia node: a massless link.
  RigidInertia inertia(rdf::TermId frame) const {
    RigidInertia I;
    for (rdf::TermId r : subjects(V::as_seen_by, frame)) {
      if (!has_type(r, V::RotationalInertia)) continue;
      require_units(r, {"KiloGM-M2"});
      const auto c = [&](V k) { return number(r, k); };
      I.I_Scm_S << c(V::ixx), c(V::ixy), c(V::ixz), c(V::ixy), c(V::iyy), c(V::iyz), c(V::ixz),
          c(V::iyz), c(V::izz);
      const rdf::TermId com = one(r, V::about);
      bool found = false;
      for (rdf::TermId p : subjects(V::of, com)) {
        if (!has_type(p, V::Position)) continue;
        require_units(p, {"M"});
        I.p_SoScm_S = Vec3(number(p, V::x), number(p, V::y), number(p, V::z));
        found = true;
      }
      if (!found) {
        throw Error("invalid-robot-model", name(r) + ": no Position of its point " + name(com));
      }
      const rdf::TermId body = one(r, V::of_body);
      found = false;
      for (rdf::TermId m : subjects(V::of_body, body)) {
        if (!has_type(m, V::Mass)) continue;
        require_units(m, {"KiloGM"});
        I.mass = number(m, V::mass);
        found = true;
      }
      if (!found) throw Error("invalid-robot-model", name(body) + ": has inertia but no Mass");
      return I;
    }
    return I;
  }

  // Whether a quad is in the graphs read.
  bool read(const rdf::Quad& q) const {
    return !filtered_ || std::find(graphs_.begin(), graphs_.end(), q.graph) != graphs_.end();
  }

  static std::string local_name(const std::string& iri_text, std::string_view prefix) {
    std::string s = iri_text.substr(iri_text.find_last_of("/#") + 1);
    if (s.rfind(prefix, 0) == 0) s = s.substr(prefix.size());
    return s;
  }

 private:
  const rdf::Dataset& g_;
  std::vector<rdf::TermId> graphs_;  // filtered_: the graphs read
  bool filtered_ = false;
  // id(V): unknown until first asked (any() is "not in the dataset").
  static constexpr rdf::TermId kUnknown{UINT32_MAX - 1};
  mutable std::array<rdf::TermId, kVocabSize> ids_ = [] {
    std::array<rdf::TermId, kVocabSize> a;
    a.fill(kUnknown);
    return a;
  }();
};

ChainDescription describe(const Reader& r, std::string_view chain_iri);

}  // namespace

Chain chain_from_rdf(const rdf::Dataset& graph, std::string_view chain_iri) {
  return describe_chain(graph, chain_iri).chain;
}

ChainDescription describe_chain(const rdf::Dataset& graph, std::string_view chain_iri) {
  return describe(Reader(graph), chain_iri);
}

ChainDescription describe_chain(const rdf::Dataset& dataset, std::span<const rdf::TermId> graphs,
                                std::string_view chain_iri) {
  return describe(Reader(dataset, graphs), chain_iri);
}

namespace {

ChainDescription describe(const Reader& r, std::string_view chain_iri) {
  const rdf::TermId chain_id = r.id(chain_iri);
  if (chain_id.is_any() || !r.has_type(chain_id, V::KinematicChain)) {
    throw Error("invalid-robot-model",
                "no KinematicChain named <" + std::string(chain_iri) + "> in the model");
  }
  struct JointInfo {
    rdf::TermId joint, attachment, child, parent_frame, pose;
    JointType type;
  };
  std::map<rdf::TermId, JointInfo> by_parent_frame;
  std::map<rdf::TermId, rdf::TermId> child_frames;  // child frame -> joint
  for (rdf::TermId j : r.objects(chain_id, V::joints)) {
    const bool revolute = r.has_type(j, V::RevoluteJoint);
    if (revolute == r.has_type(j, V::PrismaticJoint)) {
      throw Error("invalid-robot-model",
                  r.name(j) +
                      (revolute ? ": is both a RevoluteJoint and a PrismaticJoint"
                                : ": only RevoluteJoint and PrismaticJoint (mospec/joints) "
                                  "are supported") +
                      "; state exactly one of them");
    }
    const auto at = r.objects(j, V::between_attachments);
    if (at.size() != 2) {
      throw Error("invalid-robot-model",
                  r.name(j) + ": expected 2 between-attachments, got " + std::to_string(at.size()));
    }
    // The parent-side attachment is the one placed by a Pose.
    const auto p0 = r.pose_of(at[0]), p1 = r.pose_of(at[1]);
    if (p0.has_value() == p1.has_value()) {
      throw Error("invalid-robot-model",
                  r.name(j) + ": exactly one attachment needs a Pose relative to its parent link");
    }
    JointInfo info{j, p0 ? at[0] : at[1], p0 ? at[1] : at[0], {}, p0 ? *p0 : *p1, {}};
    info.type = revolute ? JointType::Revolute : JointType::Prismatic;
    info.parent_frame = r.one(info.pose, V::with_respect_to);
    if (!by_parent_frame.emplace(info.parent_frame, info).second) {
      throw Error("invalid-robot-model",
                  r.name(info.parent_frame) + ": two joints start here; a chain cannot branch");
    }
    child_frames.emplace(info.child, j);
  }
  if (by_parent_frame.empty()) throw Error("invalid-robot-model", r.name(chain_id) + ": no joints");
  std::vector<rdf::TermId> roots;
  for (const auto& [frame, info] : by_parent_frame) {
    if (!child_frames.count(frame)) roots.push_back(frame);
  }
  if (roots.size() != 1) {
    throw Error("invalid-robot-model", r.name(chain_id) + ": the joints form " +
                                           std::to_string(roots.size()) +
                                           " chains; expected one serial chain");
  }
  ChainDescription out{Chain(Reader::local_name(r.name(roots.front()), "frame-")), {}};
  Chain& chain = out.chain;
  // A frame's origin point and the body it is attached to, by the model's
  // relations: the frame's `origin`; the simplicial complex (link) whose
  // `simplices` hold the frame, else the body whose inertia the frame sees.
  const auto unique = [](std::vector<rdf::TermId> v) {
    std::sort(v.begin(), v.end(), [](rdf::TermId a, rdf::TermId b) { return a.index < b.index; });
    v.erase(std::unique(v.begin(), v.end()), v.end());
    return v;
  };
  const auto origin_of = [&](rdf::TermId f) {
    const auto o = unique(r.objects(f, V::origin));
    return o.size() == 1 ? r.name(o.front()) : std::string();
  };
  const auto body_of = [&](rdf::TermId f) {
    const auto complexes = unique(r.subjects(V::simplices, f));
    if (complexes.size() == 1) return r.name(complexes.front());
    for (rdf::TermId i : r.subjects(V::as_seen_by, f)) {
      if (!r.has_type(i, V::RotationalInertia)) continue;
      const auto bodies = unique(r.objects(i, V::of_body));
      if (bodies.size() == 1) return r.name(bodies.front());
    }
    return std::string();
  };
  out.frames.root = {r.name(roots.front()), origin_of(roots.front()), body_of(roots.front()), {}};
  rdf::TermId frame = roots.front();
  for (auto it = by_parent_frame.find(frame); it != by_parent_frame.end();
       it = by_parent_frame.find(frame)) {
    const JointInfo& info = it->second;
    Segment s;
    s.joint = Reader::local_name(r.name(info.joint), "joint-");
    s.link = Reader::local_name(r.name(info.child), "frame-");
    s.type = info.type;
    s.X_PJ = r.pose(info.pose);
    const rdf::TermId axis = r.one(info.joint, V::common_axis);
    s.axis_J = Vec3(r.number(axis, V::x), r.number(axis, V::y), r.number(axis, V::z));
    s.inertia = r.inertia(info.child);
    chain.add_segment(std::move(s));
    out.frames.segments.push_back(
        {r.name(info.child), origin_of(info.child), body_of(info.child), r.name(info.joint)});
    frame = info.child;
    by_parent_frame.erase(it);
  }
  if (!by_parent_frame.empty()) {
    throw Error("invalid-robot-model", r.name(chain_id) + ": " +
                                           std::to_string(by_parent_frame.size()) +
                                           " joints are not on the chain from its root");
  }
  // The tip: a frame posed relative to the last link's frame, if any.
  std::vector<rdf::TermId> tips;
  for (rdf::TermId p : r.subjects(V::with_respect_to, frame)) {
    if (r.has_type(p, V::Pose)) tips.push_back(p);
  }
  if (tips.size() > 1) {
    throw Error("invalid-robot-model", r.name(frame) + ": more than one tip frame is posed here");
  }
  if (!tips.empty()) {
    const rdf::TermId tip = r.one(tips.front(), V::of);
    chain.add_fixed(Reader::local_name(r.name(tip), "frame-"), r.pose(tips.front()), {});
  }
  return out;
}

}  // namespace

}  // namespace mospec::description
