// read-clock: the control clock's time, the first step of every tick.
#include "ir/kinds/kinds.hpp"

namespace mospec::ir::kinds {

void interpret_read_clock(Machine& m, const Step& st, size_t, const robot::MeasuredState& state,
                          robot::Command&) noexcept {
  m.s.scalars[m.slot(st.out[0])] = state.clock.t;
}

void emit_read_clock(const EmitContext& ctx, const Step& st, size_t, mustache::Data& s) {
  put(s, "out0", ctx.out(st, 0));
}

Signature signature_read_clock(const Step&, const Program&) {
  return {{}, {DataType::Scalar}};
}

}  // namespace mospec::ir::kinds
