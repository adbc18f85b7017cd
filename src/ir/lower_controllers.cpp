// Lowering pass. Controllers: every kind of the registry (controllers.hpp), one
// step per instance of its class: its signals and control signal are the
// quantities the properties name, its parameters are read as the kind declares
// (a literal, a constant quantity, or the runtime's default), their units must
// form one of the kind's accepted combinations, and whatever the model states
// that the kind cannot honour is refused, located.
#include <map>
#include <memory_resource>
#include <set>

#include "ir/controllers.hpp"
#include "ir/lowering.hpp"

namespace mospec::ir::lowering {

namespace {

// The accepted unit combinations, as messages list them:
// "measured-velocity M-PER-SEC, maximum-velocity M-PER-SEC, ...; or RAD-PER-SEC, ...".
std::string accepted_units(const ControllerKind& k) {
  std::string out;
  for (size_t r = 0; r < k.units.size(); ++r) {
    out.append(r ? "; or " : "");
    for (size_t i = 0; i < k.unit_ports.size(); ++i) {
      if (i) out.append(", ");
      if (r == 0) out.append(k.unit_ports[i]).append(" ");
      out.append(k.units[r][i]);
    }
  }
  return out;
}

// One controller of kind `kind` (index `index`), lowered to a step; what it
// cannot honour is reported.
void lower_controller(State& st, TermId c, const ControllerKind& kind, int index) {
  const std::string iri = st.str(c);
  const std::string ctrl = "the controller '" + iri + "'";
  st.pending_iri = iri;
  bool ok = true;
  // A property of the kind's vocabulary, by its local name (the IRI built in
  // one allocation; absent when the model never states it).
  const auto property_term = [&](std::string_view property) {
    std::string iri;
    iri.reserve(kind.vocabulary.size() + property.size());
    iri.append(kind.vocabulary).append(property);
    return st.term(iri);
  };
  // The one value of a property (several: refused by State::object; none: nullopt).
  const auto value_of = [&](std::string_view property) {
    return st.object(c, property_term(property));
  };

  // Signals: the scalar inputs, then the control signal.
  std::vector<std::optional<TermId>> signals;
  std::vector<std::string_view> signal_properties(kind.in.begin(), kind.in.end());
  signal_properties.push_back(kind.out);
  bool all_signals = true;
  for (std::string_view p : signal_properties) {
    signals.push_back(value_of(p));
    all_signals = all_signals && signals.back().has_value();
  }
  if (!all_signals) {
    std::string needs;
    for (size_t i = 0; i < signal_properties.size(); ++i) {
      needs.append(i == 0 ? "" : i + 1 == signal_properties.size() ? " and " : ", ");
      needs.append(article(signal_properties[i])).append(signal_properties[i]);
    }
    st.error(c, "missing-property", ctrl + " needs " + needs);
    return;
  }

  Step s = st.step_for(StepKind::Controller, c);
  s.controller = index;
  s.parameters = kind.defaults();
  s.parameters_where.assign(kind.parameters.size(), s.where);
  // (Scratch maps and sets: from the lowering's arena.)
  std::pmr::map<std::string_view, int> port_datum{&st.arena};  // unit port -> datum
  for (size_t i = 0; i < kind.in.size(); ++i) {
    s.in.push_back(st.datum(*signals[i], DataType::Scalar, c, std::string(kind.in[i])));
    port_datum[kind.in[i]] = s.in.back();
  }
  s.out = {st.datum(*signals.back(), DataType::Scalar, c, std::string(kind.out))};
  port_datum[kind.out] = s.out[0];

  // Parameters.
  std::pmr::set<std::string_view> read(signal_properties.begin(), signal_properties.end(),
                                       &st.arena);
  for (size_t f = 0; f < kind.parameters.size(); ++f) {
    const ControllerParameter& p = kind.parameters[f];
    if (p.source == ParameterSource::Fixed) continue;
    const std::string name(p.property);
    if (!p.only_with.empty() && !st.graph.has_type(c, property_term(p.only_with))) {
      // Stated without the class that gives it meaning: not read, so refused.
      const std::vector<TermId> stated = st.graph.objects(c, property_term(p.property));
      if (!stated.empty()) {
        st.error(st.graph.where(c, property_term(p.property), stated[0]), "unsupported-property",
                 ctrl + " states `" + name + "`, which only " + article(p.only_with) +
                     std::string(p.only_with) + " has; add that class or remove `" + name + "`");
        ok = false;
      }
      read.insert(p.property);
      continue;
    }
    read.insert(p.property);
    const auto term = value_of(p.property);
    if (!term) {
      if (p.required && ok) {
        st.error(c, "missing-property",
                 ctrl + " needs " +
                     (p.source == ParameterSource::Literal ? "a numeric " + name
                                                           : article(name) + name));
        ok = false;
      }
      continue;
    }
    if (p.source == ParameterSource::Literal) {
      const auto v = st.number(*term);
      if (v) {
        s.parameters[f] = *v;
        s.parameters_where[f] = st.graph.where(c, property_term(p.property), *term);
      } else if (st.graph.terms()[*term].is_literal()) {
        st.error(st.graph.where(c, property_term(p.property), *term), "invalid-number",
                 ctrl + " has " + name + " " + st.literal_text(*term) +
                     ", which is not a finite number of its datatype (xsd:double: e.g. 100, "
                     "+100.0, -1.5e2)");
        ok = false;
      } else {
        st.error(c, "missing-property", ctrl + " needs a numeric " + name);
        ok = false;
      }
      continue;
    }
    // A constant quantity: its value, in its unit.
    const int d = st.datum(*term, DataType::Scalar, c, name);
    port_datum[p.property] = d;
    const Data& q = st.program.data[static_cast<size_t>(d)];
    if (q.value.empty()) {
      const auto lit = st.object(*term, kQudt + "value");
      if (lit && st.graph.terms()[*lit].is_literal()) {
        st.error(st.where(*term, kQudt + "value", *lit), "invalid-number",
                 "the " + name + " '" + q.iri + "' of " + ctrl + " has the value " +
                     st.literal_text(*lit) + ", which is not a finite number of its datatype");
      } else {
        st.error(*term, "not-a-constant",
                 "the " + name + " '" + q.iri + "' of " + ctrl +
                     " has no value; a controller parameter is a constant");
      }
      ok = false;
      continue;
    }
    s.parameters[f] = q.value[0];
    s.parameters_where[f] = st.graph.where(c, property_term(p.property), *term);
  }

  // Units: the first port's unit picks the kind's combination; every other
  // port must have that combination's unit.
  if (!kind.units.empty()) {
    const auto unit_of = [&](std::string_view port) -> std::string {
      auto it = port_datum.find(port);
      return it == port_datum.end() ? std::string()
                                    : st.program.data[static_cast<size_t>(it->second)].unit;
    };
    const auto where_of = [&](std::string_view port) {
      auto it = port_datum.find(port);
      return it == port_datum.end() ? st.where(c)
                                    : st.program.data[static_cast<size_t>(it->second)].where;
    };
    const std::string_view key = kind.unit_ports[0];
    const std::string key_unit = unit_of(key);
    const std::vector<std::string_view>* row = nullptr;
    for (const auto& r : kind.units) {
      if (r[0] == key_unit) row = &r;
    }
    if (row == nullptr && port_datum.count(key)) {
      st.error(where_of(key), "wrong-unit",
               ctrl + ": its " + std::string(key) +
                   (key_unit.empty() ? " has no unit" : " is in '" + key_unit + "'") +
                   ", which mospec's " + std::string(kind.name) +
                   " controller does not take (it takes " + accepted_units(kind) + ")");
      ok = false;
    }
    for (size_t i = 1; row != nullptr && i < kind.unit_ports.size(); ++i) {
      const std::string_view port = kind.unit_ports[i];
      if (!port_datum.count(port)) continue;  // an optional parameter the model leaves out
      const std::string unit = unit_of(port);
      if (unit == (*row)[i]) continue;
      st.error(where_of(port), "wrong-unit",
               ctrl + ": its " + std::string(port) +
                   (unit.empty() ? " has no unit" : " is in '" + unit + "'") + ", but with its " +
                   std::string(key) + " in '" + key_unit + "' it must be in '" +
                   std::string((*row)[i]) + "' (mospec's " + std::string(kind.name) +
                   " controller takes " + accepted_units(kind) + ")");
      ok = false;
    }
  }

  // What the kind refuses, and what it does not know.
  for (const RefusedProperty& r : kind.refused) {
    read.insert(r.property);
    for (TermId o : st.graph.objects(c, property_term(r.property))) {
      st.error(st.graph.where(c, property_term(r.property), o), std::string(r.code),
               ctrl + " states `" + std::string(r.property) + "` '" + st.str(o) +
                   "'; mospec cannot honour it: " + std::string(r.why));
      ok = false;
    }
  }
  std::pmr::set<std::string_view> seen{&st.arena};  // views of the term table's IRIs
  st.graph.each_statement(c, [&](const Graph::Statement& statement) {
    const std::string_view p = st.graph.str(statement.predicate);
    if (!p.starts_with(kind.vocabulary)) return;
    const std::string_view local = p.substr(kind.vocabulary.size());
    if (read.count(local) || !seen.insert(p).second) return;
    std::string known;
    for (std::string_view r : read) known.append(known.empty() ? "" : ", ").append(r);
    st.error(statement.where.known() ? statement.where : st.where(c), "unsupported-property",
             ctrl + " states `" + std::string(local) + "`, which mospec's " +
                 std::string(kind.name) + " controller does not implement (it reads " + known +
                 "); remove it");
    ok = false;
  });

  // The runtime's own check of the values (reported in its words). The step is
  // added even when something was refused, so that its control signal has its
  // producer and later passes report nothing that follows from this.
  if (ok) {
    try {
      kind.instantiate(s.parameters, iri.c_str());
    } catch (const Error& e) {
      st.error(c, "invalid-controller", e.diagnostic().message);
    }
  }
  if (auto it = st.active_of_controller.find(c.index); it != st.active_of_controller.end())
    s.in.push_back(it->second);
  if (kind.has_state()) {
    st.program.controller_states.resize(controller_kinds().size());
    s.state = st.program.controller_states[static_cast<size_t>(index)]++;
  }
  st.add_step(std::move(s));
}

}  // namespace

void lower_controllers(State& st) {
  const auto kinds = controller_kinds();
  // A controller of two kinds would be two laws writing one signal: refused.
  std::map<uint32_t, int> kind_of;
  for (size_t k = 0; k < kinds.size(); ++k) {
    for (TermId c : st.instances(kinds[k].class_iri())) {
      auto [it, fresh] = kind_of.emplace(c.index, static_cast<int>(k));
      if (fresh) continue;
      const ControllerKind& first = kinds[static_cast<size_t>(it->second)];
      st.error(c, "ambiguous-controller",
               "the controller '" + st.str(c) + "' is both " + article(first.type) +
                   std::string(first.type) + " and " + article(kinds[k].type) +
                   std::string(kinds[k].type) +
                   "; mospec runs one law per controller: give it one of these classes");
      it->second = -1;
    }
  }
  for (size_t k = 0; k < kinds.size(); ++k) {
    for (TermId c : st.instances(kinds[k].class_iri())) {
      if (kind_of.at(c.index) == static_cast<int>(k))
        lower_controller(st, c, kinds[k], static_cast<int>(k));
    }
  }
}

}  // namespace mospec::ir::lowering
