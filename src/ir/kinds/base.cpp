// base-force-distribution and base-velocity-composition: the KELO base's
// solvers (Eq. 2-3): the platform wrench distributed to the hub torques, and
// the platform twist composed from the pivots and wheel rates.
#include "ir/kinds/kinds.hpp"

namespace mospec::ir {

Machine::Base::Base(const BaseSolver& s) : model(kelo_config(s)), data(model) {}

namespace kinds {

// in[0] is the platform wrench; the rest are the running flags of the
// motions that drive the base (none running: it brakes and holds).
void interpret_base_force_distribution(Machine& m, const Step& st, size_t,
                                       const robot::MeasuredState& state,
                                       robot::Command& command) noexcept {
  namespace steps = runtime::steps;
  bool driven = st.in.size() == st.drivers();  // no gates: always
  for (size_t k = st.drivers(); k < st.in.size(); ++k)
    driven = driven || m.s.flags[m.slot(st.in[k])] != 0;
  Machine::Base& base = *m.base;
  if (!driven) {
    steps::base_hold(base.model, base.data, state.pivot_q, state.wheel_qd, command.wheel_tau);
  } else {
    steps::base_force_distribution(base.model, base.data, state.pivot_q,
                                   m.s.wrenches[m.slot(st.in[0])], command.wheel_tau);
  }
}

void emit_base_force_distribution(const EmitContext& ctx, const Step& st, size_t,
                                  mustache::Data& s) {
  put(s, "in0", ctx.in(st, 0));
  const std::string gates = join_inputs(ctx, st, st.drivers(), st.in.size(), " || ");
  put(s, "gated", !gates.empty());
  put(s, "gates", gates);
  put(s, "indent", gates.empty() ? "  " : "    ");
}

void interpret_base_velocity_composition(Machine& m, const Step& st, size_t,
                                         const robot::MeasuredState& state,
                                         robot::Command&) noexcept {
  runtime::steps::base_velocity(m.base->model, m.base->data, state.pivot_q, state.wheel_qd,
                                m.s.twists[m.slot(st.out[0])]);
}

void emit_base_velocity_composition(const EmitContext& ctx, const Step& st, size_t,
                                    mustache::Data& s) {
  put(s, "out0", ctx.out(st, 0));
}

Signature signature_base_force_distribution(const Step& st, const Program&) {
  Signature s{{DataType::Wrench}, {}};
  for (size_t k = 1; k < st.in.size(); ++k) s.in.push_back(DataType::Flag);
  return s;
}

void verify_base_force_distribution(const Step& st, const Program& p, Findings& f) {
  verify_base(st, p, f);
  verify_gates(st, p, f);
}

void verify_base(const Step& st, const Program& p, Findings& f) {
  if (!p.base) f.step(st, "uses the base solver, but the program has none");
}

Signature signature_base_velocity_composition(const Step&, const Program&) {
  return {{}, {DataType::Twist}};
}

// The platform wrench [f_x, f_y, m_z] the drives are to exert.
void log_base_force_distribution(const Program&, const Step& st, std::vector<LogColumn>& log) {
  const std::string base = lowering::local_name(st.iri);
  log.push_back({base + ".fx", "N", st.in[0], 3});
  log.push_back({base + ".fy", "N", st.in[0], 4});
  log.push_back({base + ".mz", "N-M", st.in[0], 2});
}

// The platform's measured planar twist [v_x, v_y, w_z].
void log_base_velocity_composition(const Program&, const Step& st, std::vector<LogColumn>& log) {
  const std::string base = lowering::local_name(st.iri);
  log.push_back({base + ".vx", "M-PER-SEC", st.out[0], 3});
  log.push_back({base + ".vy", "M-PER-SEC", st.out[0], 4});
  log.push_back({base + ".wz", "RAD-PER-SEC", st.out[0], 2});
}

}  // namespace kinds
}  // namespace mospec::ir
