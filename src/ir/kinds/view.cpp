// view-read and view-write: one component of a pose, twist or wrench as a
// scalar, and scalars written into the components of a twist or wrench.
#include "ir/kinds/kinds.hpp"

namespace mospec::ir::kinds {

namespace {

void verify_view_components(const Step& st, Findings& f) {
  for (int v : st.views) {
    if (v < 0 || v > 5)
      f.step(st, "view component " + std::to_string(v) + " is out of range; expected 0..5");
  }
}

}  // namespace

void interpret_view_read(Machine& m, const Step& st, size_t, const robot::MeasuredState&,
                         robot::Command&) noexcept {
  namespace steps = runtime::steps;
  const Data& super = m.program.data[static_cast<size_t>(st.in[0])];
  const size_t in = m.slot(st.in[0]);
  const int v = st.views[0];
  double& out = m.s.scalars[m.slot(st.out[0])];
  if (super.type == DataType::Pose) {
    out = steps::view_pose(m.s.poses[in], v);
  } else {
    out = steps::view_vec6(super.type == DataType::Twist ? m.s.twists[in] : m.s.wrenches[in], v);
  }
}

void emit_view_read(const EmitContext& ctx, const Step& st, size_t, mustache::Data& s) {
  put(s, "function", ctx.datum(st.in.at(0)).type == DataType::Pose ? "view_pose" : "view_vec6");
  put(s, "in0", ctx.in(st, 0));
  put(s, "component", std::to_string(st.views[0]));
  put(s, "out0", ctx.out(st, 0));
}

void interpret_view_write(Machine& m, const Step& st, size_t, const robot::MeasuredState&,
                          robot::Command&) noexcept {
  const size_t out = m.slot(st.out[0]);
  runtime::Vec6& target = m.program.data[static_cast<size_t>(st.out[0])].type == DataType::Twist
                              ? m.s.twists[out]
                              : m.s.wrenches[out];
  target.setZero();
  for (size_t k = 0; k < st.in.size(); ++k) target[st.views[k]] = m.s.scalars[m.slot(st.in[k])];
}

void emit_view_write(const EmitContext& ctx, const Step& st, size_t, mustache::Data& s) {
  put(s, "out0", ctx.out(st, 0));
  mustache::Data components = list();
  for (size_t k = 0; k < st.in.size(); ++k) {
    mustache::Data c;
    put(c, "out0", ctx.out(st, 0));
    put(c, "component", std::to_string(st.views[k]));
    put(c, "source", ctx.in(st, k));
    append(components, std::move(c));
  }
  put(s, "components", std::move(components));
}

Signature signature_view_read(const Step& st, const Program& p) {
  const bool known =
      !st.in.empty() && st.in[0] >= 0 && static_cast<size_t>(st.in[0]) < p.data.size();
  const DataType super = known ? p.data[static_cast<size_t>(st.in[0])].type : DataType::Pose;
  if (super != DataType::Pose && super != DataType::Twist && super != DataType::Wrench)
    return {{},
            {},
            true,
            "reads a view of a " + std::string(to_string(super)) +
                "; a view reads a pose, twist or wrench"};
  return {{super}, {DataType::Scalar}};
}

void verify_view_read(const Step& st, const Program&, Findings& f) {
  if (st.views.size() != 1)
    f.step(st, "has " + std::to_string(st.views.size()) + " view components; expected 1");
  verify_view_components(st, f);
}

Signature signature_view_write(const Step& st, const Program& p) {
  const bool known =
      !st.out.empty() && st.out[0] >= 0 && static_cast<size_t>(st.out[0]) < p.data.size();
  const DataType super = known ? p.data[static_cast<size_t>(st.out[0])].type : DataType::Wrench;
  if (super != DataType::Twist && super != DataType::Wrench)
    return {{},
            {},
            true,
            "writes a view of a " + std::string(to_string(super)) +
                "; a view writes a twist or wrench"};
  return {Types(st.in.size(), DataType::Scalar), {super}};
}

void verify_view_write(const Step& st, const Program&, Findings& f) {
  if (st.views.size() != st.in.size())
    f.step(st, "has " + std::to_string(st.views.size()) + " view components for " +
                   std::to_string(st.in.size()) + " inputs; expected one per input");
  verify_view_components(st, f);
}

void print_view(const Step& st, StepJson& j) {
  if (!st.views.empty()) j.e["views"] = st.views;
}

}  // namespace mospec::ir::kinds
