#include "plot/figure.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>

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
  Curve look;  // y and sd left empty
  size_t panel = 0;
};

struct Layout {
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
  for (CurveSpec& t : thresholds) {
    const auto& y = table.data[*table.find(t.column)];
    const bool duplicate = std::any_of(distinct.begin(), distinct.end(), [&](const CurveSpec& d) {
      return table.data[*table.find(d.column)] == y;
    });
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
  throw Error("missing-column", message, table.path);
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

Figure make_figure(const Layout& layout, const std::string& title, std::vector<double> t) {
  Figure figure;
  figure.title = title;
  figure.t = std::move(t);
  figure.panels.resize(2);
  figure.panels[0].ylabel = "shoulder-contact distance [m]";
  figure.panels[1].ylabel = "force [N]";
  if (layout.torque) figure.panels[1].y2label = "torque [N·m]";
  return figure;
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

Figure run_figure(const Table& run, const Selection& selection, const std::string& title) {
  const size_t t = run.require("t", "time [s]");
  Layout layout;
  add_distances(run, selection, layout);
  add_forces(run, selection, /*base_wrench=*/true, layout);
  Figure figure = make_figure(layout, title, run.data[t]);
  for (const CurveSpec& spec : layout.curves) {
    Curve c = spec.look;
    c.y = run.data[*run.find(spec.column)];
    figure.panels[spec.panel].curves.push_back(std::move(c));
  }
  return figure;
}

Figure trials_figure(const std::vector<Table>& trials, const Selection& selection,
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
      throw Error("trials", message, trial.path, 1);
    }
    if (trial.rows() != first.rows()) {
      std::string message = "has ";
      message.append(std::to_string(trial.rows()))
          .append(" rows, ")
          .append(first.path)
          .append(" has ");
      message.append(std::to_string(first.rows()))
          .append(": the trials must share their time base");
      throw Error("trials", message, trial.path);
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
        throw Error("trials", message, trial.path,
                    static_cast<uint32_t>(r + 2));  // the header is line 1
      }
    }
  }
  Layout layout;
  add_distances(first, selection, layout);
  add_forces(first, selection, /*base_wrench=*/false, layout);
  Figure figure = make_figure(layout, title, first.data[t]);
  const size_t rows = first.rows();
  const double n = static_cast<double>(trials.size());
  for (const CurveSpec& spec : layout.curves) {
    const size_t column = *first.find(spec.column);
    Curve c = spec.look;
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
  size_t index = 0;  // the curve's position in the datablock
  for (const Panel& p : figure.panels) {
    s.append("set ylabel ").append(quoted(p.ylabel)).append("\n");
    if (p.y2label.empty()) {
      s.append("unset y2label\nunset y2tics\nset ytics mirror\n");
    } else {
      s.append("set y2label ")
          .append(quoted(p.y2label))
          .append("\nset y2tics\nset ytics nomirror\n");
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
