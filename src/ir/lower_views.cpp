// Lowering passes. Views: components of 3D quantities read from or written into them.
#include <algorithm>
#include <cmath>

#include "ir/lowering.hpp"

namespace mospec::ir::lowering {

namespace {

// The unit of component `index` (0-2 angular, 3-5 linear, along x, y, z) of a
// pose, twist or wrench, and how messages name it.
const char* component_unit(DataType super, int index) {
  const bool angular = index < 3;
  switch (super) {
    case DataType::Pose:
      return angular ? "RAD" : "M";
    case DataType::Twist:
      return angular ? "RAD-PER-SEC" : "M-PER-SEC";
    default:
      return angular ? "N-M" : "N";
  }
}
std::string component_name(DataType super, int index) {
  static const char* const kAxis[3] = {"x", "y", "z"};
  const bool angular = index < 3;
  const std::string part = super == DataType::Pose ? (angular ? "orientation" : "position")
                           : super == DataType::Twist
                               ? (angular ? "angular velocity" : "linear velocity")
                               : (angular ? "torque" : "force");
  return part + " along " + kAxis[index % 3];
}

const std::string kMap = "task/map";

// A view of one component (`index`: 0-2 angular, 3-5 linear) of its
// superobject.
struct ViewInfo {
  TermId view, super, sub;
  int index = 0;
  DataType super_type = DataType::Pose;
};

// The vocabulary terms views are read through, looked up once.
struct ViewTerms {
  TermId superobject, subobject, subspace, axis, pose_view, twist_view, wrench_view;
};
ViewTerms view_terms(const State& st) {
  const auto term = [&](std::string_view local) { return st.term(vocab(kMap, local)); };
  return {term("superobject"),
          term("subobject"),
          term("subspace"),
          term("axis"),
          term("PoseCoordinateView"),
          term("VelocityTwistCoordinateView"),
          term("WrenchCoordinateView")};
}

// The view v: its objects and the component it views; nullopt when it cannot
// be read (reported).
std::optional<ViewInfo> read_view(State& st, const ViewTerms& t, TermId v) {
  auto super = st.object(v, t.superobject);
  auto sub = st.object(v, t.subobject);
  auto space = st.object(v, t.subspace);
  auto axis = st.object(v, t.axis);
  if (!super || !sub || !space || !axis) {
    st.error(v, "missing-property",
             "the view '" + st.str(v) + "' needs superobject, subobject, subspace and axis");
    return std::nullopt;
  }
  ViewInfo info{v, *super, *sub};
  const std::string sp = local_name(st.str(*space)), ax = local_name(st.str(*axis));
  const int a = ax == "x" ? 0 : ax == "y" ? 1 : ax == "z" ? 2 : -1;
  int base = -1;
  if (st.graph.has_type(v, t.pose_view)) {
    info.super_type = DataType::Pose;
    base = sp == "orientation" || sp == "rotation" ? 0 : sp == "position" ? 3 : -1;
  } else if (st.graph.has_type(v, t.twist_view)) {
    info.super_type = DataType::Twist;
    base = sp == "angular-velocity" ? 0 : sp == "linear-velocity" ? 3 : -1;
  } else if (st.graph.has_type(v, t.wrench_view)) {
    info.super_type = DataType::Wrench;
    base = sp == "torque" || sp == "moment" ? 0 : sp == "force" ? 3 : -1;
  }
  if (base < 0 || a < 0) {
    st.error(v, "invalid-view",
             "the view '" + st.str(v) + "' has subspace '" + sp + "' and axis '" + ax +
                 "', which mospec cannot read");
    return std::nullopt;
  }
  info.index = base + a;
  return info;
}

// A component in another unit is another quantity (a velocity written as a
// force, a position read as an angle): the view's subspace or the quantity is
// wrong. Judged once either side is produced.
void check_view_unit(State& st, const ViewInfo& v, int super, int sub) {
  const std::string& unit = st.program.data[static_cast<size_t>(sub)].unit;
  const char* expected = component_unit(v.super_type, v.index);
  if (unit.empty() || unit == expected) return;
  st.error(v.view, "wrong-unit",
           "the view '" + st.str(v.view) + "' " +
               (st.produced(super) ? "reads the " : "writes '" + st.str(v.sub) + "' as the ") +
               component_name(v.super_type, v.index) + " of '" + st.str(v.super) + "'" +
               (st.produced(super) ? " into '" + st.str(v.sub) + "'" : "") + ", which is in '" +
               expected + "', but '" + st.str(v.sub) + "' is in '" + unit +
               "'; check the view's subspace and axis, or use the quantity it means");
}

void add_view_read(State& st, const ViewInfo& v, int super, int sub) {
  Step s;
  s.kind = StepKind::ViewRead;
  s.iri = st.str(v.view);
  s.name = local_name(s.iri);
  s.where = st.where(v.view);
  s.in = {super};
  s.out = {sub};
  s.views = {v.index};
  st.add_step(std::move(s));
}

// The views `list` writing into one superobject, as one step.
void add_view_write(State& st, const std::vector<ViewInfo>& views, const std::vector<size_t>& list,
                    std::vector<char>& done) {
  Step s;
  s.kind = StepKind::ViewWrite;
  const ViewInfo& first = views[list.front()];
  s.iri = st.str(first.super);
  s.name = "assemble_" + local_name(s.iri);
  s.where = st.where(first.view);
  std::map<int, size_t> writer_of;  // component -> the view writing it
  for (size_t i : list) {
    done[i] = 1;
    // Two views writing one component: the assembled value would keep only one.
    if (auto [it, fresh] = writer_of.emplace(views[i].index, i); !fresh) {
      const ViewInfo& first_writer = views[it->second];
      st.error(views[i].view, "driven-twice",
               "the views '" + st.str(first_writer.view) + "' (" + st.place(first_writer.view) +
                   ") and '" + st.str(views[i].view) + "' both write the " +
                   component_name(views[i].super_type, views[i].index) + " of '" +
                   st.str(views[i].super) + "' ('" + st.str(first_writer.sub) + "' and '" +
                   st.str(views[i].sub) +
                   "'), and the assembled value would keep only one; write each component "
                   "once (sum the signals in one controller, or assemble two wrenches and add "
                   "them with AddWrench)");
      continue;
    }
    s.in.push_back(st.datum(views[i].sub, DataType::Scalar, views[i].view, "subobject"));
    s.views.push_back(views[i].index);
  }
  s.out = {st.datum(first.super, first.super_type, first.view, "superobject")};
  st.add_step(std::move(s));
}

// One pass over the views not yet done: those whose superobject is produced
// read, those whose subobject is write (grouped by superobject). Whether any
// step was added.
bool lower_produced_views(State& st, const std::vector<ViewInfo>& views, std::vector<char>& done,
                          std::set<size_t>& unit_checked) {
  bool progress = false;
  std::map<uint32_t, std::vector<size_t>> writes;
  for (size_t i = 0; i < views.size(); ++i) {
    if (done[i]) continue;
    const ViewInfo& v = views[i];
    st.pending_iri = st.str(v.view);
    const int super = st.datum(v.super, v.super_type, v.view, "superobject");
    const int sub = st.datum(v.sub, DataType::Scalar, v.view, "subobject");
    if ((st.produced(super) || st.produced(sub)) && unit_checked.insert(i).second)
      check_view_unit(st, v, super, sub);
    if (st.produced(super)) {
      add_view_read(st, v, super, sub);
      done[i] = 1;
      progress = true;
    } else if (st.produced(sub) && v.super_type != DataType::Pose) {
      writes[v.super.index].push_back(i);
    }
  }
  for (const auto& [super_term, list] : writes) {
    add_view_write(st, views, list, done);
    progress = true;
  }
  return progress;
}

}  // namespace

void lower_views(State& st) {
  const ViewTerms terms = view_terms(st);
  std::vector<ViewInfo> views;
  for (TermId v : st.instances(vocab(kMap, "View"))) {
    if (auto info = read_view(st, terms, v)) views.push_back(*info);
  }
  // Direction: a view reads when its superobject is produced, writes when its
  // subobject is. Writes into one superobject become one step.
  std::vector<char> done(views.size(), 0);
  std::set<size_t> unit_checked;  // views whose unit has been judged
  while (lower_produced_views(st, views, done, unit_checked)) {
  }
  for (size_t i = 0; i < views.size(); ++i) {
    if (done[i]) continue;
    st.error(views[i].view, "unproduced-quantity",
             "the view '" + st.str(views[i].view) + "': nothing produces its superobject '" +
                 st.str(views[i].super) + "' or its subobject '" + st.str(views[i].sub) + "'");
    done[i] = 1;
  }
}

}  // namespace mospec::ir::lowering
