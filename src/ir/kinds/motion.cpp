// guarded-motion: a motion's state from its pre-, per- and post-conditions;
// any-of: a flag that is any of several.
#include <array>

#include "ir/kinds/kinds.hpp"

namespace mospec::ir::kinds {

void interpret_guarded_motion(Machine& m, const Step& st, size_t, const robot::MeasuredState&,
                              robot::Command&) noexcept {
  std::array<bool, kMaxGuards> when{}, whiles{}, until{};
  const auto n_when = static_cast<size_t>(st.n_when);
  const auto n_while = static_cast<size_t>(st.n_while);
  const size_t n_until = st.in.size() - n_when - n_while;
  const auto flag = [&](size_t k) { return m.s.flags[m.slot(st.in[k])] != 0; };
  for (size_t k = 0; k < n_when; ++k) when[k] = flag(k);
  for (size_t k = 0; k < n_while; ++k) whiles[k] = flag(n_when + k);
  for (size_t k = 0; k < n_until; ++k) until[k] = flag(n_when + n_while + k);
  std::uint8_t ended = 0;
  m.s.flags[m.slot(st.out[0])] = runtime::steps::guarded_motion(
      m.motion_states[static_cast<size_t>(st.state)], std::span<const bool>(when.data(), n_when),
      std::span<const bool>(whiles.data(), n_while), std::span<const bool>(until.data(), n_until),
      ended);
  m.s.events[m.slot(st.out[1])] = static_cast<char>(ended);
}

void emit_guarded_motion(const EmitContext& ctx, const Step& st, size_t, mustache::Data& s) {
  const auto n_when = static_cast<size_t>(st.n_when);
  const auto n_while = static_cast<size_t>(st.n_while);
  put(s, "n_when", std::to_string(n_when));
  put(s, "n_while", std::to_string(n_while));
  put(s, "n_until", std::to_string(st.in.size() - n_when - n_while));
  put(s, "when", join_inputs(ctx, st, 0, n_when, ", "));
  put(s, "whiles", join_inputs(ctx, st, n_when, n_when + n_while, ", "));
  put(s, "until", join_inputs(ctx, st, n_when + n_while, st.in.size(), ", "));
  put(s, "state_slot", std::to_string(st.state));
  put(s, "out0", ctx.out(st, 0));
  put(s, "out1", ctx.out(st, 1));
}

void interpret_any_of(Machine& m, const Step& st, size_t, const robot::MeasuredState&,
                      robot::Command&) noexcept {
  bool any = false;
  for (int d : st.in) any = any || m.s.flags[m.slot(d)] != 0;
  m.s.flags[m.slot(st.out[0])] = any;
}

void emit_any_of(const EmitContext& ctx, const Step& st, size_t, mustache::Data& s) {
  put(s, "any", join_inputs(ctx, st, 0, st.in.size(), " || "));
  put(s, "out0", ctx.out(st, 0));
}

Signature signature_guarded_motion(const Step& st, const Program&) {
  return {Types(st.in.size(), DataType::Flag), {DataType::Flag, DataType::Event}};
}

void verify_guarded_motion(const Step& st, const Program& p, Findings& f) {
  const int n_until = static_cast<int>(st.in.size()) - st.n_when - st.n_while;
  if (st.n_when < 0 || st.n_while < 0 || n_until < 0)
    f.step(st, std::to_string(st.n_when) + " when- and " + std::to_string(st.n_while) +
                   " while-guards of " + std::to_string(st.in.size()) + " inputs");
  if (st.n_when > kMaxGuards || st.n_while > kMaxGuards || n_until > kMaxGuards)
    f.step(st, "has " + std::to_string(st.n_when) + " when-, " + std::to_string(st.n_while) +
                   " while- and " + std::to_string(n_until) + " until-guards; at most " +
                   std::to_string(kMaxGuards) + " each");
  if (st.n_goal_whiles < 0 || static_cast<size_t>(st.n_goal_whiles) > st.goals.size())
    f.step(st, std::to_string(st.n_goal_whiles) + " goal-whiles of " +
                   std::to_string(st.goals.size()) + " goals");
  for (int g : st.goals) {
    if (!f.valid_datum(g) || p.data[static_cast<size_t>(g)].type != DataType::Flag)
      f.step(st, "goal " + f.describe(g) + " must be a constraint's satisfied flag");
  }
}

void print_guarded_motion(const Step& st, StepJson& j) {
  j.e["when"] = st.n_when;
  j.e["while"] = st.n_while;
  j.e["goals"] = st.goals;
  j.e["goal-whiles"] = st.n_goal_whiles;
}

Signature signature_any_of(const Step& st, const Program&) {
  return {Types(st.in.size(), DataType::Flag), {DataType::Flag}};
}

void log_guarded_motion(const Program& p, const Step& st, std::vector<LogColumn>& log) {
  log.push_back(step_column(p, st, ".running", st.out[0], robot::LogColumnKind::Value));
  log.push_back(step_column(p, st, ".ended", st.out[1], robot::LogColumnKind::Event));
}

}  // namespace mospec::ir::kinds
