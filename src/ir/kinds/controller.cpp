// controller: one instance of the controller registry (controllers.hpp): its
// runtime model on its signals, gated by the running flag after them, if any.
#include <array>

#include "ir/kinds/kinds.hpp"

namespace mospec::ir::kinds {

void prepare_controller(Machine& m, const Step& st, size_t index) {
  m.controllers[index] = controller_kinds()[static_cast<size_t>(st.controller)].instantiate(
      st.parameters, st.name.c_str());
}

void interpret_controller(Machine& m, const Step& st, size_t index,
                          const robot::MeasuredState& state, robot::Command&) noexcept {
  const size_t n = controller_kinds()[static_cast<size_t>(st.controller)].in.size();
  std::array<double, kMaxControllerSignals> signals{};
  for (size_t k = 0; k < n; ++k) signals[k] = m.s.scalars[m.slot(st.in[k])];
  const bool active = st.in.size() <= n || m.s.flags[m.slot(st.in[n])] != 0;
  m.s.scalars[m.slot(st.out[0])] =
      m.controllers[index]->step(signals.data(), state.clock.dt, active);
}

// The kernel called as the registry declares it: (model, [state,] signals...,
// [dt,] active).
void emit_controller(const EmitContext& ctx, const Step& st, size_t index, mustache::Data& s) {
  const ControllerKind& k = controller_kinds()[static_cast<size_t>(st.controller)];
  std::string call = "rt::";
  call.append(k.kernel).append("(m.").append(ctx.member(index));
  if (k.has_state()) {
    call.append(", d.").append(k.name).append("[").append(std::to_string(st.state));
    call.append("]");
  }
  for (size_t i = 0; i < k.in.size(); ++i) call.append(", ").append(ctx.in(st, i));
  if (k.kernel_takes_dt) call.append(", state.clock.dt");
  call.append(", ").append(st.in.size() > k.in.size() ? ctx.in(st, k.in.size()) : "true");
  call.append(")");
  put(s, "call", call);
  put(s, "out0", ctx.out(st, 0));
}

}  // namespace mospec::ir::kinds
