// level-monitor and edge-monitor: whether an error is within its tolerance
// (a flag), or the ticks it crosses it (an event), gated by the running flag
// after the error when a handler lists one. One pair of hooks serves both.
#include "ir/kinds/kinds.hpp"

namespace mospec::ir::kinds {

void interpret_monitor(Machine& m, const Step& st, size_t, const robot::MeasuredState&,
                       robot::Command&) noexcept {
  namespace steps = runtime::steps;
  const bool running = st.in.size() < 2 || m.s.flags[m.slot(st.in[1])] != 0;
  runtime::MonitorState& state = m.monitor_states[static_cast<size_t>(st.state)];
  const double error = m.s.scalars[m.slot(st.in[0])];
  const size_t out = m.slot(st.out[0]);
  if (st.kind == StepKind::LevelMonitor)
    m.s.flags[out] = steps::level_monitor(state, error, st.constraint.tolerance, running);
  else
    m.s.events[out] = static_cast<char>(
        steps::edge_monitor(state, error, st.constraint.tolerance, st.edges, running));
}

void emit_monitor(const EmitContext& ctx, const Step& st, size_t index, mustache::Data& s) {
  put(s, "state_slot", std::to_string(st.state));
  put(s, "in0", ctx.in(st, 0));
  put(s, "tolerance", ctx.member(index));
  put(s, "edges",
      std::string(st.edges == runtime::Edges::Rising    ? "Rising"
                  : st.edges == runtime::Edges::Falling ? "Falling"
                                                        : "Both"));
  put(s, "running", st.in.size() < 2 ? std::string("true") : ctx.in(st, 1));
  put(s, "out0", ctx.out(st, 0));
}

Signature signature_monitor(const Step& st, const Program&) {
  using T = DataType;
  const T out = st.kind == StepKind::LevelMonitor ? T::Flag : T::Event;
  if (st.in.size() == 2) return {{T::Scalar, T::Flag}, {out}};
  return {{T::Scalar}, {out}};
}

void verify_monitor(const Step& st, const Program&, Findings& f) {
  if (st.kind != StepKind::EdgeMonitor) return;
  const auto e = static_cast<int>(st.edges);
  if (e < 1 || e > 3)
    f.step(st, "reports edges " + std::to_string(e) + "; expected 1 (rising), 2 (falling) or 3");
}

void print_monitor(const Step& st, StepJson& j) {
  j.e["constraint"] = constraint_json(st.constraint);
  if (st.kind == StepKind::EdgeMonitor) {
    static constexpr const char* kEdges[] = {"", "rising", "falling", "both"};
    j.e["edges"] = kEdges[static_cast<int>(st.edges) & 3];
  }
}

// What a monitor signals is latched: a log that keeps every N-th tick shows it
// in the next row it keeps.
void log_monitor(const Program& p, const Step& st, std::vector<LogColumn>& log) {
  const bool level = st.kind == StepKind::LevelMonitor;
  log.push_back(step_column(p, st, level ? ".flag" : ".event", st.out[0],
                            level ? robot::LogColumnKind::Flag : robot::LogColumnKind::Event));
}

}  // namespace mospec::ir::kinds
