// Lowering passes. Operators (the registry in operators.hpp), accumulated wrenches and planar
// angles.
#include <algorithm>
#include <cmath>

#include "ir/lowering.hpp"

namespace mospec::ir::lowering {

// Every operator kind of the registry (operators.hpp) that maps its class's
// properties onto its ports: one step per instance, its inputs and output the
// quantities the properties name, and the kind's frame rules checked.
void lower_operators(State& st) {
  const auto kinds = operator_kinds();
  for (size_t k = 0; k < kinds.size(); ++k) {
    const OperatorKind& kind = kinds[k];
    if (!kind.generic_lowering) continue;
    for (TermId e : st.instances(kind.class_iri())) {
      st.pending_iri = st.str(e);
      Step s = st.step_for(StepKind::Operator, e);
      s.op = static_cast<int>(k);
      bool ok = true;
      const auto port_datum = [&](const OperatorPort& port) {
        const std::vector<TermId> values = st.objects(e, kind.property_iri(port.property));
        if (values.size() > 1) {
          st.error(e, "several-values",
                   "the " + std::string(kind.type) + " '" + s.iri + "' names " +
                       std::to_string(values.size()) + " values for `" +
                       std::string(port.property) + "` ('" + st.str(values[0]) + "', '" +
                       st.str(values[1]) + "'" + (values.size() > 2 ? ", ..." : "") +
                       "); an operator reads exactly one");
          ok = false;
          return -1;
        }
        auto o = values.empty() ? std::optional<TermId>() : std::optional<TermId>(values[0]);
        if (!o) {
          st.error(e, "missing-property",
                   "the " + std::string(kind.type) + " '" + s.iri + "' names no `" +
                       std::string(port.property) + "`");
          ok = false;
          return -1;
        }
        if (port.source == PortSource::Axis) return axis_constant(st, e, kind, port, *o);
        return st.datum(*o, port.type, e, std::string(port.property));
      };
      for (const OperatorPort& port : kind.in) s.in.push_back(port_datum(port));
      const int out = port_datum(kind.out);
      refuse_unknown_properties(st, e, kind);
      if (!ok) continue;
      s.out.push_back(out);
      check_frames(st, e, kind, s);
      st.add_step(std::move(s));
    }
  }
}

// A property of the operator's vocabulary that the kind does not read (e.g.
// TransformWrenchToProximal's `at-index` into an array of wrenches) would be
// ignored: refuse it instead.
void refuse_unknown_properties(State& st, TermId e, const OperatorKind& kind) {
  std::set<std::string_view> seen;  // views of the term table's IRIs
  st.graph.each_statement(e, [&](const Graph::Statement& stmt) {
    const std::string_view p = st.graph.str(stmt.predicate);
    if (!p.starts_with(kind.vocabulary)) return;
    const std::string_view local = p.substr(kind.vocabulary.size());
    if (kind.port(local) >= 0 || !seen.insert(p).second) return;
    std::string ports;
    for (const OperatorPort& port : kind.in) ports.append(port.property).append(", ");
    ports.append(kind.out.property);
    st.error(stmt.where.known() ? stmt.where : st.where(e), "unsupported-property",
             "the " + std::string(kind.type) + " '" + st.str(e) + "' states `" +
                 std::string(local) + "`, which mospec's " + std::string(kind.name) +
                 " does not implement (it reads only " + ports +
                 "); remove it or model the "
                 "computation another way");
  });
}

// An axis the model names (geom-op:x, y or z): a unit-vector constant.
int axis_constant(State& st, TermId e, const OperatorKind& kind, const OperatorPort& port,
                  TermId axis) {
  const std::string name = local_name(st.str(axis));
  const int index = st.str(axis) == kind.property_iri("x")   ? 0
                    : st.str(axis) == kind.property_iri("y") ? 1
                    : st.str(axis) == kind.property_iri("z") ? 2
                                                             : -1;
  if (index < 0) {
    st.error(st.where(e, kind.property_iri(port.property), axis), "invalid-axis",
             "the " + std::string(kind.type) + " '" + st.str(e) + "' names `" +
                 std::string(port.property) + "` '" + st.str(axis) + "'; it must be one of " +
                 kind.property_iri("x") + ", y or z");
    // A placeholder constant, so the refusal is reported once.
    const int d = st.synthetic(st.str(e) + "#" + std::string(port.property),
                               local_name(st.str(e)) + "_" + std::string(port.property),
                               DataType::Vector3, st.where(e), "UNITLESS");
    st.program.data[static_cast<size_t>(d)].value = {0.0, 0.0, 0.0};
    return d;
  }
  const int d = st.synthetic(st.str(e) + "#" + std::string(port.property),
                             local_name(st.str(e)) + "_" + std::string(port.property) + "_" + name,
                             DataType::Vector3, st.where(e), "UNITLESS");
  std::vector<double> v(3, 0.0);
  v[static_cast<size_t>(index)] = 1.0;
  st.program.data[static_cast<size_t>(d)].value = std::move(v);
  return d;
}

// The frame rules of an operator kind, on the quantities a step relates: a
// rule whose two sides are both stated must hold; a side the model leaves
// unstated is not checked (the shapes decide what must be stated).
void check_frames(State& st, TermId e, const OperatorKind& kind, const Step& s) {
  const auto quantity = [&](int port) -> const Data& {
    const int d = port < static_cast<int>(s.in.size()) ? s.in[static_cast<size_t>(port)] : s.out[0];
    return st.program.data[static_cast<size_t>(d)];
  };
  for (const FrameRule& rule : kind.frames) {
    const Data& lhs = quantity(rule.lhs_port);
    const Data& rhs = quantity(rule.rhs_port);
    const std::string& got = frame_field(lhs, rule.lhs_field);
    std::string expected = frame_field(rhs, rule.rhs_field);
    if (rule.rhs_origin && !expected.empty()) expected = frame_origin(st, expected);
    if (got.empty() || expected.empty() || got == expected) continue;
    const std::string lhs_port(kind.port_at(rule.lhs_port).property);
    const std::string rhs_port(kind.port_at(rule.rhs_port).property);
    std::string msg = "the ";
    msg.append(kind.type)
        .append(" '")
        .append(st.str(e))
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
    st.error(st.where(e, kind.property_iri(lhs_port), st.term(lhs.iri)), "frame-mismatch", msg);
  }
}

// The origin point of a frame, by the model's `origin` relation ("" if it
// states none).
std::string frame_origin(const State& st, const std::string& frame) {
  const TermId f = st.term(frame);
  if (st.absent(f)) return {};
  auto o = st.object(f, vocab("geometry/structural-entities", "origin"));
  return o ? st.str(*o) : std::string();
}

// AccumulateWrench: every instance that names one `aggregate` adds its
// `element` to it, so the aggregate is the sum of all their elements, added in
// the order of the elements' IRIs (the same sum, to the bit, every time): a
// copy of the first (assign-wrench), then one add-wrench step per other element.
void lower_accumulated_wrenches(State& st) {
  const std::string dop = "newtonian-rigid-body-dynamics/operators";
  const std::string prefix = vocab(dop, "");
  struct Term {
    std::string element;
    TermId entity, element_term;
  };
  std::map<std::string, std::vector<Term>> by_aggregate;
  std::map<std::string, TermId> aggregate_term;
  for (TermId e : st.instances(vocab(dop, "AccumulateWrench"))) {
    st.pending_iri = st.str(e);
    auto aggregate = st.object(e, vocab(dop, "aggregate"));
    auto element = st.object(e, vocab(dop, "element"));
    for (const Graph::Statement& stmt : st.graph.statements(e)) {
      const std::string p = st.str(stmt.predicate);
      if (!p.starts_with(prefix) || p == vocab(dop, "aggregate") || p == vocab(dop, "element"))
        continue;
      const TermId o = stmt.object;
      if (p == vocab(dop, "number-of-wrenches") && st.number(o) == 1.0) continue;
      st.error(stmt.where.known() ? stmt.where : st.where(e), "unsupported-property",
               "the AccumulateWrench '" + st.str(e) + "' states `" + p.substr(prefix.size()) +
                   "`, which mospec does not implement (it accumulates one wrench per instance: "
                   "aggregate, element, and number-of-wrenches 1 at most)");
    }
    if (!aggregate || !element) {
      st.error(e, "missing-property",
               "the AccumulateWrench '" + st.str(e) + "' names no `" +
                   (aggregate ? "element" : "aggregate") + "`");
      continue;
    }
    by_aggregate[st.str(*aggregate)].push_back({st.str(*element), e, *element});
    aggregate_term.emplace(st.str(*aggregate), *aggregate);
  }
  const int assign = operator_index("assign-wrench"), add = operator_index("add-wrench");
  for (auto& [aggregate_iri, terms] : by_aggregate) {
    std::sort(terms.begin(), terms.end(), [&](const Term& a, const Term& b) {
      return a.element != b.element ? a.element < b.element : st.str(a.entity) < st.str(b.entity);
    });
    st.pending_iri = st.str(terms.front().entity);
    const int aggregate = st.datum(aggregate_term.at(aggregate_iri), DataType::Wrench,
                                   terms.front().entity, "aggregate");
    int sum = -1;
    for (size_t k = 0; k < terms.size(); ++k) {
      const Term& t = terms[k];
      st.pending_iri = st.str(t.entity);
      const int element = st.datum(t.element_term, DataType::Wrench, t.entity, "element");
      const Data& a = st.program.data[static_cast<size_t>(aggregate)];
      const Data& el = st.program.data[static_cast<size_t>(element)];
      if (el.reference_point != a.reference_point || el.as_seen_by != a.as_seen_by) {
        st.error(st.where(t.entity, vocab(dop, "element"), t.element_term), "frame-mismatch",
                 "the AccumulateWrench '" + st.str(t.entity) + "' adds '" + el.iri + "' (about '" +
                     el.reference_point + "', seen by '" + el.as_seen_by + "') to '" + a.iri +
                     "' (about '" + a.reference_point + "', seen by '" + a.as_seen_by +
                     "'): both must be about one point and seen by one frame");
      }
      const std::string unit = a.unit;  // st.synthetic() may move st.program.data
      const bool last = k + 1 == terms.size();
      const int target =
          last ? aggregate
               : st.synthetic(aggregate_iri + "#partial-" + std::to_string(k + 1),
                              local_name(aggregate_iri) + "_partial_" + std::to_string(k + 1),
                              DataType::Wrench, st.where(t.entity), unit);
      Step s = st.step_for(StepKind::Operator, t.entity);
      if (k == 0) {
        s.op = assign;
        s.in = {element};
      } else {
        s.op = add;
        s.in = {sum, element};
      }
      s.out = {target};
      st.add_step(std::move(s));
      sum = target;
    }
  }
}

// PlanarAngleFromDirections: the signed angle from the first to the second
// direction in the xy-plane of the frame both are seen by (about its z axis).
// The vocabulary's from-directions must then be ordered: an RDF list.
void lower_planar_angles(State& st) {
  const std::string gop = "geometry/spatial-operators";
  for (TermId e : st.instances(vocab(gop, "PlanarAngleFromDirections"))) {
    st.pending_iri = st.str(e);
    Step s = st.step_for(StepKind::Operator, e);
    s.op = operator_index("planar-angle-from-directions");
    auto dirs = st.objects(e, vocab(gop, "from-directions"));
    std::vector<TermId> ordered;
    if (dirs.size() == 1) ordered = st.list(dirs.front());
    auto angle = st.object(e, vocab(gop, "angle"));
    if (ordered.size() != 2 || !angle) {
      st.error(
          e, "unordered-directions",
          "PlanarAngleFromDirections '" + s.iri +
              "' needs `from-directions` as an ordered list of two "
              "directions (\"@list\" in JSON-LD: the angle's sign depends on their order) and an "
              "`angle`");
      continue;
    }
    const int d1 = st.datum(ordered[0], DataType::Vector3, e, "from-directions");
    const int d2 = st.datum(ordered[1], DataType::Vector3, e, "from-directions");
    const Data& a = st.program.data[static_cast<size_t>(d1)];
    const Data& b = st.program.data[static_cast<size_t>(d2)];
    if (a.as_seen_by != b.as_seen_by || a.as_seen_by.empty()) {
      st.error(e, "frame-mismatch",
               "PlanarAngleFromDirections '" + s.iri +
                   "' needs both directions seen by one frame; '" + a.iri + "' is seen by '" +
                   a.as_seen_by + "', '" + b.iri + "' by '" + b.as_seen_by + "'");
      continue;
    }
    const int normal = st.synthetic(s.iri + "#normal", local_name(s.iri) + "_normal",
                                    DataType::Vector3, s.where, "UNITLESS");
    st.program.data[static_cast<size_t>(normal)].value = {0.0, 0.0, 1.0};
    st.program.data[static_cast<size_t>(normal)].as_seen_by = a.as_seen_by;
    s.in = {d1, d2, normal};
    s.out = {st.datum(*angle, DataType::Scalar, e, "angle")};
    st.add_step(std::move(s));
  }
}

}  // namespace mospec::ir::lowering
