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

// One controller of kind `kind` (index `index`) being lowered to a step; what
// it cannot honour is reported, and clears `ok`.
class ControllerLowering {
 public:
  ControllerLowering(State& st, TermId c, const ControllerKind& kind, int index)
      : st_(st),
        c_(c),
        kind_(kind),
        index_(index),
        iri_(st.str(c)),
        ctrl_("the controller '" + iri_ + "'"),
        port_datum_(&st.arena),
        read_(&st.arena) {}

  void lower() {
    st_.pending_iri = iri_;
    if (!read_signals()) return;
    for (size_t f = 0; f < kind_.parameters.size(); ++f) read_parameter(f);
    if (!kind_.units.empty()) check_units();
    check_refused();
    check_unknown();
    add_step();
  }

 private:
  // A property of the kind's vocabulary, by its local name (the IRI built in
  // one allocation; absent when the model never states it).
  TermId property_term(std::string_view property) const {
    std::string iri;
    iri.reserve(kind_.vocabulary.size() + property.size());
    iri.append(kind_.vocabulary).append(property);
    return st_.term(iri);
  }
  // The one value of a property (several: refused by State::object; none: nullopt).
  std::optional<TermId> value_of(std::string_view property) const {
    return st_.object(c_, property_term(property));
  }

  // Signals: the scalar inputs, then the control signal; the step reading
  // and writing them. False when one is missing (reported).
  bool read_signals() {
    std::vector<std::optional<TermId>> signals;
    std::vector<std::string_view> properties(kind_.in.begin(), kind_.in.end());
    properties.push_back(kind_.out);
    bool all_signals = true;
    for (std::string_view p : properties) {
      signals.push_back(value_of(p));
      all_signals = all_signals && signals.back().has_value();
    }
    if (!all_signals) {
      std::string needs;
      for (size_t i = 0; i < properties.size(); ++i) {
        needs.append(i == 0 ? "" : i + 1 == properties.size() ? " and " : ", ");
        needs.append(article(properties[i])).append(properties[i]);
      }
      st_.error(c_, "missing-property", ctrl_ + " needs " + needs);
      return false;
    }
    s_ = st_.step_for(StepKind::Controller, c_);
    s_.controller = index_;
    s_.parameters = kind_.defaults();
    s_.parameters_where.assign(kind_.parameters.size(), s_.where);
    for (size_t i = 0; i < kind_.in.size(); ++i) {
      s_.in.push_back(st_.datum(*signals[i], DataType::Scalar, c_, std::string(kind_.in[i])));
      port_datum_[kind_.in[i]] = s_.in.back();
    }
    s_.out = {st_.datum(*signals.back(), DataType::Scalar, c_, std::string(kind_.out))};
    port_datum_[kind_.out] = s_.out[0];
    read_.insert(properties.begin(), properties.end());
    return true;
  }

  // Parameter f, as the kind declares it: a literal, a constant quantity, or
  // the runtime's default.
  void read_parameter(size_t f) {
    const ControllerParameter& p = kind_.parameters[f];
    if (p.source == ParameterSource::Fixed) return;
    const std::string name(p.property);
    read_.insert(p.property);
    if (!p.only_with.empty() && !st_.graph.has_type(c_, property_term(p.only_with))) {
      // Stated without the class that gives it meaning: not read, so refused.
      const std::vector<TermId> stated = st_.graph.objects(c_, property_term(p.property));
      if (!stated.empty()) {
        st_.error(st_.graph.where(c_, property_term(p.property), stated[0]), "unsupported-property",
                  ctrl_ + " states `" + name + "`, which only " + article(p.only_with) +
                      std::string(p.only_with) + " has; add that class or remove `" + name + "`");
        ok_ = false;
      }
      return;
    }
    const auto term = value_of(p.property);
    if (!term) {
      if (p.required && ok_) {
        st_.error(c_, "missing-property",
                  ctrl_ + " needs " +
                      (p.source == ParameterSource::Literal ? "a numeric " + name
                                                            : article(name) + name));
        ok_ = false;
      }
      return;
    }
    if (p.source == ParameterSource::Literal) {
      read_literal(f, name, *term);
    } else {
      read_constant(f, name, *term);
    }
  }

  void read_literal(size_t f, const std::string& name, TermId term) {
    const TermId property = property_term(kind_.parameters[f].property);
    if (const auto v = st_.number(term)) {
      s_.parameters[f] = *v;
      s_.parameters_where[f] = st_.graph.where(c_, property, term);
    } else if (st_.graph.terms()[term].is_literal()) {
      st_.error(st_.graph.where(c_, property, term), "invalid-number",
                ctrl_ + " has " + name + " " + st_.literal_text(term) +
                    ", which is not a finite number of its datatype (xsd:double: e.g. 100, "
                    "+100.0, -1.5e2)");
      ok_ = false;
    } else {
      st_.error(c_, "missing-property", ctrl_ + " needs a numeric " + name);
      ok_ = false;
    }
  }

  // A constant quantity: its value, in its unit.
  void read_constant(size_t f, const std::string& name, TermId term) {
    const std::string_view property = kind_.parameters[f].property;
    const int d = st_.datum(term, DataType::Scalar, c_, name);
    port_datum_[property] = d;
    const Data& q = st_.program.data[static_cast<size_t>(d)];
    if (!q.value.empty()) {
      s_.parameters[f] = q.value[0];
      s_.parameters_where[f] = st_.graph.where(c_, property_term(property), term);
      return;
    }
    const auto lit = st_.object(term, kQudt + "value");
    if (lit && st_.graph.terms()[*lit].is_literal()) {
      st_.error(st_.where(term, kQudt + "value", *lit), "invalid-number",
                "the " + name + " '" + q.iri + "' of " + ctrl_ + " has the value " +
                    st_.literal_text(*lit) + ", which is not a finite number of its datatype");
    } else {
      st_.error(term, "not-a-constant",
                "the " + name + " '" + q.iri + "' of " + ctrl_ +
                    " has no value; a controller parameter is a constant");
    }
    ok_ = false;
  }

  std::string unit_of(std::string_view port) const {
    auto it = port_datum_.find(port);
    return it == port_datum_.end() ? std::string()
                                   : st_.program.data[static_cast<size_t>(it->second)].unit;
  }
  SourceLoc where_of(std::string_view port) const {
    auto it = port_datum_.find(port);
    return it == port_datum_.end() ? st_.where(c_)
                                   : st_.program.data[static_cast<size_t>(it->second)].where;
  }

  // Units: the first port's unit picks the kind's combination; every other
  // port must have that combination's unit.
  void check_units() {
    const std::string_view key = kind_.unit_ports[0];
    const std::string key_unit = unit_of(key);
    const std::vector<std::string_view>* row = nullptr;
    for (const auto& r : kind_.units) {
      if (r[0] == key_unit) row = &r;
    }
    if (row == nullptr && port_datum_.count(key)) {
      st_.error(where_of(key), "wrong-unit",
                ctrl_ + ": its " + std::string(key) +
                    (key_unit.empty() ? " has no unit" : " is in '" + key_unit + "'") +
                    ", which mospec's " + std::string(kind_.name) +
                    " controller does not take (it takes " + accepted_units(kind_) + ")");
      ok_ = false;
    }
    for (size_t i = 1; row != nullptr && i < kind_.unit_ports.size(); ++i) {
      const std::string_view port = kind_.unit_ports[i];
      if (!port_datum_.count(port)) continue;  // an optional parameter the model leaves out
      const std::string unit = unit_of(port);
      if (unit == (*row)[i]) continue;
      st_.error(where_of(port), "wrong-unit",
                ctrl_ + ": its " + std::string(port) +
                    (unit.empty() ? " has no unit" : " is in '" + unit + "'") + ", but with its " +
                    std::string(key) + " in '" + key_unit + "' it must be in '" +
                    std::string((*row)[i]) + "' (mospec's " + std::string(kind_.name) +
                    " controller takes " + accepted_units(kind_) + ")");
      ok_ = false;
    }
  }

  // What the kind refuses.
  void check_refused() {
    for (const RefusedProperty& r : kind_.refused) {
      read_.insert(r.property);
      for (TermId o : st_.graph.objects(c_, property_term(r.property))) {
        st_.error(st_.graph.where(c_, property_term(r.property), o), std::string(r.code),
                  ctrl_ + " states `" + std::string(r.property) + "` '" + st_.str(o) +
                      "'; mospec cannot honour it: " + std::string(r.why));
        ok_ = false;
      }
    }
  }

  // What the kind does not know: a property of its vocabulary it never reads.
  void check_unknown() {
    std::pmr::set<std::string_view> seen{&st_.arena};  // views of the term table's IRIs
    st_.graph.each_statement(c_, [&](const Graph::Statement& statement) {
      const std::string_view p = st_.graph.str(statement.predicate);
      if (!p.starts_with(kind_.vocabulary)) return;
      const std::string_view local = p.substr(kind_.vocabulary.size());
      if (read_.count(local) || !seen.insert(p).second) return;
      std::string known;
      for (std::string_view r : read_) known.append(known.empty() ? "" : ", ").append(r);
      st_.error(statement.where.known() ? statement.where : st_.where(c_), "unsupported-property",
                ctrl_ + " states `" + std::string(local) + "`, which mospec's " +
                    std::string(kind_.name) + " controller does not implement (it reads " + known +
                    "); remove it");
      ok_ = false;
    });
  }

  // The runtime's own check of the values (reported in its words). The step is
  // added even when something was refused, so that its control signal has its
  // producer and later passes report nothing that follows from this.
  void add_step() {
    if (ok_) {
      try {
        kind_.instantiate(s_.parameters, iri_.c_str());
      } catch (const Error& e) {
        st_.error(c_, "invalid-controller", e.diagnostic().message);
      }
    }
    if (auto it = st_.active_of_controller.find(c_.index); it != st_.active_of_controller.end())
      s_.in.push_back(it->second);
    if (kind_.has_state()) {
      st_.program.controller_states.resize(controller_kinds().size());
      s_.state = st_.program.controller_states[static_cast<size_t>(index_)]++;
    }
    st_.add_step(std::move(s_));
  }

  State& st_;
  TermId c_;
  const ControllerKind& kind_;
  int index_;
  const std::string iri_;
  const std::string ctrl_;  // "the controller '<iri>'", as messages name it
  bool ok_ = true;
  Step s_;
  // (Scratch maps and sets: from the lowering's arena.)
  std::pmr::map<std::string_view, int> port_datum_;  // unit port -> datum
  std::pmr::set<std::string_view> read_;             // the properties read
};

// One controller of kind `kind` (index `index`), lowered to a step; what it
// cannot honour is reported.
void lower_controller(State& st, TermId c, const ControllerKind& kind, int index) {
  ControllerLowering(st, c, kind, index).lower();
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
