#include "ir/lowering.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/SVD>
#include <algorithm>
#include <array>
#include <cstdio>

#include "rdf/dataset.hpp"

namespace mospec::ir::lowering {

std::string State::did_you_mean(TermId e) const {
  const std::string best = rdf::nearest_subject_iri(model.dataset(), graph.str(e));
  return best.empty() ? std::string() : "; did you mean '" + best + "'?";
}

void State::several_values(TermId s, const std::string& p,
                           const std::vector<TermId>& values) const {
  if (!several_reported.emplace(s.index, p).second) return;
  const auto quoted = [&](TermId v) {
    if (graph.terms()[v].is_literal()) return literal_text(v);
    std::string out = "'";
    out.append(graph.str(v)).append("'");
    return out;
  };
  std::string msg = "'";
  msg.append(graph.str(s))
      .append("' has ")
      .append(std::to_string(values.size()))
      .append(" values for `")
      .append(local_name(p))
      .append("`, which takes one: ");
  for (size_t k = 0; k < values.size() && k < 3; ++k) {
    if (k) msg.append(k + 1 == values.size() ? " and " : ", ");
    msg.append(quoted(values[k])).append(" (").append(place(where(s, p, values[k]))).append(")");
  }
  if (values.size() > 3) msg.append(", ...");
  msg.append(
      "; give it once (a value in a second file does not override the first: both are part of "
      "the model)");
  error(where(s, p, values[1]), "several-values", msg);
}

const State::DatumTerms& State::datum_terms() const {
  if (datum_terms_) return *datum_terms_;
  const std::string gr = "geometry/spatial-relations", gc = "geometry/coordinates",
                    de = "newtonian-rigid-body-dynamics/structural-entities",
                    dc = "newtonian-rigid-body-dynamics/coordinates";
  DatumTerms t;
  t.pose = term(vocab(gr, "Pose"));
  t.pose_coordinate = term(vocab(gc, "PoseCoordinate"));
  t.twist = term(vocab(gr, "VelocityTwist"));
  t.twist_coordinate = term(vocab(gc, "VelocityTwistCoordinate"));
  t.wrench = term(vocab(de, "Wrench"));
  t.wrench_coordinate = term(vocab(dc, "WrenchCoordinate"));
  t.rigid_body_inertia = term(vocab(de, "RigidBodyInertia"));
  t.rigid_body_inertia_coordinate = term(vocab(dc, "RigidBodyInertiaCoordinate"));
  t.of_body = term(vocab(de, "of-body"));
  t.about = term(vocab(de, "about"));
  t.direction_coordinate = term(vocab(gc, "DirectionCoordinate"));
  t.position = term(vocab(gr, "Position"));
  t.position_coordinate = term(vocab(gc, "PositionCoordinate"));
  t.quantity = term(kQudt + "Quantity");
  t.linear_distance = term(vocab(gr, "LinearDistance"));
  t.has_quantity_kind = term(kQudt + "hasQuantityKind");
  t.unit = term(kQudt + "unit");
  t.value = term(kQudt + "value");
  t.of = term(vocab(gr, "of"));
  t.with_respect_to = term(vocab(gr, "with-respect-to"));
  t.reference_point = term(vocab(gr, "reference-point"));
  t.dyn_reference_point = term(vocab(de, "reference-point"));
  t.as_seen_by = term(vocab(gc, "as-seen-by"));
  t.dyn_as_seen_by = term(vocab(dc, "as-seen-by"));
  t.x = term(vocab(gc, "x"));
  t.y = term(vocab(gc, "y"));
  t.z = term(vocab(gc, "z"));
  t.direction_cosine[0] = term(vocab(gc, "direction-cosine-x"));
  t.direction_cosine[1] = term(vocab(gc, "direction-cosine-y"));
  t.direction_cosine[2] = term(vocab(gc, "direction-cosine-z"));
  return datum_terms_.emplace(t);
}

namespace {

// What type_of() and datum() ask of an entity, in one pass over its statements
// (Graph::read): these types (their order is kTypeOrder's) and properties.
enum DatumType {
  kPose,
  kPoseCoordinate,
  kTwist,
  kTwistCoordinate,
  kWrench,
  kWrenchCoordinate,
  kInertia,
  kInertiaCoordinate,
  kDirectionCoordinate,
  kPosition,
  kPositionCoordinate,
  kQuantity,
  kLinearDistance,
  kDatumTypes
};
enum DatumProperty {
  kOf,
  kWithRespectTo,
  kReferencePoint,
  kDynReferencePoint,
  kOfBody,
  kAbout,
  kAsSeenBy,
  kDynAsSeenBy,
  kQuantityKind,
  kUnit,
  kValue,
  kX,
  kY,
  kZ,
  kDirectionCosine0,  // ..2
  kDatumProperties = kDirectionCosine0 + 3
};

std::array<TermId, kDatumTypes> datum_types(const State::DatumTerms& t) {
  return {t.pose,
          t.pose_coordinate,
          t.twist,
          t.twist_coordinate,
          t.wrench,
          t.wrench_coordinate,
          t.rigid_body_inertia,
          t.rigid_body_inertia_coordinate,
          t.direction_coordinate,
          t.position,
          t.position_coordinate,
          t.quantity,
          t.linear_distance};
}

// The data type an entity's classes (bit k: it has type k of DatumType) and
// a quantity kind make it; the first match in this order.
std::optional<DataType> type_from(uint64_t types, bool has_quantity_kind) {
  const auto is = [&](DatumType k) { return (types >> k) & 1U; };
  if (is(kPose) || is(kPoseCoordinate)) return DataType::Pose;
  if (is(kTwist) || is(kTwistCoordinate)) return DataType::Twist;
  if (is(kWrench) || is(kWrenchCoordinate)) return DataType::Wrench;
  if (is(kInertia) || is(kInertiaCoordinate)) return DataType::Inertia;
  if (is(kDirectionCoordinate) || is(kPosition) || is(kPositionCoordinate))
    return DataType::Vector3;
  if (is(kQuantity) || is(kLinearDistance) || has_quantity_kind) return DataType::Scalar;
  return std::nullopt;
}

// A constant's value, from the entity's properties as `value(k)` gives them
// (State::object's answer for property k of DatumProperty, read only when
// needed, so that a property with several values is reported only if read).
template <class Value>
void fill_constant(State& st, Data& d, TermId e, const Value& value) {
  const auto number = [&](DatumProperty k) -> std::optional<double> {
    auto o = value(k);
    return o ? st.number(*o) : std::nullopt;
  };
  switch (d.type) {
    case DataType::Scalar:
      if (auto v = number(kValue)) d.value = {*v};
      break;
    case DataType::Vector3: {
      auto x = number(kX), y = number(kY), z = number(kZ);
      if (x && y && z) d.value = {*x, *y, *z};
      break;
    }
    case DataType::Pose: {
      auto x = number(kX), y = number(kY), z = number(kZ);
      std::array<std::vector<double>, 3> cols;
      bool ok = x && y && z;
      for (int c = 0; c < 3 && ok; ++c) {
        auto head = value(static_cast<DatumProperty>(kDirectionCosine0 + c));
        if (!head) {
          ok = false;
          break;
        }
        for (TermId t : st.list(*head)) {
          if (auto v = st.number(t)) cols[static_cast<size_t>(c)].push_back(*v);
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
        st.error(e, "invalid-pose",
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
    case DataType::Inertia:
      if (st.defined(e)) st.fill_inertia(d, e);
      break;
    default:
      break;
  }
}

}  // namespace

std::optional<DataType> State::type_of(TermId e) const {
  const DatumTerms& t = datum_terms();
  const std::array<TermId, kDatumTypes> types = datum_types(t);
  const TermId kind[1] = {t.has_quantity_kind};
  Graph::Value kind_value[1];
  const Graph::Reading r = graph.read(e, kind, kind_value, types);
  return type_from(r.types, !kind_value[0].first.is_any());
}

// A rigid-body inertia is always a constant: its ten numbers are read here, and
// a model that leaves one out, or states a body no physical mass distribution
// has, is refused rather than run with zeros.
void State::fill_inertia(Data& d, TermId e) {
  const std::string dc = "newtonian-rigid-body-dynamics/coordinates";
  const auto missing = [&](const std::string& what) {
    error(e, "missing-property",
          "the rigid-body inertia '" + d.iri + "' gives no " + what +
              "; state `mass` (kg), `first-moment-of-mass` (3 values, kg m: the mass times the "
              "centre of mass's position from `about`), `ixx`, `iyy`, `izz` and, unless its axes "
              "are principal, `ixy`, `ixz`, `iyz` (kg m2, about `about`)");
  };
  // Units, when stated, must be the SI ones the numbers are read in.
  for (TermId u : objects(e, kQudt + "unit")) {
    const std::string unit = local_name(str(u));
    if (unit != "KiloGM" && unit != "KiloGM-M" && unit != "KiloGM-M2")
      error(e, "wrong-unit",
            "the rigid-body inertia '" + d.iri + "' states the unit '" + unit +
                "'; its numbers are read in KiloGM (mass), KiloGM-M (first moment) and KiloGM-M2 "
                "(moments of inertia): convert them, or state no unit");
  }
  const auto m = number(e, vocab(dc, "mass"));
  if (!m) return missing("`mass`");
  std::vector<double> h;
  if (auto head = object(e, vocab(dc, "first-moment-of-mass"))) {
    for (TermId t : list(*head)) {
      if (auto v = number(t)) h.push_back(*v);
    }
  }
  if (h.size() != 3) return missing("`first-moment-of-mass` of 3 numbers");
  std::array<std::optional<double>, 6> I;
  const char* names[6] = {"ixx", "iyy", "izz", "ixy", "ixz", "iyz"};
  for (size_t k = 0; k < 6; ++k) I[k] = number(e, vocab(dc, names[k]));
  for (size_t k = 0; k < 3; ++k) {
    if (!I[k]) return missing(std::string("`") + names[k] + "`");
  }
  const int products = (I[3] ? 1 : 0) + (I[4] ? 1 : 0) + (I[5] ? 1 : 0);
  if (products != 0 && products != 3) return missing("all three products of inertia");
  std::vector<double> value = {*m, h[0], h[1], h[2], *I[0], *I[1], *I[2]};
  for (size_t k = 3; k < 6; ++k) value.push_back(I[k].value_or(0.0));
  // Physical: m > 0, and the rotational inertia about the centre of mass
  // (I_Po + [h]x [h]x / m) positive semi-definite with its principal moments
  // obeying the triangle inequality.
  std::string why;
  if (!(*m > 0.0)) {
    why = "its mass " + literal_text(*object(e, vocab(dc, "mass"))) + " is not positive";
  } else {
    const runtime::RigidBodyInertia M =
        runtime::rigid_body_inertia(std::span<const double, 10>(value.data(), 10));
    const runtime::Mat3 hx = runtime::skew(M.h);
    const runtime::Mat3 I_cm = M.I + hx * hx / M.m;
    const Eigen::SelfAdjointEigenSolver<runtime::Mat3> eig(I_cm);
    const runtime::Vec3 l = eig.eigenvalues();  // ascending
    const double tol = 1e-9 * std::max(1.0, l.cwiseAbs().maxCoeff());
    char moments[96];
    std::snprintf(moments, sizeof moments, " (%.6g, %.6g, %.6g kg m2)", l[0], l[1], l[2]);
    if (!(l[0] >= -tol)) {
      why = "its rotational inertia about the centre of mass has a negative principal moment";
      why.append(moments);
    } else if (!(l[0] + l[1] >= l[2] - tol)) {
      why =
          "its principal moments about the centre of mass break the triangle inequality "
          "(the two smaller sum to less than the largest)";
      why.append(moments);
    }
  }
  if (!why.empty()) {
    error(e, "invalid-inertia",
          "the rigid-body inertia '" + d.iri + "' is not a physical body: " + why +
              "; check the values' signs and that the moments are about `about`, not about the "
              "centre of mass");
    return;
  }
  d.value = std::move(value);
}

namespace {

// The properties a datum is read through, in DatumProperty's order.
std::array<TermId, kDatumProperties> datum_properties(const State::DatumTerms& t) {
  std::array<TermId, kDatumProperties> properties{};
  properties[kOf] = t.of;
  properties[kWithRespectTo] = t.with_respect_to;
  properties[kReferencePoint] = t.reference_point;
  properties[kDynReferencePoint] = t.dyn_reference_point;
  properties[kOfBody] = t.of_body;
  properties[kAbout] = t.about;
  properties[kAsSeenBy] = t.as_seen_by;
  properties[kDynAsSeenBy] = t.dyn_as_seen_by;
  properties[kQuantityKind] = t.has_quantity_kind;
  properties[kUnit] = t.unit;
  properties[kValue] = t.value;
  properties[kX] = t.x;
  properties[kY] = t.y;
  properties[kZ] = t.z;
  for (int c = 0; c < 3; ++c) properties[kDirectionCosine0 + c] = t.direction_cosine[c];
  return properties;
}

// The statements of a datum's entity e, read in one pass; a property with
// several values is read (and reported) by State::object when it is used.
struct DatumReading {
  DatumReading(const State& state, TermId entity)
      : st(state), e(entity), properties(datum_properties(state.datum_terms())) {
    read = st.graph.read(e, properties, values, datum_types(st.datum_terms()));
  }
  std::optional<TermId> value(DatumProperty k) const {
    if (values[k].several) return st.several_of(e, properties[k]);
    if (values[k].first.is_any()) return std::nullopt;
    return values[k].first;
  }
  // All values of a property, sorted (Graph::objects).
  std::vector<TermId> all(DatumProperty k) const {
    if (values[k].several) return st.graph.objects(e, properties[k]);
    if (values[k].first.is_any()) return {};
    return {values[k].first};
  }
  const State& st;
  TermId e;
  std::array<TermId, kDatumProperties> properties;
  std::array<Graph::Value, kDatumProperties> values;
  Graph::Reading read;
};

// "'R' uses 'X' as its ROLE, which must be a T, but it is a U", at R.
void type_mismatch(const State& st, TermId referenced_by, const std::string& role,
                   const std::string& iri, DataType expected, DataType got) {
  std::string msg = "'";
  msg.append(st.str(referenced_by))
      .append("' uses '")
      .append(iri)
      .append("' as its ")
      .append(role)
      .append(", which must be a ")
      .append(to_string(expected))
      .append(", but it is a ")
      .append(to_string(got));
  st.error(referenced_by, "type-mismatch", msg);
}

// Where the datum is (of, w.r.t., at, seen by), its quantity kinds and units.
void read_placement(const DatumReading& r, Data& d) {
  const State& st = r.st;
  if (auto o = r.value(kOf)) d.of = st.str(*o);
  if (auto o = r.value(kWithRespectTo)) d.with_respect_to = st.str(*o);
  if (auto o = r.value(kReferencePoint)) d.reference_point = st.str(*o);
  if (auto o = r.value(kDynReferencePoint)) d.reference_point = st.str(*o);
  if (d.type == DataType::Inertia) {
    if (auto o = r.value(kOfBody)) d.of = st.str(*o);
    if (auto o = r.value(kAbout)) d.reference_point = st.str(*o);
  }
  if (auto o = r.value(kAsSeenBy)) d.as_seen_by = st.str(*o);
  if (auto o = r.value(kDynAsSeenBy)) d.as_seen_by = st.str(*o);
  const std::vector<TermId> kinds = r.all(kQuantityKind), units = r.all(kUnit);
  for (size_t i = 0; i < kinds.size(); ++i)
    d.quantity_kind.append(i ? "," : "").append(local_view(st.graph.str(kinds[i])));
  for (size_t i = 0; i < units.size(); ++i)
    d.unit.append(i ? "," : "").append(local_view(st.graph.str(units[i])));
}

}  // namespace

int State::datum(TermId e, DataType expected, TermId referenced_by, const std::string& role) {
  if (auto it = data_of.find(e.index); it != data_of.end()) {
    const Data& d = program.data[static_cast<size_t>(it->second)];
    if (d.type != expected) type_mismatch(*this, referenced_by, role, d.iri, expected, d.type);
    return it->second;
  }
  Data d;
  d.iri = str(e);
  d.type = expected;
  d.where = where(e);
  const DatumReading r(*this, e);
  if (!r.read.defined) {
    std::string msg = "'";
    msg.append(str(referenced_by))
        .append("' names '")
        .append(d.iri)
        .append("' as its ")
        .append(role)
        .append(", but no model file defines it")
        .append(did_you_mean(e));
    error(where(referenced_by), "undefined-quantity", msg);
  } else if (auto ty = type_from(r.read.types, !r.values[kQuantityKind].first.is_any());
             ty && *ty != expected) {
    type_mismatch(*this, referenced_by, role, d.iri, expected, *ty);
  }
  read_placement(r, d);
  fill_constant(*this, d, e, [&](DatumProperty k) { return r.value(k); });
  d.name = unique_name(local_name(d.iri), data_names);
  d.slot = program.slots[static_cast<size_t>(d.type)]++;
  const int index = static_cast<int>(program.data.size());
  program.data.push_back(std::move(d));
  data_of[e.index] = index;
  return index;
}

int State::synthetic(const std::string& iri, const std::string& name, DataType type, SourceLoc loc,
                     const std::string& unit) {
  Data d;
  d.iri = iri;
  d.type = type;
  d.where = loc;
  d.unit = unit;
  d.name = unique_name(name, data_names);
  d.slot = program.slots[static_cast<size_t>(type)]++;
  program.data.push_back(std::move(d));
  return static_cast<int>(program.data.size()) - 1;
}

}  // namespace mospec::ir::lowering
