// evaluate: a constraint's satisfaction and error (or an assignment's output)
// from its quantity, gated by the running flag after it, if any.
#include "ir/kinds/kinds.hpp"

namespace mospec::ir::kinds {

void prepare_evaluate(Machine& m, const Step& st, size_t index) {
  m.evaluators[index] =
      std::make_unique<runtime::ConstraintEvaluator>(st.constraint, st.name.c_str());
}

void interpret_evaluate(Machine& m, const Step& st, size_t index, const robot::MeasuredState&,
                        robot::Command&) noexcept {
  bool satisfied = false;
  const bool active = st.in.size() < 2 || m.s.flags[m.slot(st.in[1])] != 0;
  runtime::steps::evaluate(*m.evaluators[index], m.s.scalars[m.slot(st.in[0])], active, satisfied,
                           m.s.scalars[m.slot(st.out[1])]);
  m.s.flags[m.slot(st.out[0])] = satisfied;
}

void emit_evaluate(const EmitContext& ctx, const Step& st, size_t index, mustache::Data& s) {
  put(s, "evaluator", ctx.member(index));
  put(s, "in0", ctx.in(st, 0));
  put(s, "active", st.in.size() < 2 ? std::string("true") : ctx.in(st, 1));
  put(s, "out0", ctx.out(st, 0));
  put(s, "out1", ctx.out(st, 1));
}

Json constraint_json(const runtime::ConstraintSpec& spec) {
  Json c;
  c["relation"] = relation_name(spec.kind);
  c["reference"] = spec.reference;
  c["threshold"] = spec.threshold;
  c["lower"] = spec.lower;
  c["upper"] = spec.upper;
  c["tolerance"] = spec.tolerance;
  return c;
}

Signature signature_evaluate(const Step& st, const Program&) {
  using T = DataType;
  if (st.in.size() == 2) return {{T::Scalar, T::Flag}, {T::Flag, T::Scalar}};
  return {{T::Scalar}, {T::Flag, T::Scalar}};
}

void print_evaluate(const Step& st, StepJson& j) {
  Json c = constraint_json(st.constraint);
  static constexpr const char* kSources[] = {"none", "stated", "default"};
  c["tolerance-source"] = kSources[static_cast<int>(st.tolerance_source)];
  j.e["constraint"] = std::move(c);
}

// The constraint's value, error and satisfaction (an assignment's output and
// satisfaction), and a bilateral constraint's bounds, named after the
// constraint, not the evaluator.
void log_evaluate(const Program& p, const Step& st, std::vector<LogColumn>& log) {
  const bool assignment = st.constraint.kind == runtime::ConstraintKind::Assignment;
  const Data& sat = p.data[static_cast<size_t>(st.out[0])];
  const std::string name = lowering::local_name(sat.iri.substr(0, sat.iri.find('#')));
  const int value = assignment ? st.out[1] : st.in[0];
  const std::string& unit = p.data[static_cast<size_t>(value)].unit;
  log.push_back({name + ".value", unit, value});
  if (!assignment)
    log.push_back({name + ".error", p.data[static_cast<size_t>(st.out[1])].unit, st.out[1]});
  log.push_back({name + ".satisfied", "", st.out[0]});
  if (st.lower_bound >= 0 && st.upper_bound >= 0) {
    log.push_back({name + ".lower", unit, st.lower_bound});
    log.push_back({name + ".upper", unit, st.upper_bound});
  }
}

void verify_evaluate(const Step& st, const Program& p, Findings& f) {
  for (int bound : {st.lower_bound, st.upper_bound}) {
    if (bound == -1) continue;
    if (!f.valid_datum(bound) || p.data[static_cast<size_t>(bound)].type != DataType::Scalar)
      f.step(st, "logs bound " + f.describe(bound) + ", which must be a scalar");
  }
  // The error and the bounds are in the quantity's unit (an assignment's
  // output is the quantity itself).
  const auto unit_of = [&](int d) -> const std::string* {
    return f.valid_datum(d) ? &p.data[static_cast<size_t>(d)].unit : nullptr;
  };
  const std::string* unit = st.in.empty() ? nullptr : unit_of(st.in[0]);
  if (unit && !unit->empty()) {
    const bool assignment = st.constraint.kind == runtime::ConstraintKind::Assignment;
    const auto same_unit = [&](int d, const char* what) {
      const std::string* u = unit_of(d);
      if (u && !u->empty() && *u != *unit)
        f.step(st, std::string(what) + " " + f.describe(d) + " is in '" + *u +
                       "'; expected its quantity's unit '" + *unit + "'");
    };
    if (!assignment && st.out.size() > 1) same_unit(st.out[1], "error");
    if (st.lower_bound >= 0) same_unit(st.lower_bound, "lower bound");
    if (st.upper_bound >= 0) same_unit(st.upper_bound, "upper bound");
  }
  if ((st.lower_bound >= 0 || st.upper_bound >= 0) &&
      st.constraint.kind != runtime::ConstraintKind::Bilateral)
    f.step(st, "has bound data, but its constraint is not bilateral");
}

// An assignment's running flag after its value: what it writes drives a
// solver only while its motion runs. An error evaluation drives nothing.
int gate_evaluate(const Step& st) {
  return st.constraint.kind == runtime::ConstraintKind::Assignment && st.in.size() == 2 ? 1 : -1;
}

}  // namespace mospec::ir::kinds
