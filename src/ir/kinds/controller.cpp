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

Signature signature_controller(const Step& st, const Program&) {
  const auto kinds = controller_kinds();
  if (st.controller < 0 || static_cast<size_t>(st.controller) >= kinds.size())
    return {{},
            {},
            true,
            "names controller kind " + std::to_string(st.controller) + ", which does not exist"};
  // The signals, then (when its motion gates it) the running flag.
  const ControllerKind& k = kinds[static_cast<size_t>(st.controller)];
  Signature s{Types(k.in.size(), DataType::Scalar), {DataType::Scalar}};
  if (st.in.size() == k.in.size() + 1) s.in.push_back(DataType::Flag);
  return s;
}

void verify_controller(const Step& st, const Program& p, Findings& f) {
  if (st.controller < 0 || static_cast<size_t>(st.controller) >= controller_kinds().size())
    return;  // the signature says so
  const ControllerKind& k = controller_kinds()[static_cast<size_t>(st.controller)];
  if (st.parameters.size() != k.parameters.size())
    f.step(st, "has " + std::to_string(st.parameters.size()) + " parameters; a " +
                   std::string(k.name) + " controller has " + std::to_string(k.parameters.size()));
  const int n = p.controller_state_count(st.controller);
  if (k.has_state() && (st.state < 0 || st.state >= n))
    f.step(st, "has state slot " + std::to_string(st.state) + "; expected 0.." +
                   std::to_string(n - 1) + " (the program's " + std::string(k.name) + " states)");
  if (!k.has_state() && st.state != -1)
    f.step(st, "has state slot " + std::to_string(st.state) + "; a " + std::string(k.name) +
                   " controller keeps no state (expected -1)");
}

// The parameters the model states, by their JSON keys, under the kind's name.
void print_controller(const Step& st, StepJson& j) {
  if (st.controller < 0 || static_cast<size_t>(st.controller) >= controller_kinds().size()) return;
  const ControllerKind& k = controller_kinds()[static_cast<size_t>(st.controller)];
  Json params = Json::object();
  for (size_t i = 0; i < k.parameters.size() && i < st.parameters.size(); ++i) {
    if (!k.parameters[i].json.empty()) params[std::string(k.parameters[i].json)] = st.parameters[i];
  }
  j.e[std::string(k.name)] = std::move(params);
}

void log_controller(const Program& p, const Step& st, std::vector<LogColumn>& log) {
  log.push_back(step_column(p, st, ".output", st.out[0], robot::LogColumnKind::Value));
}

// The running flag after the signals, when a handler gates it.
int gate_controller(const Step& st) {
  const size_t n = controller_kinds()[static_cast<size_t>(st.controller)].in.size();
  return st.in.size() == n + 1 ? static_cast<int>(n) : -1;
}

}  // namespace mospec::ir::kinds
