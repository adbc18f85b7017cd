#include "report/report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>

#include "report/html.hpp"
#include "support/diagnostics.hpp"
#include "support/io.hpp"
#include "support/paths.hpp"

namespace mospec::report {
namespace {

using Json = nlohmann::ordered_json;

std::string base64(std::string_view bytes) {
  static constexpr char kDigits[] =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  size_t i = 0;
  for (; i + 2 < bytes.size(); i += 3) {
    const unsigned v = (static_cast<unsigned char>(bytes[i]) << 16) |
                       (static_cast<unsigned char>(bytes[i + 1]) << 8) |
                       static_cast<unsigned char>(bytes[i + 2]);
    out += kDigits[(v >> 18) & 63];
    out += kDigits[(v >> 12) & 63];
    out += kDigits[(v >> 6) & 63];
    out += kDigits[v & 63];
  }
  if (i < bytes.size()) {
    unsigned v = static_cast<unsigned char>(bytes[i]) << 16;
    if (i + 1 < bytes.size()) v |= static_cast<unsigned char>(bytes[i + 1]) << 8;
    out += kDigits[(v >> 18) & 63];
    out += kDigits[(v >> 12) & 63];
    out += i + 1 < bytes.size() ? kDigits[(v >> 6) & 63] : '=';
    out += '=';
  }
  return out;
}

std::string number(double v, int precision = 6) {
  if (!std::isfinite(v)) return std::isnan(v) ? "NaN" : (v > 0 ? "inf" : "-inf");
  std::ostringstream s;
  s.precision(precision);
  s << v;
  return s.str();
}

bool ends_with(std::string_view s, std::string_view suffix) {
  return s.size() >= suffix.size() && s.substr(s.size() - suffix.size()) == suffix;
}
bool starts_with(std::string_view s, std::string_view prefix) {
  return s.substr(0, prefix.size()) == prefix;
}

// A chart is drawn on a screen a thousand-odd pixels wide: each series keeps
// its minimum and maximum per bucket of rows (decimate()), at most
// kBuckets buckets, as many fewer as keep the page's data within kDataBudget
// bytes (at least kMinBuckets).
constexpr size_t kBuckets = 1000;
constexpr size_t kMinBuckets = 100;
constexpr size_t kDataBudget = 1000 * 1000;

// The log's columns, grouped into the page's charts: one kind of quantity in
// one unit per chart, so every axis has a single unit.
struct Group {
  std::string title, unit;  // unit: a symbol ("m"), "" when the run did not record it
  std::vector<size_t> columns;
  bool steps = false;  // flags and events: drawn as steps
};

// Where a column goes: the index of its kind in kKinds, or -1 for a column
// the page does not chart on its own (a constraint's .lower/.upper: its
// band; .satisfied: the constraints table).
struct Kind {
  const char* title;
  bool steps;
  bool fixed_unit;  // the unit is part of the kind (flags)
};
constexpr Kind kKinds[] = {
    {"Motions running", true, true},
    {"Constraint values", false, false},
    {"Constraint errors", false, false},
    {"Controller outputs", false, false},
    {"Platform twist and wrench", false, false},
    {"Monitors, events and degraded solves", true, true},
    {"Controlled frames' positions in W (simulator)", false, false},
    {"Contact and ground forces (simulator)", false, false},
    {"Base pose (simulator)", false, false},
    {"Joint positions (simulator)", false, false},
    {"Joint velocities (simulator)", false, false},
    {"Joint torques (simulator)", false, false},
    {"Other columns", false, false},
};

bool joint_column(std::string_view c, std::string_view field) {
  // <arm>_<field><digits>, e.g. right_q3, left_qd6
  const size_t u = c.find('_');
  if (u == std::string_view::npos) return false;
  std::string_view rest = c.substr(u + 1);
  if (!starts_with(rest, field) || rest.size() == field.size()) return false;
  rest.remove_prefix(field.size());
  return std::all_of(rest.begin(), rest.end(), [](char ch) { return ch >= '0' && ch <= '9'; });
}

int kind_of(const std::string& c) {
  if (ends_with(c, ".running")) return 0;
  if (ends_with(c, ".value")) return 1;
  if (ends_with(c, ".error")) return 2;
  if (ends_with(c, ".output")) return 3;
  if (ends_with(c, ".vx") || ends_with(c, ".vy") || ends_with(c, ".wz") || ends_with(c, ".fx") ||
      ends_with(c, ".fy") || ends_with(c, ".mz"))
    return 4;
  if (ends_with(c, ".flag") || ends_with(c, ".event") || ends_with(c, ".ended") ||
      ends_with(c, ".degraded"))
    return 5;
  if (ends_with(c, ".lower") || ends_with(c, ".upper") || ends_with(c, ".satisfied")) return -1;
  if (ends_with(c, "_ee_x") || ends_with(c, "_ee_y") || ends_with(c, "_ee_z")) return 6;
  if (ends_with(c, "_fn") || ends_with(c, "_fx") || ends_with(c, "_fy") || ends_with(c, "_fz") ||
      starts_with(c, "ground_"))
    return 7;
  if (starts_with(c, "base_")) return 8;
  if (joint_column(c, "q") || starts_with(c, "pivot_q")) return 9;
  if (joint_column(c, "qd") || starts_with(c, "wheel_qd")) return 10;
  if (joint_column(c, "tau")) return 11;
  return 12;
}

// The first row at which a motion's .running column is 1 (the log's row
// count when it never runs): the charts list motions in the order they start.
size_t start_row(const std::vector<double>& running) {
  for (size_t r = 0; r < running.size(); ++r)
    if (running[r] == 1.0) return r;
  return running.size();
}

std::vector<Group> group_columns(const plot::Table& t, const plot::LogInfo& info) {
  std::vector<std::pair<int, Group>> groups;
  for (size_t i = 0; i < t.columns.size(); ++i) {
    const std::string& c = t.columns[i];
    if (c == "t") continue;
    const int k = kind_of(c);
    if (k < 0) continue;
    const Kind& kind = kKinds[static_cast<size_t>(k)];
    const std::string unit = kind.fixed_unit ? std::string() : plot::column_unit(info, c);
    auto it = std::find_if(groups.begin(), groups.end(),
                           [&](const auto& g) { return g.first == k && g.second.unit == unit; });
    if (it == groups.end()) {
      Group g;
      g.title = kind.title;
      g.unit = unit;
      g.steps = kind.steps;
      groups.emplace_back(k, std::move(g));
      it = std::prev(groups.end());
    }
    it->second.columns.push_back(i);
  }
  std::stable_sort(groups.begin(), groups.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<Group> out;
  for (auto& [k, g] : groups) {
    if (k == 0) {
      std::stable_sort(g.columns.begin(), g.columns.end(), [&](size_t a, size_t b) {
        return start_row(t.data[a]) < start_row(t.data[b]);
      });
    }
    out.push_back(std::move(g));
  }
  return out;
}

// A value as the page's data writes it: six significant digits (a chart
// shows three), null for NaN and infinities.
void append_value(std::string& out, double v) {
  if (!std::isfinite(v)) {
    out += "null";
    return;
  }
  char buf[32];
  const int n = std::snprintf(buf, sizeof buf, "%.6g", v == 0.0 ? 0.0 : v);
  out.append(buf, static_cast<size_t>(n));
}

// Draws the charts: a legend always shown beside each (its labelsDiv), and
// each constraint's band (where it holds) shaded under its series in the
// series' colour, a band of zero width as a dashed line.
constexpr const char* kChartScript =
    R"js(const palette = ["#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd", "#8c564b",
  "#e377c2", "#7f7f7f", "#bcbd22", "#17becf"];
function raw(g, row, col) {
  const v = g.getValue(row, col);
  return Array.isArray(v) ? v[0] : v;
}
function drawBands(c, ctx, area, g) {
  for (const b of c.bands) {
    const colour = palette[b.s % palette.length];
    ctx.save();
    ctx.fillStyle = colour;
    ctx.strokeStyle = colour;
    ctx.globalAlpha = 0.15;
    if (b.loS !== null && b.hiS !== null) {
      const n = g.numRows();
      ctx.beginPath();
      for (let r = 0; r < n; ++r) {
        const x = g.toDomXCoord(g.getValue(r, 0)), y = g.toDomYCoord(raw(g, r, b.hiS + 1));
        if (r === 0) ctx.moveTo(x, y); else ctx.lineTo(x, y);
      }
      for (let r = n - 1; r >= 0; --r)
        ctx.lineTo(g.toDomXCoord(g.getValue(r, 0)), g.toDomYCoord(raw(g, r, b.loS + 1)));
      ctx.closePath();
      ctx.fill();
    } else {
      const top = b.hi === null ? area.y : g.toDomYCoord(b.hi);
      const bottom = b.lo === null ? area.y + area.h : g.toDomYCoord(b.lo);
      ctx.globalAlpha = 0.6;
      ctx.setLineDash([6, 4]);
      for (const v of [b.lo, b.hi]) {
        if (v === null) continue;
        const y = g.toDomYCoord(v);
        ctx.beginPath();
        ctx.moveTo(area.x, y);
        ctx.lineTo(area.x + area.w, y);
        ctx.stroke();
      }
      ctx.globalAlpha = 0.15;
      if (bottom - top > 0.5) ctx.fillRect(area.x, top, area.w, bottom - top);
    }
    ctx.restore();
  }
}
window.mospecCharts = charts.map((c, i) => new Dygraph(document.getElementById(c.id),
  chartData[i], {labels: c.labels, visibility: c.visible, colors: palette, xlabel: "t [s]",
  ylabel: c.ylabel, legend: "always", labelsDiv: document.getElementById(c.id + "-legend"),
  labelsSeparateLines: false, stepPlot: c.steps, errorBars: c.trials, sigma: 1,
  showRangeSelector: !c.trials, connectSeparatedPoints: false,
  underlayCallback: (ctx, area, g) => drawBands(c, ctx, area, g)}));
document.body.dataset.charts = String(window.mospecCharts.length);
)js";

// A constraint's band on a chart of its .value: where it holds.
struct Band {
  size_t series = 0;  // the .value's index among the chart's series
  std::optional<double> lo, hi;
  std::optional<size_t> lo_series, hi_series;  // logged thresholds (hidden series)
};

// A chart: its series (columns of the log), which of them are only there for
// a band (hidden), and its bands.
struct ChartSpec {
  std::vector<size_t> columns;
  std::vector<bool> visible;
  std::vector<Band> bands;
};

ChartSpec chart_spec(const plot::Table& t, const Group& group, const plot::LogInfo& info) {
  ChartSpec spec;
  spec.columns = group.columns;
  spec.visible.assign(spec.columns.size(), true);
  const size_t shown = spec.columns.size();
  for (size_t s = 0; s < shown; ++s) {
    const std::string& c = t.columns[spec.columns[s]];
    if (!ends_with(c, ".value")) continue;
    const std::string name = c.substr(0, c.size() - std::string_view(".value").size());
    Band band;
    band.series = s;
    const auto lo = t.find(name + ".lower"), hi = t.find(name + ".upper");
    if (lo && hi) {
      band.lo_series = spec.columns.size();
      spec.columns.push_back(*lo);
      band.hi_series = spec.columns.size();
      spec.columns.push_back(*hi);
      spec.visible.resize(spec.columns.size(), false);
    } else if (const auto it = info.constraints.find(name); it != info.constraints.end()) {
      const plot::ConstraintInfo& k = it->second;
      const double tol = k.tolerance.value_or(0.0);
      if (k.relation == "equality" && k.reference) {
        band.lo = *k.reference - tol;
        band.hi = *k.reference + tol;
      } else if (k.relation == "less-than" || k.relation == "greater-than" ||
                 k.relation == "bilateral") {
        band.lo = k.lower;
        band.hi = k.upper;
      }
      if (!band.lo && !band.hi) continue;
    } else {
      continue;
    }
    spec.bands.push_back(band);
  }
  return spec;
}

// One chart's data as JSON rows: [t, v...] (a single run) or [t, [mean,
// std]...] (trials), decimated to `buckets` (decimate()).
std::string chart_data(const std::vector<const plot::Table*>& runs, const ChartSpec& spec,
                       size_t buckets, size_t& kept) {
  size_t rows = runs.front()->rows();
  for (const plot::Table* r : runs) rows = std::min(rows, r->rows());
  const size_t t = runs.front()->find("t").value_or(0);
  std::vector<double> time(runs.front()->data[t].begin(),
                           runs.front()->data[t].begin() + static_cast<std::ptrdiff_t>(rows));
  std::vector<std::vector<double>> mean(spec.columns.size()), sd;
  if (runs.size() > 1) sd.resize(spec.columns.size());
  for (size_t k = 0; k < spec.columns.size(); ++k) {
    const size_t c = spec.columns[k];
    if (runs.size() == 1) {
      mean[k].assign(runs.front()->data[c].begin(),
                     runs.front()->data[c].begin() + static_cast<std::ptrdiff_t>(rows));
      continue;
    }
    mean[k].resize(rows);
    sd[k].resize(rows);
    for (size_t row = 0; row < rows; ++row) {
      double sum = 0, sq = 0;
      size_t n = 0;
      for (const plot::Table* run : runs) {
        const double v = run->data[c][row];
        if (!std::isfinite(v)) continue;
        sum += v;
        sq += v * v;
        ++n;
      }
      const double m = n ? sum / static_cast<double>(n) : std::nan("");
      mean[k][row] = m;
      sd[k][row] = n > 1 ? std::sqrt(std::max(0.0, (sq - static_cast<double>(n) * m * m) /
                                                       static_cast<double>(n - 1)))
                         : 0.0;
    }
  }
  std::vector<const std::vector<double>*> series;
  for (const auto& m : mean) series.push_back(&m);
  const Decimation d = decimate(series, rows, buckets);
  kept = d.time_row.size();
  std::string out = "[";
  for (size_t i = 0; i < d.time_row.size(); ++i) {
    out += i ? ",[" : "[";
    append_value(out, time[d.time_row[i]]);
    for (size_t k = 0; k < series.size(); ++k) {
      const size_t row = d.row[k][i];
      out += ',';
      if (sd.empty()) {
        append_value(out, mean[k][row]);
      } else {
        out += '[';
        append_value(out, mean[k][row]);
        out += ',';
        append_value(out, sd[k][row]);
        out += ']';
      }
    }
    out += ']';
  }
  out += ']';
  return out;
}

std::string optional_number(const std::optional<double>& v, int precision = 6) {
  return v ? number(*v, precision) : std::string("–");
}

std::string verdict_html(const LoadedRun& run) {
  const Summary& s = run.summary;
  const std::string name = html_escape(run.name);
  std::ostringstream o;
  o << "<section class=\"verdict\" id=\"verdict-" << name << "\"><h3>" << name
    << ": <span class=\"status " << (s.status == "ok" ? "ok" : "failed") << "\">"
    << html_escape(s.status) << "</span></h3>\n";
  if (!s.why.empty()) {
    o << "<ul class=\"why\">";
    for (const std::string& w : s.why) o << "<li>" << html_escape(w) << "</li>";
    o << "</ul>\n";
  }
  o << "<p>" << html_escape(s.controller) << " controller, " << number(s.duration)
    << " s simulated (" << optional_number(s.ticks) << " ticks); peak torque ratio "
    << optional_number(s.max_torque_ratio, 4) << "</p>\n";
  // The timeline.
  const double duration = s.duration;
  o << "<table class=\"motions\"><tr><th>motion</th><th>started</th><th>ended</th><th>ended "
       "by</th><th class=\"bar\">timeline (0 to "
    << number(duration) << " s)</th></tr>\n";
  // In the order they started; those that never did last.
  std::vector<const MotionRow*> motions;
  for (const MotionRow& m : s.motions) motions.push_back(&m);
  std::stable_sort(motions.begin(), motions.end(), [](const MotionRow* a, const MotionRow* b) {
    return a->started_time.value_or(INFINITY) < b->started_time.value_or(INFINITY);
  });
  for (const MotionRow* mp : motions) {
    const MotionRow& m = *mp;
    o << "<tr><td>" << html_escape(m.name) << "</td><td>" << optional_number(m.started_time)
      << " s</td><td>"
      << (m.ended_time ? number(*m.ended_time) + " s"
                       : std::string("still running at ") + number(duration) + " s")
      << "</td><td>" << html_escape(m.ended_by) << "</td><td class=\"bar\">";
    if (m.started_time && duration > 0) {
      const double t0 = *m.started_time, t1 = m.ended_time.value_or(duration);
      const double left = 100 * std::clamp(t0 / duration, 0.0, 1.0);
      const double width = std::max(0.5, 100 * std::clamp((t1 - t0) / duration, 0.0, 1.0));
      o << "<div class=\"run\" style=\"margin-left:" << number(left, 4)
        << "%;width:" << number(width, 4) << "%\"></div>";
    }
    o << "</td></tr>\n";
  }
  o << "</table>\n";
  // Events.
  o << "<details" << (s.events.size() <= 20 ? " open" : "") << "><summary>" << s.events.size()
    << " event(s)</summary><table "
       "class=\"events\"><tr><th>tick</th><th>column</th><th>what</th></tr>\n";
  for (const EventRow& e : s.events) {
    o << "<tr><td>" << optional_number(e.tick, 17) << "</td><td>" << html_escape(e.column)
      << "</td><td>" << html_escape(e.what) << "</td></tr>\n";
  }
  o << "</table></details>\n";
  // Constraints at the end.
  o << "<details><summary>constraints at the end</summary><table class=\"constraints\"><tr><th>"
       "constraint</th><th>relation</th><th>final value</th><th>final "
       "error</th><th>met</th></tr>\n";
  for (const ConstraintRow& c : s.constraints) {
    o << "<tr><td>" << html_escape(c.name) << "</td><td>" << html_escape(c.relation)
      << (c.guard ? " (guard)" : "") << "</td><td>" << optional_number(c.final_value) << "</td><td>"
      << optional_number(c.final_error) << "</td><td>"
      << (c.judged ? (c.satisfied ? "yes" : "no") : "not judged (no tolerance)") << "</td></tr>\n";
  }
  o << "</table></details>\n</section>\n";
  return o.str();
}

namespace fs = std::filesystem;

// `path` read only when it lies inside `dir` once symbolic links are resolved:
// a shared run directory must not make the page carry a file of its reader's.
std::string read_inside(const std::string& path, const std::string& dir, std::string_view what) {
  const fs::path canonical = canonical_path(path);
  const fs::path root = canonical_path(dir);
  if (!is_within(canonical, root) || canonical == root) {
    throw Error("report", "mospec report: the run's " + std::string(what) + " " +
                              escaped_bytes(path) + " resolves to '" +
                              escaped_bytes(canonical.string()) +
                              "', outside the run's directory '" + escaped_bytes(root.string()) +
                              "'; a report reads a run's files only from its own directory "
                              "(copy the file there instead of linking to it)");
  }
  return read_file(canonical.string());
}

}  // namespace

Decimation decimate(const std::vector<const std::vector<double>*>& series, size_t rows,
                    size_t buckets) {
  Decimation d;
  d.row.resize(series.size());
  if (buckets == 0 || rows <= 2 * buckets) {
    for (size_t r = 0; r < rows; ++r) d.time_row.push_back(r);
    for (auto& rs : d.row) rs = d.time_row;
    return d;
  }
  for (size_t b = 0; b < buckets; ++b) {
    const size_t first = b * rows / buckets, last = (b + 1) * rows / buckets - 1;
    d.time_row.push_back(first);
    d.time_row.push_back(last);
    for (size_t k = 0; k < series.size(); ++k) {
      const std::vector<double>& v = *series[k];
      std::optional<size_t> lo, hi;
      for (size_t r = first; r <= last; ++r) {
        if (std::isnan(v[r])) continue;
        if (!lo || v[r] < v[*lo]) lo = r;
        if (!hi || v[r] > v[*hi]) hi = r;
      }
      if (!lo) {
        d.row[k].push_back(first);
        d.row[k].push_back(last);
        continue;
      }
      d.row[k].push_back(std::min(*lo, *hi));
      d.row[k].push_back(std::max(*lo, *hi));
    }
  }
  return d;
}

VideoKind sniff_video(std::string_view bytes) {
  if (bytes.size() >= 12 && bytes.substr(4, 4) == "ftyp") return VideoKind::Mp4;
  if (bytes.size() >= 6 && (bytes.substr(0, 6) == "GIF87a" || bytes.substr(0, 6) == "GIF89a"))
    return VideoKind::Gif;
  return VideoKind::None;
}

LoadedRun load_run(const Run& run, SourceFiles& files) {
  LoadedRun r;
  r.name = run.name;
  r.summary =
      parse_summary(read_inside(run.summary_path, run.dir, "summary"), run.summary_path, files);
  r.log = plot::parse_csv(read_inside(run.log_path, run.dir, "log"), run.log_path);
  if (!r.log.find("t")) {
    throw Error("report",
                "a run log has a `t` column first; this one has none (write logs with "
                "`mospec run --log`)",
                run.log_path, 1, 1);
  }
  if (!run.video_path.empty()) {
    r.video = read_inside(run.video_path, run.dir, "video");
    r.video_kind = sniff_video(r.video);
    const bool gif = fs::path(run.video_path).extension() == ".gif";
    const VideoKind expected = gif ? VideoKind::Gif : VideoKind::Mp4;
    if (r.video_kind != expected) {
      throw Error("report", "mospec report: the run's video " + escaped_bytes(run.video_path) +
                                " is not " + (gif ? "a GIF" : "an MP4") + " (its first bytes say " +
                                (r.video_kind == VideoKind::Gif   ? "GIF"
                                 : r.video_kind == VideoKind::Mp4 ? "MP4"
                                                                  : "neither") +
                                "); the page inlines only videos that `mospec run --video` "
                                "writes (remove the file, or pass --no-video)");
    }
  }
  return r;
}

std::string link_to(const std::string& file, const std::string& page, bool absolute) {
  std::error_code ec;
  const fs::path target = fs::absolute(file, ec).lexically_normal();
  if (ec) return {};
  if (absolute) return "file://" + url_path_escape(target.generic_string());
  const fs::path page_dir = fs::absolute(page == "-" ? fs::path(".") / "page" : fs::path(page), ec)
                                .lexically_normal()
                                .parent_path();
  if (ec) return {};
  return url_path_escape(target.lexically_relative(page_dir).generic_string());
}

std::string dygraphs_dir() {
  const char* env = std::getenv("MOSPEC_DYGRAPHS_DIR");
  return env && *env ? env : "/usr/share/javascript/dygraphs";
}

Assets load_assets() {
  const std::string dir = dygraphs_dir();
  try {
    return {read_file(dir + "/dygraph.min.js"), read_file(dir + "/dygraph.min.css")};
  } catch (const Error& e) {
    throw Error("report",
                std::string("the page needs dygraphs from Debian's libjs-dygraphs (run "
                            "scripts/install-deps): ") +
                    e.diagnostic().message,
                e.diagnostic().file, e.diagnostic().line, e.diagnostic().column);
  }
}

std::string render(const Input& in, const Assets& assets) {
  if (in.runs.empty()) throw Error("report", "mospec report: no run to report");
  for (const LoadedRun& r : in.runs) {
    if (r.log.columns != in.runs.front().log.columns)
      throw Error("report",
                  "its columns differ from " + in.runs.front().log.path +
                      "'s; the trials of one report come from one app",
                  r.log.path, 1, 1);
  }
  std::vector<const plot::Table*> logs;
  for (const LoadedRun& r : in.runs) logs.push_back(&r.log);

  std::ostringstream o;
  o << "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n<title>"
    << html_escape(in.title) << "</title>\n<style>\n"
    << assets.css << "\n"
    << "body{font-family:sans-serif;margin:1.5em;max-width:75em;color:#222}"
       "h1{font-size:1.5em}h2{font-size:1.2em;border-bottom:1px solid #ccc}"
       "h3{font-size:1.05em}.status.ok{color:#070}.status.failed{color:#b00}"
       "table{border-collapse:collapse;margin:.5em 0}td,th{border:1px solid #ddd;padding:2px 6px;"
       "font-size:.9em;text-align:left}td.bar,th.bar{width:30em}"
       ".run{height:.8em;background:#48a}.chart{width:100%;height:260px;margin:.5em 0 2em}"
       ".note{color:#666;font-size:.9em}.legend{font-size:.85em;margin:-1.5em 0 2em}"
       ".legend .dygraph-legend-line{display:inline-block}\n</style>\n</head><body>\n";
  o << "<h1>" << html_escape(in.title) << "</h1>\n";
  o << "<h2>Model</h2>\n<p class=\"model " << (in.model_ok ? "ok" : "failed") << "\">"
    << html_escape(in.model_verdict) << "</p>\n";
  if (!in.entities.empty()) {
    o << "<details><summary>" << in.entities.size()
      << " constraints, monitors, controllers and motions</summary><table class=\"entities\">"
         "<tr><th>kind</th><th>entity</th><th>where</th></tr>\n";
    for (const Entity& e : in.entities) {
      o << "<tr><td>" << html_escape(e.kind) << "</td><td>" << html_escape(e.iri) << "</td><td>";
      if (!e.file.empty()) {
        const std::string where = html_escape(format_place(e.file, e.line, 0));
        const std::string href = link_to(e.file, in.page, in.absolute_links);
        if (href.empty())
          o << where;
        else
          o << "<a href=\"" << html_escape(href) << "\">" << where << "</a>";
      }
      o << "</td></tr>\n";
    }
    o << "</table></details>\n";
  }
  o << "<h2>" << (in.runs.size() == 1 ? "Verdict" : "Verdicts of the trials") << "</h2>\n";
  for (const LoadedRun& r : in.runs) o << verdict_html(r);

  // The video of the (first) run that has one.
  for (const LoadedRun& r : in.runs) {
    if (r.video_kind == VideoKind::None) continue;
    o << "<h2>Video</h2>\n";
    if (r.video_kind == VideoKind::Gif) {
      o << "<img class=\"video\" alt=\"the run of " << html_escape(r.name)
        << "\" src=\"data:image/gif;base64," << base64(r.video) << "\">\n";
    } else {
      o << "<video class=\"video\" controls muted src=\"data:video/mp4;base64," << base64(r.video)
        << "\"></video>\n";
    }
    break;
  }

  // The charts.
  const plot::LogInfo& info =
      in.runs.front().summary.log.empty() ? in.log_info : in.runs.front().summary.log;
  o << "<h2>Time series</h2>\n<p class=\"note\">"
    << (in.runs.size() == 1 ? "Hover for values; drag to zoom, double-click to reset; the "
                              "range selector under each chart pans."
                            : "Mean ± one standard deviation over the trials. Hover for values; "
                              "drag to zoom, double-click to reset.")
    << " A shaded band is where a constraint holds (its thresholds, or its setpoint ± its "
       "tolerance); a dashed line, a setpoint without a tolerance.</p>\n";
  const std::vector<Group> groups = group_columns(*logs.front(), info);
  std::vector<ChartSpec> specs;
  for (const Group& g : groups) specs.push_back(chart_spec(*logs.front(), g, info));
  // The data of every chart, at the most buckets that keep it in the budget.
  std::vector<std::string> data(groups.size());
  std::vector<size_t> kept(groups.size());
  // The data's size is about proportional to the buckets: a page over the
  // budget is made again with as many as fit (a tenth fewer each further try).
  for (size_t buckets = kBuckets;;) {
    size_t bytes = 0;
    for (size_t g = 0; g < groups.size(); ++g) {
      data[g] = chart_data(logs, specs[g], buckets, kept[g]);
      bytes += data[g].size();
    }
    if (bytes <= kDataBudget || buckets == kMinBuckets) break;
    const double fit = static_cast<double>(buckets) * kDataBudget / static_cast<double>(bytes);
    buckets = std::max(kMinBuckets, std::min(buckets * 9 / 10, static_cast<size_t>(fit)));
  }
  const size_t rows = logs.front()->rows();
  Json charts = Json::array();
  for (size_t g = 0; g < groups.size(); ++g) {
    const Group& group = groups[g];
    const ChartSpec& spec = specs[g];
    Json labels = Json::array({"t"});
    for (size_t c : spec.columns) labels.push_back(logs.front()->columns[c]);
    const std::string id = "chart-" + std::to_string(g);
    Json chart;
    chart["id"] = id;
    // dygraphs writes an axis label as HTML (innerHTML): escaped for it.
    chart["ylabel"] = group.unit.empty() ? std::string() : html_escape("[" + group.unit + "]");
    chart["labels"] = labels;
    chart["visible"] = spec.visible;
    chart["steps"] = group.steps;
    chart["trials"] = in.runs.size() > 1;
    Json bands = Json::array();
    for (const Band& b : spec.bands) {
      Json x;
      x["s"] = b.series;
      x["lo"] = b.lo ? Json(*b.lo) : Json(nullptr);
      x["hi"] = b.hi ? Json(*b.hi) : Json(nullptr);
      x["loS"] = b.lo_series ? Json(*b.lo_series) : Json(nullptr);
      x["hiS"] = b.hi_series ? Json(*b.hi_series) : Json(nullptr);
      bands.push_back(std::move(x));
    }
    chart["bands"] = std::move(bands);
    const std::string unit = group.steps          ? "flags and running motions 0/1; event codes"
                             : group.unit.empty() ? "unit not recorded by this run"
                                                  : group.unit;
    o << "<h3>" << html_escape(group.title) << " <span class=\"note\">[" << html_escape(unit) << "]"
      << (kept[g] < rows ? "; " + std::to_string(rows) +
                               " logged rows drawn as each series' "
                               "minimum and maximum over " +
                               std::to_string(kept[g] / 2) + " intervals"
                         : std::string())
      << "</span></h3>\n"
      << "<div class=\"chart\" id=\"" << id << "\"></div>"
      << "<div class=\"legend\" id=\"" << id << "-legend\"></div>\n";
    charts.push_back(std::move(chart));
  }
  // The data goes in as JSON made safe for a script block: with its
  // non-ASCII escaped (dump's ensure_ascii) and '<', '>', '&' as \u escapes,
  // no label or value can end the block or open a comment in it. The series'
  // values are numbers and null only (append_value()).
  std::string all_data = "[";
  for (size_t g = 0; g < data.size(); ++g) all_data += (g ? "," : "") + data[g];
  all_data += "]";
  o << "<script>\n"
    << assets.js << "\n</script>\n<script>\n\"use strict\";\nconst charts = "
    << script_safe_json(charts.dump(-1, ' ', true, Json::error_handler_t::replace))
    << ";\nconst chartData = " << script_safe_json(all_data) << ";\n"
    << kChartScript << "</script>\n</body></html>\n";
  return o.str();
}

}  // namespace mospec::report
