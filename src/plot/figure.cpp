#include "plot/figure.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>
#include <map>
#include <optional>

#include "support/diagnostics.hpp"

namespace mospec::plot {

namespace {

// Okabe-Ito colours: distinguishable for colour-blind readers and in grey.
constexpr const char* kRight = "#0072B2";
constexpr const char* kLeft = "#D55E00";
constexpr const char* kParallel = "#009E73";
constexpr const char* kTorque = "#CC79A7";
constexpr const char* kThreshold = "#555555";
constexpr const char* kOthers[] = {"#E69F00", "#56B4E9", "#F0E442", "#000000", "#999999"};

constexpr const char* kRightDistance = "cstr-dist-rightarm-shoulder-ee.value";
constexpr const char* kLeftDistance = "cstr-dist-leftarm-shoulder-ee.value";
constexpr const char* kBaseFx = "base-force-distribution.fx";
constexpr const char* kBaseFy = "base-force-distribution.fy";
constexpr const char* kBaseMz = "base-force-distribution.mz";

bool ends_with(std::string_view s, std::string_view suffix) {
  return s.size() >= suffix.size() && s.substr(s.size() - suffix.size()) == suffix;
}

bool contains(std::string_view s, std::string_view part) {
  return s.find(part) != std::string_view::npos;
}

// "ctrl-dist-<anything>-shoulder-ee.output": a distance controller's output
// column. Plain string tests (a regex engine that recurses per character
// overflowed the stack on a 100k-character column name).
bool is_distance_controller_output(std::string_view column) {
  constexpr std::string_view kPrefix = "ctrl-dist-", kSuffix = "-shoulder-ee.output";
  if (column.size() < kPrefix.size() + kSuffix.size()) return false;
  if (column.substr(0, kPrefix.size()) != kPrefix || !ends_with(column, kSuffix)) return false;
  const std::string_view middle =
      column.substr(kPrefix.size(), column.size() - kPrefix.size() - kSuffix.size());
  return middle.find_first_of("\r\n") == std::string_view::npos;
}

// Which arm a column belongs to, by mospec's naming ("...-rightarm-...").
enum class Arm { None, Right, Left };
Arm arm_of(std::string_view column) {
  if (contains(column, "rightarm")) return Arm::Right;
  if (contains(column, "leftarm")) return Arm::Left;
  return Arm::None;
}

// One curve before its values: the column it reads and how it looks.
struct CurveSpec {
  std::string column;
  std::optional<double> constant;  // a setpoint or threshold the log does not hold
  Curve look;                      // y and sd left empty
  size_t panel = 0;
};

struct Layout {
  const LogInfo* info = nullptr;
  std::vector<CurveSpec> curves;
  bool torque = false;  // the force panel has a right-hand torque scale
};

const char* other_color(size_t& next) {
  return kOthers[next++ % std::size(kOthers)];
}

// The distance curves and their thresholds (panel 0).
void add_distances(const Table& table, const Selection& selection, Layout& layout) {
  std::vector<std::string> columns = selection.distances;
  if (columns.empty()) {
    table.require(kRightDistance, "d_r; choose others with --distance");
    table.require(kLeftDistance, "d_l; choose others with --distance");
    columns = {kRightDistance, kLeftDistance};
  }
  size_t next_other = 0;
  std::vector<CurveSpec> thresholds;
  for (const std::string& column : columns) {
    table.require(column, "--distance");
    CurveSpec spec;
    spec.column = column;
    const Arm arm = arm_of(column);
    const bool standard = column == kRightDistance || column == kLeftDistance;
    spec.look.label = standard ? (arm == Arm::Right ? "d_r" : "d_l") : column;
    spec.look.label_enhanced = standard;
    spec.look.color = arm == Arm::Right  ? kRight
                      : arm == Arm::Left ? kLeft
                                         : other_color(next_other);
    layout.curves.push_back(spec);
    if (!ends_with(column, ".value")) continue;
    const std::string base = column.substr(0, column.size() - std::string_view(".value").size());
    if (!table.find(base + ".lower") && layout.info) {
      // Not logged: the model's constants, as the summary recorded them.
      if (const auto it = layout.info->constraints.find(base);
          it != layout.info->constraints.end()) {
        const ConstraintInfo& k = it->second;
        std::vector<std::pair<std::string, double>> lines;
        if (k.relation == "equality" && k.reference) lines.emplace_back(".setpoint", *k.reference);
        if (k.relation != "equality" && k.relation != "assignment") {
          if (k.lower) lines.emplace_back(".lower", *k.lower);
          if (k.upper) lines.emplace_back(".upper", *k.upper);
        }
        for (const auto& [suffix, value] : lines) {
          CurveSpec t;
          t.column = base + suffix;
          t.constant = value;
          t.look.dashed = true;
          t.look.color = kThreshold;
          t.look.label = t.column;
          t.look.label_enhanced = false;
          thresholds.push_back(std::move(t));
        }
      }
    }
    for (const char* bound : {".lower", ".upper"}) {
      std::string name = base;
      name.append(bound);
      if (!table.find(name)) continue;
      CurveSpec t;
      t.column = name;
      t.look.dashed = true;
      t.look.color = kThreshold;
      t.look.label = standard ? (arm == Arm::Right ? "d_{thr,r}" : "d_{thr,l}") : name;
      t.look.label_enhanced = standard;
      thresholds.push_back(std::move(t));
    }
  }
  // Arms usually share their thresholds: draw each distinct one once, the
  // first titled d_thr, the rest untitled.
  std::vector<CurveSpec> distinct;
  const auto values = [&](const CurveSpec& c) {
    return c.constant ? std::vector<double>(table.rows(), *c.constant)
                      : table.data[*table.find(c.column)];
  };
  for (CurveSpec& t : thresholds) {
    const std::vector<double> y = values(t);
    const bool duplicate = std::any_of(distinct.begin(), distinct.end(),
                                       [&](const CurveSpec& d) { return values(d) == y; });
    if (!duplicate) distinct.push_back(std::move(t));
  }
  const bool shared = distinct.size() <= 2;
  for (size_t i = 0; i < distinct.size(); ++i) {
    CurveSpec& t = distinct[i];
    if (shared && t.look.label_enhanced) {
      t.look.label = "d_{thr}";
      t.look.titled = i == 0;
    } else {
      t.look.titled = ends_with(t.column, ".lower") || !t.look.label_enhanced;
    }
    if (!shared) {
      const Arm arm = arm_of(t.column);
      if (arm != Arm::None) t.look.color = arm == Arm::Right ? kRight : kLeft;
    }
    layout.curves.push_back(std::move(t));
  }
}

CurveSpec force_curve(const std::string& column, size_t& next_other) {
  CurveSpec spec;
  spec.column = column;
  spec.panel = 1;
  const Arm arm = arm_of(column);
  if (column == kBaseFx) {
    spec.look.label = "F_{⊥}";
    spec.look.color = kRight;
  } else if (column == kBaseFy) {
    spec.look.label = "F_{∥}";
    spec.look.color = kParallel;
  } else if (column == kBaseMz) {
    spec.look.label = "τ";
    spec.look.color = kTorque;
    spec.look.right_axis = true;
  } else if (arm != Arm::None && is_distance_controller_output(column)) {
    spec.look.label = arm == Arm::Right ? "F_{⊥,r}" : "F_{⊥,l}";
    spec.look.color = arm == Arm::Right ? kRight : kLeft;
  } else {
    spec.look.label = column;
    spec.look.label_enhanced = false;
    spec.look.color = other_color(next_other);
    spec.look.right_axis = ends_with(column, ".mz");
  }
  return spec;
}

// Every arm's distance-controller output, right arm first.
std::vector<std::string> distance_controller_outputs(const Table& table) {
  std::vector<std::string> out;
  for (const std::string& c : table.columns) {
    if (is_distance_controller_output(c)) out.push_back(c);
  }
  std::stable_sort(out.begin(), out.end(), [](const std::string& a, const std::string& b) {
    return arm_of(a) == Arm::Right && arm_of(b) != Arm::Right;
  });
  return out;
}

void no_force_columns(const Table& table, std::string_view wanted) {
  std::string message = "no force columns: expected ";
  message.append(wanted)
      .append("; choose columns with --force; the columns are: ")
      .append(join_names(table.columns));
  throw Error("missing-column", message, table.path, 1, 1);  // the header lists them
}

// The force curves (panel 1). `base_wrench`: prefer the platform wrench (one
// run); otherwise the distance controllers' outputs (trials, as in Fig. 6).
void add_forces(const Table& table, const Selection& selection, bool base_wrench, Layout& layout) {
  std::vector<std::string> columns = selection.forces;
  if (columns.empty()) {
    if (base_wrench && table.find(kBaseFx)) {
      for (const char* c : {kBaseFx, kBaseFy, kBaseMz}) {
        if (table.find(c)) columns.emplace_back(c);
      }
    } else {
      columns = distance_controller_outputs(table);
      if (columns.empty()) {
        no_force_columns(
            table, base_wrench
                       ? "base-force-distribution.fx/.fy/.mz or ctrl-dist-*-shoulder-ee.output"
                       : "ctrl-dist-*-shoulder-ee.output");
      }
    }
  }
  size_t next_other = 0;
  for (const std::string& column : columns) {
    table.require(column, "--force");
    layout.curves.push_back(force_curve(column, next_other));
    layout.torque = layout.torque || layout.curves.back().look.right_axis;
  }
}

// An axis label that names what is plotted on it: the columns (verbatim, at
// most two, then "and N more") and their unit when they share one that the
// names tell.
std::string axis_label(const Layout& layout, size_t panel, bool right_axis) {
  std::vector<std::string> names;
  for (const CurveSpec& c : layout.curves) {
    if (c.panel != panel || c.look.dashed || c.look.right_axis != right_axis) continue;
    names.push_back(c.column);
  }
  if (names.empty()) return "";
  std::string label = names[0];
  if (names.size() >= 2) label.append(", ").append(names[1]);
  if (names.size() > 2)
    label.append(" and ").append(std::to_string(names.size() - 2)).append(" more");
  const LogInfo none;
  const LogInfo& info = layout.info ? *layout.info : none;
  const std::string unit = column_unit(info, names[0]);
  const bool shared = std::all_of(names.begin(), names.end(), [&](const std::string& n) {
    return column_unit(info, n) == unit;
  });
  if (shared && !unit.empty()) label.append(" [").append(unit).append("]");
  return label;
}

// The labels: the paper's quantities for the default columns, else the
// plotted columns themselves.
Figure make_figure(const Layout& layout, const Selection& selection, const std::string& title,
                   std::vector<double> t) {
  Figure figure;
  figure.title = title;
  figure.t = std::move(t);
  figure.panels.resize(2);
  if (selection.distances.empty()) {
    figure.panels[0].ylabel = "shoulder-contact distance [m]";
  } else {
    figure.panels[0].ylabel = axis_label(layout, 0, false);
  }
  const bool default_forces = selection.forces.empty();
  if (default_forces) {
    figure.panels[1].ylabel = "force [N]";
    if (layout.torque) figure.panels[1].y2label = "torque [N·m]";
  } else {
    figure.panels[1].ylabel = axis_label(layout, 1, false);
    figure.panels[1].y2label = axis_label(layout, 1, true);
  }
  return figure;
}

// A short number for a note: 4 significant digits.
std::string short_number(double x) {
  char buf[32];
  auto [p, ec] = std::to_chars(buf, buf + sizeof buf, x, std::chars_format::general, 4);
  return ec == std::errc() ? std::string(buf, p) : exact_number(x);
}

struct Extent {
  double lo = std::numeric_limits<double>::infinity();
  double hi = -std::numeric_limits<double>::infinity();
  void add(double x) {
    if (!std::isfinite(x)) return;
    lo = std::min(lo, x);
    hi = std::max(hi, x);
  }
  bool empty() const { return !(lo <= hi); }
};

// The extent of one axis's data curves (bands included): all of it, and the
// part after the start-up window (the first 5 % of the run).
void extents(const Figure& figure, const Panel& panel, bool right_axis, Extent& all, Extent& late) {
  const std::vector<double>& t = figure.t;
  const double start = t.empty() ? 0.0 : t.front() + 0.05 * (t.back() - t.front());
  for (const Curve& c : panel.curves) {
    if (c.dashed || c.right_axis != right_axis) continue;
    for (size_t r = 0; r < c.y.size() && r < t.size(); ++r) {
      const double sd = c.sd.empty() || !std::isfinite(c.sd[r]) ? 0.0 : c.sd[r];
      for (const double v : {c.y[r] - sd, c.y[r] + sd}) {
        all.add(v);
        if (t[r] > start) late.add(v);
      }
    }
  }
}

// Decides one axis's range and drops the thresholds that would fall outside
// it (a threshold is never drawn on the frame).
Range decide_range(const Figure& figure, Panel& panel, bool right_axis, const std::string& unit) {
  Extent all, late;
  extents(figure, panel, right_axis, all, late);
  Range range;
  if (all.empty()) return range;
  double lo = all.lo, hi = all.hi;
  const double scale = std::max({1.0, std::abs(late.lo), std::abs(late.hi)});
  if (!late.empty() && late.hi - late.lo > 1e-9 * scale) {
    // A start-up spike: beyond the rest's extent by more than three times the
    // rest's span (SC2's distances rise 1.9 spans from their start: kept;
    // SC1's platform force jumps 6 spans: clipped).
    const double span = late.hi - late.lo;
    const double allowed_lo = late.lo - 3.0 * span, allowed_hi = late.hi + 3.0 * span;
    const bool above = hi > allowed_hi, below = lo < allowed_lo;
    if (above || below) {
      range.clipped = above && below ? short_number(lo) + " to " + short_number(hi)
                      : above        ? "up to " + short_number(hi)
                                     : "down to " + short_number(lo);
      if (!unit.empty()) range.clipped.append(" ").append(unit);
    }
    if (above) hi = allowed_hi;
    if (below) lo = allowed_lo;
  }
  // Thresholds near the data widen the range to show them; the others are
  // not drawn.
  const double reach = std::max({hi - lo, 0.1 * std::max(std::abs(lo), std::abs(hi)), 1e-9});
  std::vector<Curve> kept;
  for (Curve& c : panel.curves) {
    if (c.dashed && c.right_axis == right_axis) {
      Extent e;
      for (double v : c.y) e.add(v);
      if (e.empty() || e.lo < lo - 0.5 * reach || e.hi > hi + 0.5 * reach) continue;
      lo = std::min(lo, e.lo);
      hi = std::max(hi, e.hi);
    }
    kept.push_back(std::move(c));
  }
  panel.curves = std::move(kept);
  // A margin, so that no curve and no threshold lies on the frame.
  const double margin = hi > lo ? 0.05 * (hi - lo) : 0.05 * std::max(1.0, std::abs(hi));
  range.lo = lo - margin;
  range.hi = hi + margin;
  return range;
}

// The unit an axis's label ends in ("[N]" -> "N"), for the clipped note.
std::string unit_in(const std::string& label) {
  const size_t open = label.rfind('[');
  if (open == std::string::npos || label.back() != ']') return "";
  return label.substr(open + 1, label.size() - open - 2);
}

void decide_ranges(Figure& figure) {
  for (Panel& p : figure.panels) {
    p.y = decide_range(figure, p, false, unit_in(p.ylabel));
    p.y2 = decide_range(figure, p, true, unit_in(p.y2label));
  }
}

}  // namespace

std::string unit_of(std::string_view c) {
  auto digit_after = [&](std::string_view prefix) {
    // "<arm>_<prefix><digit>": right_q3, left_tau6
    for (std::string_view arm : {"right_", "left_"}) {
      if (c.size() == arm.size() + prefix.size() + 1 && c.substr(0, arm.size()) == arm &&
          c.substr(arm.size(), prefix.size()) == prefix && c.back() >= '0' && c.back() <= '9')
        return true;
    }
    return false;
  };
  if (c == "t") return "s";
  if (c == "base_x" || c == "base_y" || c == "base_z") return "m";
  if (c == "base_yaw" || digit_after("q") ||
      c.substr(0, std::min<size_t>(c.size(), 7)) == "pivot_q")
    return "rad";
  if (digit_after("qd") || c.substr(0, std::min<size_t>(c.size(), 8)) == "wheel_qd") return "rad/s";
  if (digit_after("tau") || c == "ground_mz" || ends_with(c, ".mz")) return "N·m";
  if (c == "tau_ratio") return "1";
  for (std::string_view arm : {"right_", "left_"}) {
    if (c.substr(0, std::min(c.size(), arm.size())) != arm) continue;
    const std::string_view rest = c.substr(arm.size());
    if (rest == "ee_x" || rest == "ee_y" || rest == "ee_z") return "m";
    if (rest == "fn" || rest == "fx" || rest == "fy" || rest == "fz" || rest == "mount_fx" ||
        rest == "mount_fy" || rest == "mount_fz")
      return "N";
  }
  if (c == "ground_fx" || c == "ground_fy" || ends_with(c, ".fx") || ends_with(c, ".fy"))
    return "N";
  if (c.substr(0, std::min<size_t>(c.size(), 10)) == "cstr-dist-") {
    for (std::string_view s : {".value", ".error", ".lower", ".upper"}) {
      if (ends_with(c, s)) return "m";
    }
  }
  if (is_distance_controller_output(c)) return "N";
  return "";
}

void add_markers(const Table& run, Figure& figure) {
  const std::optional<size_t> time = run.find("t");
  if (!time) return;
  // Per row, what happened, in column order.
  std::vector<std::pair<size_t, std::string>> happened;
  for (size_t col = 0; col < run.columns.size(); ++col) {
    const std::string& name = run.columns[col];
    const std::vector<double>& v = run.data[col];
    auto base = [&](std::string_view suffix) {
      return name.substr(0, name.size() - suffix.size());
    };
    if (ends_with(name, ".running")) {
      double was = 0.0;
      for (size_t r = 0; r < v.size(); ++r) {
        if (v[r] == 1.0 && was != 1.0) happened.emplace_back(r, base(".running") + " starts");
        was = v[r];
      }
    } else if (ends_with(name, ".ended")) {
      for (size_t r = 0; r < v.size(); ++r) {
        if (!(v[r] != 0.0) || std::isnan(v[r])) continue;
        const int code = static_cast<int>(v[r]);
        happened.emplace_back(r, base(".ended") + (code == 1   ? " ends (until)"
                                                   : code == 2 ? " aborted (while violated)"
                                                               : " ends"));
      }
    } else if (ends_with(name, ".event")) {
      for (size_t r = 0; r < v.size(); ++r) {
        if (!(v[r] != 0.0) || std::isnan(v[r])) continue;
        const int code = static_cast<int>(v[r]);
        happened.emplace_back(r, base(".event") + (code == 1   ? " rising"
                                                   : code == 2 ? " falling"
                                                               : " rising and falling"));
      }
    }
  }
  std::stable_sort(happened.begin(), happened.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  for (size_t i = 0; i < happened.size();) {
    size_t j = i;
    std::string label;
    for (; j < happened.size() && happened[j].first == happened[i].first; ++j) {
      if (!label.empty()) label.append(", ");
      label.append(happened[j].second);
    }
    if (figure.markers.size() < kMaxMarkers) {
      figure.markers.push_back({run.data[*time][happened[i].first], std::move(label)});
    } else {
      ++figure.markers_dropped;
    }
    i = j;
  }
}

namespace {

// Of the columns `wanted` picks, those of one unit, at most
// kMaxDefaultCurves: the unit whose columns score most in total (`score`:
// a column's weight), then the one most of them share, then the first in
// column order.
template <class Wanted, class Score>
std::vector<std::string> largest_unit_group(const Table& table, const LogInfo& info, Wanted wanted,
                                            Score score) {
  std::vector<std::string> units;
  std::map<std::string, std::pair<size_t, size_t>> rank;  // unit -> (score, count)
  for (const std::string& c : table.columns) {
    if (!wanted(c)) continue;
    const std::string u = column_unit(info, c);
    if (rank[u].second++ == 0) units.push_back(u);
    rank[u].first += score(c);
  }
  if (units.empty()) return {};
  std::string best = units.front();
  for (const std::string& u : units)
    if (rank[u] > rank[best]) best = u;
  std::vector<std::string> out;
  for (const std::string& c : table.columns) {
    if (out.size() < kMaxDefaultCurves && wanted(c) && column_unit(info, c) == best)
      out.push_back(c);
  }
  return out;
}

// The selection a figure draws: the given one, with the defaults for a log
// that is not SC1/SC2's filled in (Selection).
Selection effective_selection(const Table& table, const Selection& given, bool base_wrench) {
  Selection s = given;
  const bool distances = table.find(kRightDistance) && table.find(kLeftDistance);
  if (s.distances.empty() && !distances) {
    // The constraints the task is about: those the controllers pursue (a
    // motion's `when` and `until`, a timeout among them, left out), those
    // with a setpoint or threshold other than 0 weighing most (holding a
    // velocity at 0 is the usual background).
    const auto constraint = [&](const std::string& c) -> const ConstraintInfo* {
      const auto it = s.info.constraints.find(c.substr(0, c.size() - 6));
      return it == s.info.constraints.end() ? nullptr : &it->second;
    };
    s.distances = largest_unit_group(
        table, s.info,
        [&](const std::string& c) {
          if (!ends_with(c, ".value")) return false;
          const ConstraintInfo* k = constraint(c);
          return k == nullptr || (k->relation != "assignment" && !k->guard);
        },
        [&](const std::string& c) -> size_t {
          const ConstraintInfo* k = constraint(c);
          if (k == nullptr) return 0;
          for (const std::optional<double>& v : {k->reference, k->lower, k->upper})
            if (v && *v != 0.0) return 1;
          return 0;
        });
    if (s.distances.empty()) {
      throw Error("missing-column",
                  "no constraint's .value column to plot (choose columns with --distance); the "
                  "columns are: " +
                      join_names(table.columns),
                  table.path, 1, 1);
    }
  }
  const bool wrench = base_wrench && table.find(kBaseFx);
  if (s.forces.empty() && !wrench && distance_controller_outputs(table).empty()) {
    s.forces = largest_unit_group(
        table, s.info, [](const std::string& c) { return ends_with(c, ".output"); },
        [](const std::string&) -> size_t { return 0; });
    for (const std::string& d : s.distances) {
      if (!s.forces.empty() && !ends_with(s.forces.front(), ".error")) break;
      if (!ends_with(d, ".value")) continue;
      const std::string error = d.substr(0, d.size() - 6) + ".error";
      if (table.find(error)) s.forces.push_back(error);
    }
  }
  return s;
}

std::vector<double> curve_values(const Table& table, const CurveSpec& spec, size_t column) {
  return spec.constant ? std::vector<double>(table.rows(), *spec.constant) : table.data[column];
}

}  // namespace

Format format_of(const std::string& path) {
  std::string ext;
  const size_t dot = path.find_last_of('.');
  if (dot != std::string::npos && path.find('/', dot) == std::string::npos)
    ext = path.substr(dot + 1);
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  if (ext == "svg") return Format::Svg;
  if (ext == "png") return Format::Png;
  std::string message = "cannot tell the figure's format from '";
  message.append(path).append("': the output must end in .svg or .png");
  throw Error("usage", message);
}

Figure run_figure(const Table& run, const Selection& given, const std::string& title) {
  const size_t t = run.require("t", "time [s]");
  const Selection selection = effective_selection(run, given, /*base_wrench=*/true);
  Layout layout;
  layout.info = &selection.info;
  add_distances(run, selection, layout);
  add_forces(run, selection, /*base_wrench=*/true, layout);
  Figure figure = make_figure(layout, selection, title, run.data[t]);
  for (const CurveSpec& spec : layout.curves) {
    Curve c = spec.look;
    c.y = curve_values(run, spec, spec.constant ? 0 : *run.find(spec.column));
    figure.panels[spec.panel].curves.push_back(std::move(c));
  }
  decide_ranges(figure);
  add_markers(run, figure);
  return figure;
}

Figure trials_figure(const std::vector<Table>& trials, const Selection& given,
                     const std::string& title) {
  if (trials.empty()) throw Error("usage", "no trials to plot");
  const Table& first = trials.front();
  const size_t t = first.require("t", "time [s]");
  for (const Table& trial : trials) {
    if (trial.columns != first.columns) {
      size_t i = 0;
      while (i < trial.columns.size() && i < first.columns.size() &&
             trial.columns[i] == first.columns[i])
        ++i;
      std::string message = "the columns differ from ";
      message.append(first.path)
          .append("'s: column ")
          .append(std::to_string(i + 1))
          .append(" is '");
      message.append(i < trial.columns.size() ? trial.columns[i] : "(none)").append("', there '");
      message.append(i < first.columns.size() ? first.columns[i] : "(none)").append("'");
      throw Error("trials", message, trial.path, 1,
                  i < trial.column_at.size() ? trial.column_at[i] : 1);
    }
    if (trial.rows() != first.rows()) {
      std::string message = "has ";
      message.append(std::to_string(trial.rows()))
          .append(" rows, ")
          .append(first.path)
          .append(" has ");
      message.append(std::to_string(first.rows()))
          .append(": the trials must share their time base");
      // At its last row (the header is line 1).
      throw Error("trials", message, trial.path, static_cast<uint32_t>(trial.rows() + 1), 1);
    }
    for (size_t r = 0; r < trial.rows(); ++r) {
      const double a = trial.data[t][r], b = first.data[t][r];
      if (!(std::abs(a - b) <= 1e-9 * std::max(1.0, std::abs(b)))) {
        std::string message = "t = ";
        message.append(exact_number(a))
            .append(" differs from ")
            .append(first.path)
            .append("'s t = ");
        message.append(exact_number(b)).append(": the trials must share their time base");
        // At the row (the header is line 1).
        throw Error("trials", message, trial.path, static_cast<uint32_t>(r + 2), 1);
      }
    }
  }
  const Selection selection = effective_selection(first, given, /*base_wrench=*/false);
  Layout layout;
  layout.info = &selection.info;
  add_distances(first, selection, layout);
  add_forces(first, selection, /*base_wrench=*/false, layout);
  Figure figure = make_figure(layout, selection, title, first.data[t]);
  const size_t rows = first.rows();
  const double n = static_cast<double>(trials.size());
  for (const CurveSpec& spec : layout.curves) {
    Curve c = spec.look;
    if (spec.constant) {
      c.y = curve_values(first, spec, 0);
      figure.panels[spec.panel].curves.push_back(std::move(c));
      continue;
    }
    const size_t column = *first.find(spec.column);
    c.y.assign(rows, 0.0);
    c.sd.assign(rows, 0.0);
    for (size_t r = 0; r < rows; ++r) {
      // Two passes over a handful of trials: exact enough, no cancellation.
      double sum = 0.0;
      for (const Table& trial : trials) sum += trial.data[column][r];
      const double mean = sum / n;
      double squares = 0.0;
      for (const Table& trial : trials)
        squares += (trial.data[column][r] - mean) * (trial.data[column][r] - mean);
      c.y[r] = mean;
      c.sd[r] =
          trials.size() > 1 ? std::sqrt(squares / (n - 1.0)) : 0.0;  // sample standard deviation
    }
    if (spec.look.dashed) c.sd.clear();  // thresholds: the mean line only
    figure.panels[spec.panel].curves.push_back(std::move(c));
  }
  decide_ranges(figure);
  add_markers(first, figure);  // the first trial's
  return figure;
}

namespace {

// A gnuplot single-quoted string: no escapes inside except '' for '; line
// breaks become spaces (a string cannot span lines).
std::string quoted(std::string_view s) {
  std::string out = "'";
  for (char c : s) {
    if (c == '\'') {
      out.append("''");
    } else if (c == '\n' || c == '\r') {
      out.push_back(' ');
    } else {
      out.push_back(c);
    }
  }
  out.push_back('\'');
  return out;
}

void append_number(std::string& out, double x) {
  if (!std::isfinite(x)) {
    out.append("NaN");
    return;
  }
  char buf[32];
  auto [p, ec] = std::to_chars(buf, buf + sizeof buf, x);
  out.append(buf, ec == std::errc() ? p : buf);
}

}  // namespace

std::string gnuplot_script(const Figure& figure, Format format, const std::string& output_name) {
  std::string s;
  s.append("# mospec plot\nset encoding utf8\n");
  // Data first, inline: column 1 is t, then each curve's value and its
  // standard deviation (0 without a band).
  std::vector<const Curve*> curves;
  for (const Panel& p : figure.panels) {
    for (const Curve& c : p.curves) curves.push_back(&c);
  }
  s.append("$data << EOD\n");
  for (size_t r = 0; r < figure.t.size(); ++r) {
    append_number(s, figure.t[r]);
    for (const Curve* c : curves) {
      s.push_back(' ');
      append_number(s, c->y[r]);
      s.push_back(' ');
      append_number(s, c->sd.empty() ? 0.0 : c->sd[r]);
    }
    s.push_back('\n');
  }
  s.append("EOD\n");
  if (format == Format::Svg) {
    s.append(
        "set terminal svg size 1280,520 dynamic enhanced font 'Sans,13' background rgb 'white'\n");
  } else {
    s.append(
        "if (strstrt(GPVAL_TERMINALS, 'pngcairo') > 0) {\n"
        "  set terminal pngcairo size 1280,520 enhanced font 'Sans,11' background rgb 'white'\n"
        "} else {\n"
        "  set terminal png size 1280,520 enhanced background rgb 'white'\n"
        "}\n");
  }
  s.append("set output ").append(quoted(output_name)).append("\n");
  s.append("set multiplot layout 1,").append(std::to_string(figure.panels.size()));
  if (!figure.title.empty()) {
    s.append(" title ").append(quoted(figure.title)).append(" font ',15' noenhanced");
  }
  s.append(
      "\nset grid lc rgb '#dddddd'\nset key below horizontal height 1 spacing 1.3\nset xlabel 't "
      "[s]'\n");
  s.append("set style fill transparent solid 0.22 noborder\n");
  // Markers: a dotted vertical line and a label in every panel (no box: a
  // label must not hide the curves it crosses).
  for (const Marker& m : figure.markers) {
    std::string t;
    append_number(t, m.t);
    s.append("set arrow from first ").append(t).append(", graph 0 to first ").append(t);
    s.append(", graph 1 nohead dt 3 lw 1 lc rgb '#777777' back\n");
    s.append("set label ").append(quoted(m.label)).append(" at first ").append(t);
    s.append(
        ", graph 0.98 rotate by 90 right offset character 0.9,0 font ',9' tc rgb '#444444' "
        "noenhanced front\n");
  }
  if (figure.markers_dropped > 0) {
    s.append("set label ")
        .append(quoted("+" + std::to_string(figure.markers_dropped) + " later markers not drawn"))
        .append(" at screen 0.99, screen 0.03 right font ',9' tc rgb '#444444' noenhanced\n");
  }
  size_t index = 0;  // the curve's position in the datablock
  for (const Panel& p : figure.panels) {
    s.append("set ylabel ").append(quoted(p.ylabel)).append(" noenhanced\n");
    auto range = [&](const char* axis, const Range& r) {
      s.append("set ").append(axis).append("range [");
      append_number(s, r.lo);
      s.push_back(':');
      append_number(s, r.hi);
      s.append("]\n");
    };
    range("y", p.y);
    if (p.y2label.empty()) {
      s.append("unset y2label\nunset y2tics\nset ytics mirror\n");
    } else {
      s.append("set y2label ")
          .append(quoted(p.y2label))
          .append(" noenhanced\nset y2tics\nset ytics nomirror\n");
      range("y2", p.y2);
    }
    std::string note;
    if (!p.y.clipped.empty()) note = "clipped: start-up spike " + p.y.clipped;
    if (!p.y2label.empty() && !p.y2.clipped.empty()) {
      note.append(note.empty() ? "clipped: start-up spike, right scale " : "; right scale ");
      note.append(p.y2.clipped);
    }
    if (note.empty()) {
      s.append("unset title\n");
    } else {
      s.append("set title ")
          .append(quoted(note))
          .append(" font ',10' tc rgb '#B00000' noenhanced\n");
    }
    std::string bands, lines;
    for (const Curve& c : p.curves) {
      const std::string y = std::to_string(2 + 2 * index);
      const std::string sd = std::to_string(3 + 2 * index);
      ++index;
      const std::string axes = c.right_axis ? " axes x1y2" : " axes x1y1";
      const std::string color = " lc rgb " + quoted(c.color);
      if (!c.sd.empty()) {
        if (!bands.empty()) bands.append(", \\\n  ");
        bands.append("$data using 1:($").append(y).append("-$").append(sd).append("):($");
        bands.append(y).append("+$").append(sd).append(")").append(axes);
        bands.append(" with filledcurves").append(color).append(" notitle");
      }
      if (!lines.empty()) lines.append(", \\\n  ");
      lines.append("$data using 1:").append(y).append(axes).append(" with lines");
      lines.append(c.dashed ? " lw 1.5 dt 2" : " lw 2").append(color);
      if (c.titled) {
        lines.append(" title ")
            .append(quoted(c.label))
            .append(c.label_enhanced ? " enhanced" : " noenhanced");
      } else {
        lines.append(" notitle");
      }
    }
    s.append("plot ");
    if (!bands.empty()) s.append(bands).append(", \\\n  ");
    s.append(lines).append("\n");
  }
  s.append("unset multiplot\nset output\n");
  return s;
}

}  // namespace mospec::plot
