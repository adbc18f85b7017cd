// operator: one instance of the operator registry (operators.hpp), its kernel
// called as the registry declares it.
#include "ir/kinds/kinds.hpp"

namespace mospec::ir::kinds {

void prepare_operator(Machine& m, const Step& st, size_t index) {
  m.operator_slot_offset[index] = m.operator_slots.size();
  for (int d : st.in) m.operator_slots.push_back(static_cast<int>(m.slot(d)));
}

void interpret_operator(Machine& m, const Step& st, size_t index, const robot::MeasuredState&,
                        robot::Command&) noexcept {
  const OperatorKind& k = operator_kinds()[static_cast<size_t>(st.op)];
  k.interpret(m.s, m.operator_slots.data() + m.operator_slot_offset[index],
              static_cast<int>(m.slot(st.out[0])));
}

// The kernel returns the output, or writes it through its last parameter.
void emit_operator(const EmitContext& ctx, const Step& st, size_t, mustache::Data& s) {
  const OperatorKind& k = operator_kinds()[static_cast<size_t>(st.op)];
  std::string args;
  for (size_t i = 0; i < st.in.size(); ++i) {
    if (i) args.append(", ");
    args.append(ctx.in(st, i));
  }
  if (!k.kernel_returns) args.append(", ").append(ctx.out(st, 0));
  put(s, "returns", k.kernel_returns);
  put(s, "kernel", std::string(k.kernel));
  put(s, "args", args);
  put(s, "out0", ctx.out(st, 0));
}

Signature signature_operator(const Step& st, const Program&) {
  const auto kinds = operator_kinds();
  if (st.op < 0 || static_cast<size_t>(st.op) >= kinds.size())
    return {
        {}, {}, true, "names operator kind " + std::to_string(st.op) + ", which does not exist"};
  const OperatorKind& k = kinds[static_cast<size_t>(st.op)];
  Signature s{{}, {k.out.type}};
  for (const OperatorPort& port : k.in) s.in.push_back(port.type);
  return s;
}

// The frame rules the kernel's arithmetic assumes, as lowering established
// them, still hold between the data the step reads and writes. A rule on a
// frame's origin needs the frames' origins, which only the model knows:
// lowering checks those. A datum without the frame stated is a hand-built
// program's, judged by its type alone.
void verify_operator(const Step& st, const Program& p, Findings& f) {
  if (st.op < 0 || static_cast<size_t>(st.op) >= operator_kinds().size()) return;
  const OperatorKind& k = operator_kinds()[static_cast<size_t>(st.op)];
  const auto port_datum = [&](int port) -> const Data* {
    const auto i = static_cast<size_t>(port);
    const int d = i < st.in.size() ? st.in[i] : st.out.empty() ? -1 : st.out[0];
    return f.valid_datum(d) ? &p.data[static_cast<size_t>(d)] : nullptr;
  };
  for (const FrameRule& rule : k.frames) {
    if (rule.rhs_origin) continue;
    const Data* lhs = port_datum(rule.lhs_port);
    const Data* rhs = port_datum(rule.rhs_port);
    if (!lhs || !rhs) continue;
    const std::string& got = frame_field(*lhs, rule.lhs_field);
    const std::string& want = frame_field(*rhs, rule.rhs_field);
    if (got.empty() || want.empty() || got == want) continue;
    f.step(st, "breaks its frame rule '" + rule.text +
                   "': " + std::string(to_string(rule.lhs_field)) + " of '" + lhs->name + "' is '" +
                   got + "'; expected '" + want + "'");
  }
}

}  // namespace mospec::ir::kinds
