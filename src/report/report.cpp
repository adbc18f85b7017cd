#include "report/report.hpp"

#include <algorithm>
#include <cmath>
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

// At most this many rows per chart: a longer log is decimated uniformly (the
// page says so), keeping the page a few MB for a 30 s run.
constexpr size_t kMaxChartRows = 4000;

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

// The log's columns, grouped into the page's charts.
struct Group {
  std::string title, unit_hint;
  std::vector<size_t> columns;
  bool steps = false;  // flags and events: drawn as steps
};

std::vector<Group> group_columns(const plot::Table& t) {
  std::vector<Group> g = {
      {"Motions running", "0/1", {}, true},
      {"Constraint values", "the constrained quantities' units", {}},
      {"Constraint errors", "target − measured, the quantities' units", {}},
      {"Controller outputs", "the control signals' units", {}},
      {"Monitors and events", "flags 0/1, event codes", {}, true},
      {"Contact and ground wrenches (simulator)", "N, N·m", {}},
      {"Base pose (simulator)", "m, rad", {}},
      {"Joint positions (simulator)", "rad", {}},
      {"Joint velocities (simulator)", "rad/s", {}},
      {"Joint torques (simulator)", "N·m", {}},
  };
  for (size_t i = 0; i < t.columns.size(); ++i) {
    const std::string& c = t.columns[i];
    if (c == "t") continue;
    int k = -1;
    if (ends_with(c, ".running"))
      k = 0;
    else if (ends_with(c, ".value"))
      k = 1;
    else if (ends_with(c, ".error"))
      k = 2;
    else if (ends_with(c, ".output"))
      k = 3;
    else if (ends_with(c, ".flag") || ends_with(c, ".event") || ends_with(c, ".ended"))
      k = 4;
    else if (ends_with(c, "_fn") || ends_with(c, "_fx") || ends_with(c, "_fy") ||
             ends_with(c, "_fz") || starts_with(c, "ground_"))
      k = 5;
    else if (starts_with(c, "base_"))
      k = 6;
    else if (c.find("_q") != std::string::npos && c.find("_qd") == std::string::npos &&
             (starts_with(c, "right_") || starts_with(c, "left_")))
      k = 7;
    else if (c.find("_qd") != std::string::npos)
      k = 8;
    else if (c.find("_tau") != std::string::npos)
      k = 9;
    if (k >= 0) g[static_cast<size_t>(k)].columns.push_back(i);
  }
  std::erase_if(g, [](const Group& x) { return x.columns.empty(); });
  return g;
}

// One chart's data: rows of [t, v...] (a single run) or [t, [mean, std]...]
// (trials), decimated to at most kMaxChartRows rows.
Json chart_data(const std::vector<const plot::Table*>& runs, const Group& group, size_t& step) {
  size_t rows = runs.front()->rows();
  for (const plot::Table* r : runs) rows = std::min(rows, r->rows());
  step = std::max<size_t>(1, (rows + kMaxChartRows - 1) / kMaxChartRows);
  const size_t t = runs.front()->find("t").value_or(0);
  Json data = Json::array();
  auto value = [](double v) { return std::isfinite(v) ? Json(v) : Json(nullptr); };
  for (size_t row = 0; row < rows; row += step) {
    Json r = Json::array({runs.front()->data[t][row]});
    for (size_t c : group.columns) {
      if (runs.size() == 1) {
        r.push_back(value(runs.front()->data[c][row]));
        continue;
      }
      double sum = 0, sq = 0;
      size_t n = 0;
      for (const plot::Table* run : runs) {
        const double v = run->data[c][row];
        if (!std::isfinite(v)) continue;
        sum += v;
        sq += v * v;
        ++n;
      }
      const double mean = n ? sum / static_cast<double>(n) : std::nan("");
      const double var =
          n > 1 ? std::max(0.0, (sq - n * mean * mean) / static_cast<double>(n - 1)) : 0.0;
      r.push_back(Json::array({value(mean), value(std::sqrt(var))}));
    }
    data.push_back(std::move(r));
  }
  return data;
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
  for (const MotionRow& m : s.motions) {
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
       ".note{color:#666;font-size:.9em}\n</style>\n</head><body>\n";
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
  o << "<h2>Time series</h2>\n<p class=\"note\">"
    << (in.runs.size() == 1 ? "Hover for values; drag to zoom, double-click to reset; the "
                              "range selector under each chart pans."
                            : "Mean ± one standard deviation over the trials. Hover for values; "
                              "drag to zoom, double-click to reset.")
    << "</p>\n";
  Json charts = Json::array();
  const std::vector<Group> groups = group_columns(*logs.front());
  for (size_t g = 0; g < groups.size(); ++g) {
    size_t step = 1;
    Json labels = Json::array({"t"});
    for (size_t c : groups[g].columns) labels.push_back(logs.front()->columns[c]);
    const std::string id = "chart-" + std::to_string(g);
    Json chart;
    chart["id"] = id;
    chart["title"] = groups[g].title;
    chart["labels"] = labels;
    chart["steps"] = groups[g].steps;
    chart["trials"] = in.runs.size() > 1;
    chart["data"] = chart_data(logs, groups[g], step);
    o << "<h3>" << html_escape(groups[g].title) << " <span class=\"note\">("
      << html_escape(groups[g].unit_hint)
      << (step > 1 ? "; every " + std::to_string(step) + "th logged row" : std::string())
      << ")</span></h3>\n"
      << "<div class=\"chart\" id=\"" << id << "\"></div>\n";
    charts.push_back(std::move(chart));
  }
  // The data goes in as JSON made safe for a script block: with its
  // non-ASCII escaped (dump's ensure_ascii) and '<', '>', '&' as \u escapes,
  // no label or value can end the block or open a comment in it.
  o << "<script>\n"
    << assets.js << "\n</script>\n<script>\n\"use strict\";\nconst charts = "
    << script_safe_json(charts.dump(-1, ' ', true, Json::error_handler_t::replace))
    << ";\nwindow.mospecCharts = charts.map(c => new Dygraph(document.getElementById(c.id), "
       "c.data, {labels: c.labels, xlabel: 't [s]', legend: 'follow', stepPlot: c.steps, "
       "errorBars: c.trials, sigma: 1, showRangeSelector: !c.trials, labelsSeparateLines: true, "
       "connectSeparatedPoints: false}));\ndocument.body.dataset.charts = "
       "String(window.mospecCharts.length);\n</script>\n</body></html>\n";
  return o.str();
}

}  // namespace mospec::report
