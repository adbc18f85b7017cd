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

}  // namespace mospec::ir::kinds
