#include "description/chain_rdf.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <initializer_list>
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
  UNITLESS,
  M,
  KiloGM_M2,
  KiloGM,  // qudt units
  of_joint,
  JointLimit,
  lower,
  upper,  // kc-ext
  JointPosition,
  JointVelocity,
  JointAcceleration,
  JointForce,  // kc-stat: what a JointLimit limits
  value,       // qudt
  old_of_joint,
  JointPositionLimits,
  JointVelocityLimit,
  JointEffortLimit,  // mospec/joints: retired for kc-ext:JointLimit
  RAD,
  M_PER_SEC,
  RAD_PER_SEC,
  N,
  N_M,  // qudt units
  count
};
constexpr size_t kVocabSize = static_cast<size_t>(V::count);

// Each term's namespace and local name, in V's order: the IRI is spelled
// (into a stack buffer) only when looked up once per Reader, or for an error.
struct Term {
  std::string_view ns, local;
};
constexpr std::array<Term, kVocabSize> kTerms{{
    {kRdf, "type"},
    {kRdf, "first"},
    {kRdf, "rest"},
    {kRdf, "nil"},
    {vocab::qudt::ns, "unit"},
    {vocab::kc_ent::ns, "KinematicChain"},
    {vocab::kc_ent::ns, "joints"},
    {vocab::kc_ent::ns, "RevoluteJoint"},
    {vocab::mospec_joints::ns, "PrismaticJoint"},
    {vocab::kc_ent::ns, "between-attachments"},
    {vocab::kc_ent::ns, "common-axis"},
    {vocab::geom_rel::ns, "Pose"},
    {vocab::geom_rel::ns, "Position"},
    {vocab::geom_rel::ns, "of"},
    {vocab::geom_rel::ns, "with-respect-to"},
    {vocab::geom_coord::ns, "x"},
    {vocab::geom_coord::ns, "y"},
    {vocab::geom_coord::ns, "z"},
    {vocab::geom_coord::ns, "direction-cosine-x"},
    {vocab::geom_coord::ns, "direction-cosine-y"},
    {vocab::geom_coord::ns, "direction-cosine-z"},
    {vocab::geom_ent::ns, "origin"},
    {vocab::geom_ent::ns, "simplices"},
    {vocab::dyn_ent::ns, "RotationalInertia"},
    {vocab::dyn_ent::ns, "about"},
    {vocab::dyn_ent::ns, "of-body"},
    {vocab::dyn_ent::ns, "Mass"},
    {vocab::dyn_coord::ns, "as-seen-by"},
    {vocab::dyn_coord::ns, "ixx"},
    {vocab::dyn_coord::ns, "ixy"},
    {vocab::dyn_coord::ns, "ixz"},
    {vocab::dyn_coord::ns, "iyy"},
    {vocab::dyn_coord::ns, "iyz"},
    {vocab::dyn_coord::ns, "izz"},
    {vocab::dyn_coord::ns, "mass"},
    {kUnit, "UNITLESS"},
    {kUnit, "M"},
    {kUnit, "KiloGM-M2"},
    {kUnit, "KiloGM"},
    {vocab::kc_ext::ns, "of-joint"},
    {vocab::kc_ext::ns, "JointLimit"},
    {vocab::kc_ext::ns, "lower"},
    {vocab::kc_ext::ns, "upper"},
    {vocab::kc_stat::ns, "JointPosition"},
    {vocab::kc_stat::ns, "JointVelocity"},
    {vocab::kc_stat::ns, "JointAcceleration"},
    {vocab::kc_stat::ns, "JointForce"},
    {vocab::qudt::ns, "value"},
    {vocab::mospec_joints::ns, "of-joint"},
    {vocab::mospec_joints::ns, "JointPositionLimits"},
    {vocab::mospec_joints::ns, "JointVelocityLimit"},
    {vocab::mospec_joints::ns, "JointEffortLimit"},
    {kUnit, "RAD"},
    {kUnit, "M-PER-SEC"},
    {kUnit, "RAD-PER-SEC"},
    {kUnit, "N"},
    {kUnit, "N-M"},
}};
const Term& term(V v) {
  return kTerms[static_cast<size_t>(v)];
}
std::string text(V v) {
  return iri(term(v).ns, term(v).local);
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
    if (t == kUnknown) {
      // Every IRI of kTerms is short; a longer one is looked up as a string.
      const Term& w = term(v);
      std::array<char, 128> buf;
      if (w.ns.size() + w.local.size() > buf.size()) {
        t = id(text(v));
      } else {
        std::copy(w.ns.begin(), w.ns.end(), buf.begin());
        std::copy(w.local.begin(), w.local.end(), buf.begin() + w.ns.size());
        t = id(std::string_view(buf.data(), w.ns.size() + w.local.size()));
      }
    }
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
    // One scan over the subject's type statements, not one lookup per graph read.
    bool found = false;
    g_.scan(s, p, t, rdf::TermId::any(), [&](const rdf::Quad& q, uint32_t) {
      found = read(q);
      return !found;
    });
    return found;
  }
  // The object of (s, p) when objects(s, p) would list exactly one; else
  // any(). Reads in place: most statements read are single-valued.
  rdf::TermId single_object(rdf::TermId s, V p) const {
    const rdf::TermId pid = id(p);
    rdf::TermId first = rdf::TermId::any();
    if (pid.is_any()) return first;
    bool several = false;
    g_.scan(s, pid, rdf::TermId::any(), rdf::TermId::any(), [&](const rdf::Quad& q, uint32_t) {
      if (!read(q)) return true;
      if (first.is_any()) {
        first = q.object;
        return true;
      }
      // objects() lists a triple stated in several graphs read once, and
      // (unfiltered) every statement.
      if (filtered_ && q.object == first) return true;
      several = true;
      return false;
    });
    return several ? rdf::TermId::any() : first;
  }
  rdf::TermId one(rdf::TermId s, V p) const {
    if (const rdf::TermId o = single_object(s, p); !o.is_any()) return o;
    // None or several: the list, for the count in the error.
    const auto os = objects(s, p);
    if (os.size() != 1) {
      throw Error("invalid-robot-model", name(s) + ": expected exactly one <" + text(p) +
                                             ">, found " + std::to_string(os.size()));
    }
    return os.front();
  }
  double number(rdf::TermId s, V p) const { return to_double(s, p, one(s, p)); }

  // Several single-valued properties of one subject, read in one scan (a
  // subject has a handful of statements; each one() would scan them again).
  struct Value {
    rdf::TermId first = rdf::TermId::any();
    bool several = false;  // objects() would list more than one
  };
  template <size_t N>
  std::array<Value, N> values(rdf::TermId s, const std::array<V, N>& ps) const {
    std::array<Value, N> out;
    std::array<rdf::TermId, N> ids;
    for (size_t k = 0; k < N; ++k) ids[k] = id(ps[k]);
    g_.scan(s, rdf::TermId::any(), rdf::TermId::any(), rdf::TermId::any(),
            [&](const rdf::Quad& q, uint32_t) {
              if (!read(q)) return true;
              for (size_t k = 0; k < N; ++k) {
                if (q.predicate != ids[k] || ids[k].is_any()) continue;
                Value& v = out[k];
                if (v.first.is_any()) {
                  v.first = q.object;
                } else if (!filtered_ || q.object != v.first) {
                  v.several = true;  // as objects() counts: see single_object
                }
              }
              return true;
            });
    return out;
  }
  // The value read for (s, p), or one(s, p)'s error when there is none or several.
  rdf::TermId take(rdf::TermId s, V p, const Value& v) const {
    return v.first.is_any() || v.several ? one(s, p) : v.first;
  }
  double take_number(rdf::TermId s, V p, const Value& v) const {
    return to_double(s, p, take(s, p, v));
  }
  double to_double(rdf::TermId s, V p, rdf::TermId o) const {
    const auto& term = g_.terms()[o];
    double v = 0.0;
    if (term.is_literal()) {
      const auto r = std::from_chars(term.value.data(), term.value.data() + term.value.size(), v);
      if (r.ec == std::errc() && r.ptr == term.value.data() + term.value.size()) return v;
    }
    throw Error("invalid-robot-model", name(s) + ": <" + text(p) + "> is not a number");
  }
  // The numbers of the RDF list that `head` (read for (s, p)) starts, into
  // `out`; how many (reading stops after 17: enough to report a wrong length).
  using NumberList = std::array<double, 17>;
  size_t number_list(rdf::TermId s, V p, const Value& head, NumberList& out) const {
    size_t n = 0;
    const rdf::TermId nil = id(V::nil);
    for (rdf::TermId node = take(s, p, head); node != nil;) {
      const auto v = values(node, std::array{V::first, V::rest});
      out[n++] = to_double(s, p, take(node, V::first, v[0]));
      if (n == out.size()) break;
      node = take(node, V::rest, v[1]);
    }
    return n;
  }
  // Whether objects(s, unit) lists exactly the terms of `want` (distinct),
  // each once: then require_units passes. Compares ids, builds no strings.
  bool units_are(rdf::TermId s, std::initializer_list<V> want) const {
    const rdf::TermId pid = id(V::unit);
    if (pid.is_any()) return false;
    std::array<rdf::TermId, 4> seen;
    size_t n = 0;
    bool ok = true;
    g_.scan(s, pid, rdf::TermId::any(), rdf::TermId::any(), [&](const rdf::Quad& q, uint32_t) {
      if (!read(q)) return true;
      const bool repeat = std::find(seen.begin(), seen.begin() + n, q.object) != seen.begin() + n;
      if (repeat && filtered_) return true;  // objects() lists it once
      const bool wanted = std::any_of(want.begin(), want.end(), [&](V w) {
        const rdf::TermId t = id(w);
        return !t.is_any() && t == q.object;
      });
      if (repeat || !wanted || n == seen.size()) {
        ok = false;
        return false;
      }
      seen[n++] = q.object;
      return true;
    });
    return ok && n == want.size();
  }
  // The QUDT units of `s` must be exactly `want` (a set).
  void require_units(rdf::TermId s, std::initializer_list<V> want) const {
    if (units_are(s, want)) return;
    std::vector<std::string> got;
    for (rdf::TermId u : objects(s, V::unit)) got.push_back(name(u));
    std::sort(got.begin(), got.end());
    std::vector<std::string> expected;
    for (V w : want) expected.push_back(text(w));
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
    require_units(p, {V::UNITLESS, V::M});
    Pose X;
    const char* keys[] = {"direction-cosine-x", "direction-cosine-y", "direction-cosine-z"};
    constexpr std::array columns{V::direction_cosine_x, V::direction_cosine_y,
                                 V::direction_cosine_z};
    const auto v = values(p, std::array{V::direction_cosine_x, V::direction_cosine_y,
                                        V::direction_cosine_z, V::x, V::y, V::z});
    for (int c = 0; c < 3; ++c) {
      NumberList col;
      if (const size_t n = number_list(p, columns[c], v[c], col); n != 3) {
        throw Error("invalid-robot-model",
                    name(p) + ": " + keys[c] + " must have 3 entries, got " + std::to_string(n));
      }
      X.R.col(c) = Vec3(col[0], col[1], col[2]);
    }
    X.p = Vec3(take_number(p, V::x, v[3]), take_number(p, V::y, v[4]), take_number(p, V::z, v[5]));
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
      require_units(r, {V::KiloGM_M2});
      constexpr std::array ps{V::ixx, V::ixy, V::ixz, V::iyy, V::iyz, V::izz, V::about, V::of_body};
      const auto v = values(r, ps);
      const auto at = [&](V k) { return size_t(std::find(ps.begin(), ps.end(), k) - ps.begin()); };
      const auto c = [&](V k) { return take_number(r, k, v[at(k)]); };
      I.I_Scm_S << c(V::ixx), c(V::ixy), c(V::ixz), c(V::ixy), c(V::iyy), c(V::iyz), c(V::ixz),
          c(V::iyz), c(V::izz);
      const rdf::TermId com = take(r, V::about, v[at(V::about)]);
      bool found = false;
      for (rdf::TermId p : subjects(V::of, com)) {
        if (!has_type(p, V::Position)) continue;
        require_units(p, {V::M});
        const auto xyz = values(p, std::array{V::x, V::y, V::z});
        I.p_SoScm_S = Vec3(take_number(p, V::x, xyz[0]), take_number(p, V::y, xyz[1]),
                           take_number(p, V::z, xyz[2]));
        found = true;
      }
      if (!found) {
        throw Error("invalid-robot-model", name(r) + ": no Position of its point " + name(com));
      }
      const rdf::TermId body = take(r, V::of_body, v[at(V::of_body)]);
      found = false;
      for (rdf::TermId m : subjects(V::of_body, body)) {
        if (!has_type(m, V::Mass)) continue;
        require_units(m, {V::KiloGM});
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

  static std::string local_name(std::string_view iri_text, std::string_view prefix) {
    std::string_view s = iri_text.substr(iri_text.find_last_of("/#") + 1);
    if (s.substr(0, prefix.size()) == prefix) s.remove_prefix(prefix.size());
    return std::string(s);
  }
  // local_name of name(t), without building name(t) for an IRI.
  std::string local_name(rdf::TermId t, std::string_view prefix) const {
    const auto& term = g_.terms()[t];
    return term.is_iri() ? local_name(term.value, prefix) : local_name(name(t), prefix);
  }

  // The term at the free position (subject or object, the one given as
  // any()) of the statements read matching (s, p, o), when they all agree
  // on it; else any(). Sorting and deduplicating subjects() or objects() and
  // taking a list of one gives the same.
  rdf::TermId only(rdf::TermId s, V p, rdf::TermId o) const {
    const rdf::TermId pid = id(p);
    rdf::TermId found = rdf::TermId::any();
    if (pid.is_any()) return found;
    bool several = false;
    g_.scan(s, pid, o, rdf::TermId::any(), [&](const rdf::Quad& q, uint32_t) {
      if (!read(q)) return true;
      const rdf::TermId t = s.is_any() ? q.subject : q.object;
      if (found.is_any()) {
        found = t;
      } else if (t != found) {
        several = true;
        return false;
      }
      return true;
    });
    return several ? rdf::TermId::any() : found;
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

// The joint's limits (kc-ext:JointLimit of it, typed also by the kind of
// quantity it limits: kc-stat:JointPosition, JointVelocity or JointForce),
// in its type's units; none stated: unbounded. mospec's actuation bounds a
// joint's velocity and effort by one magnitude, so those limits must be
// symmetric; it enforces no acceleration limit: both refused, not ignored.
void read_limits(const Reader& r, rdf::TermId joint, Segment& s) {
  const bool slides = s.type == JointType::Prismatic;
  for (rdf::TermId node : r.subjects(V::old_of_joint, joint)) {
    for (V old : {V::JointPositionLimits, V::JointVelocityLimit, V::JointEffortLimit}) {
      if (!r.has_type(node, old)) continue;
      throw Error("invalid-robot-model",
                  r.name(node) + ": " + std::string(term(old).local) +
                      " (mos-jnt) is retired; a joint limit is the published kc-ext:JointLimit "
                      "(context " +
                      std::string(vocab::kSecorolab) +
                      "kinematic-chain/structural-entities-extension.json), typed also "
                      "kc-stat:JointPosition, JointVelocity or JointForce, with `of-joint` and "
                      "`lower` and `upper` quantities (docs/models.md; `mospec import-urdf` "
                      "writes them)");
    }
  }
  // One bound (`lower` or `upper`): a quantity node with a finite value in `unit`.
  const auto bound = [&](rdf::TermId node, V p, V unit) {
    const rdf::TermId q = r.one(node, p);
    r.require_units(q, {unit});
    const double v = r.number(q, V::value);
    if (!std::isfinite(v)) {
      throw Error("invalid-robot-model",
                  r.name(node) + ": the value of <" + text(p) + "> must be finite");
    }
    return v;
  };
  bool position = false, velocity = false, effort = false;
  const auto once = [&](rdf::TermId node, bool& seen, const char* kind) {
    if (seen) {
      throw Error("invalid-robot-model",
                  r.name(node) + ": a second " + kind + " limit for joint " + r.name(joint));
    }
    seen = true;
  };
  for (rdf::TermId node : r.subjects(V::of_joint, joint)) {
    if (!r.has_type(node, V::JointLimit)) continue;
    const bool is_position = r.has_type(node, V::JointPosition);
    const bool is_velocity = r.has_type(node, V::JointVelocity);
    const bool is_force = r.has_type(node, V::JointForce);
    const bool is_acceleration = r.has_type(node, V::JointAcceleration);
    if (is_position + is_velocity + is_force + is_acceleration != 1) {
      throw Error("invalid-robot-model",
                  r.name(node) +
                      ": a JointLimit is typed also by exactly one kind of quantity it limits "
                      "(kc-stat:JointPosition, JointVelocity or JointForce)");
    }
    if (is_acceleration) {
      throw Error("invalid-robot-model",
                  r.name(node) +
                      ": mospec enforces no joint acceleration limit (its actuation bounds "
                      "position, velocity and effort); remove it");
    }
    const V unit = is_position   ? (slides ? V::M : V::RAD)
                   : is_velocity ? (slides ? V::M_PER_SEC : V::RAD_PER_SEC)
                                 : (slides ? V::N : V::N_M);
    const double lower = bound(node, V::lower, unit);
    const double upper = bound(node, V::upper, unit);
    if (lower > upper) {
      throw Error("invalid-robot-model", r.name(node) + ": lower limit > upper limit");
    }
    if (is_position) {
      once(node, position, "position");
      s.limits.lower = lower;
      s.limits.upper = upper;
      continue;
    }
    once(node, is_velocity ? velocity : effort, is_velocity ? "velocity" : "effort");
    if (lower != -upper) {
      throw Error("invalid-robot-model",
                  r.name(node) + ": mospec bounds a joint's " +
                      (is_velocity ? "velocity" : "effort") +
                      " by one magnitude (|x| <= upper), so its lower limit must be -upper");
    }
    (is_velocity ? s.limits.velocity : s.limits.effort) = upper;
  }
}

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
  ChainDescription out{Chain(r.local_name(roots.front(), "frame-")), {}};
  Chain& chain = out.chain;
  // A frame's origin point and the body it is attached to, by the model's
  // relations: the frame's `origin`; the simplicial complex (link) whose
  // `simplices` hold the frame, else the body whose inertia the frame sees.
  // Each is the only distinct term found, or none (several or no candidates).
  const rdf::TermId any = rdf::TermId::any();
  const auto origin_of = [&](rdf::TermId f) {
    const rdf::TermId o = r.only(f, V::origin, any);
    return o.is_any() ? std::string() : r.name(o);
  };
  const auto body_of = [&](rdf::TermId f) {
    if (const rdf::TermId complex = r.only(any, V::simplices, f); !complex.is_any()) {
      return r.name(complex);
    }
    for (rdf::TermId i : r.subjects(V::as_seen_by, f)) {
      if (!r.has_type(i, V::RotationalInertia)) continue;
      if (const rdf::TermId body = r.only(i, V::of_body, any); !body.is_any()) return r.name(body);
    }
    return std::string();
  };
  out.frames.root = {r.name(roots.front()), origin_of(roots.front()), body_of(roots.front()), {}};
  rdf::TermId frame = roots.front();
  for (auto it = by_parent_frame.find(frame); it != by_parent_frame.end();
       it = by_parent_frame.find(frame)) {
    const JointInfo& info = it->second;
    Segment s;
    s.joint = r.local_name(info.joint, "joint-");
    s.link = r.local_name(info.child, "frame-");
    s.type = info.type;
    s.X_PJ = r.pose(info.pose);
    const rdf::TermId axis = r.one(info.joint, V::common_axis);
    const auto xyz = r.values(axis, std::array{V::x, V::y, V::z});
    s.axis_J = Vec3(r.take_number(axis, V::x, xyz[0]), r.take_number(axis, V::y, xyz[1]),
                    r.take_number(axis, V::z, xyz[2]));
    s.inertia = r.inertia(info.child);
    read_limits(r, info.joint, s);
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
    chain.add_fixed(r.local_name(tip, "frame-"), r.pose(tips.front()), {});
    out.frames.tip = {r.name(tip), origin_of(tip), body_of(tip), {}};
    out.frames.tip_pose = r.name(tips.front());
  }
  return out;
}

}  // namespace

}  // namespace mospec::description
