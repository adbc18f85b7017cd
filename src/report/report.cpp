#include "report/report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>

#include "plot/csv.hpp"
#include "support/diagnostics.hpp"
#include "support/io.hpp"

namespace mospec::report {
namespace {

using Json = nlohmann::ordered_json;

// At most this many rows per chart: a longer log is decimated uniformly (the
// page says so), keeping the page a few MB for a 30 s run.
constexpr size_t kMaxChartRows = 4000;

std::string html(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&#39;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

// JSON for a <script> block: "</" cannot end the script early.
std::string script_json(const Json& j) {
  std::string s = j.dump(-1, ' ', true, Json::error_handler_t::replace);
  std::string out;
  out.reserve(s.size());
  for (size_t i = 0; i < s.size(); ++i) {
    if (s[i] == '<' && i + 1 < s.size() && s[i + 1] == '/') {
      out += "<\\/";
      ++i;
    } else {
      out += s[i];
    }
  }
  return out;
}

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

std::string json_text(const Json& j) {
  if (j.is_null()) return "–";
  if (j.is_string()) return j.get<std::string>();
  if (j.is_number_float()) return number(j.get<double>());
  return j.dump();
}

bool ends_with(std::string_view s, std::string_view suffix) {
  return s.size() >= suffix.size() && s.substr(s.size() - suffix.size()) == suffix;
}
bool starts_with(std::string_view s, std::string_view prefix) {
  return s.substr(0, prefix.size()) == prefix;
}

Json read_summary(const std::string& path) {
  try {
    Json j = Json::parse(read_file(path));
    if (!j.is_object() || !j.contains("verdict"))
      throw Error("report", path +
                                ": not a run summary (no \"verdict\"): write it with "
                                "`mospec run --sim --summary FILE.json`");
    return j;
  } catch (const Json::exception& e) {
    throw Error("report", path + ": not a run summary: " + e.what());
  }
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
Json chart_data(const std::vector<plot::Table>& runs, const Group& group, size_t& step) {
  size_t rows = runs.front().rows();
  for (const plot::Table& r : runs) rows = std::min(rows, r.rows());
  step = std::max<size_t>(1, (rows + kMaxChartRows - 1) / kMaxChartRows);
  const size_t t = runs.front().find("t").value_or(0);
  Json data = Json::array();
  auto value = [](double v) { return std::isfinite(v) ? Json(v) : Json(nullptr); };
  for (size_t row = 0; row < rows; row += step) {
    Json r = Json::array({runs.front().data[t][row]});
    for (size_t c : group.columns) {
      if (runs.size() == 1) {
        r.push_back(value(runs.front().data[c][row]));
        continue;
      }
      double sum = 0, sq = 0;
      size_t n = 0;
      for (const plot::Table& run : runs) {
        const double v = run.data[c][row];
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

std::string verdict_html(const std::string& name, const Json& summary) {
  const Json& v = summary["verdict"];
  std::ostringstream o;
  const std::string status = v.value("status", std::string("unknown"));
  o << "<section class=\"verdict\" id=\"verdict-" << html(name) << "\"><h3>" << html(name)
    << ": <span class=\"status " << (status == "ok" ? "ok" : "failed") << "\">" << html(status)
    << "</span></h3>\n";
  if (v.contains("why") && v["why"].is_array() && !v["why"].empty()) {
    o << "<ul class=\"why\">";
    for (const Json& w : v["why"]) o << "<li>" << html(json_text(w)) << "</li>";
    o << "</ul>\n";
  }
  o << "<p>" << html(summary.value("controller", std::string())) << " controller, "
    << number(summary.value("duration", 0.0)) << " s simulated ("
    << json_text(summary.value("ticks", Json(nullptr))) << " ticks); peak torque ratio "
    << html(number(summary.value("max_torque_ratio", 0.0), 4)) << "</p>\n";
  // The timeline.
  const double duration = summary.value("duration", 0.0);
  o << "<table class=\"motions\"><tr><th>motion</th><th>started</th><th>ended</th><th>ended "
       "by</th><th class=\"bar\">timeline (0 to "
    << number(duration) << " s)</th></tr>\n";
  for (const Json& m : v.value("motions", Json::array())) {
    const double t0 =
        m.value("started_time", Json(nullptr)).is_number() ? m["started_time"].get<double>() : NAN;
    const double t1 =
        m.value("ended_time", Json(nullptr)).is_number() ? m["ended_time"].get<double>() : duration;
    o << "<tr><td>" << html(m.value("name", std::string())) << "</td><td>"
      << html(json_text(m.value("started_time", Json(nullptr)))) << " s</td><td>"
      << (m.value("ended_time", Json(nullptr)).is_number()
              ? html(json_text(m["ended_time"])) + " s"
              : std::string("still running at ") + number(duration) + " s")
      << "</td><td>" << html(m.value("ended_by", std::string())) << "</td><td class=\"bar\">";
    if (std::isfinite(t0) && duration > 0) {
      const double left = 100 * std::clamp(t0 / duration, 0.0, 1.0);
      const double width = std::max(0.5, 100 * std::clamp((t1 - t0) / duration, 0.0, 1.0));
      o << "<div class=\"run\" style=\"margin-left:" << number(left, 4)
        << "%;width:" << number(width, 4) << "%\"></div>";
    }
    o << "</td></tr>\n";
  }
  o << "</table>\n";
  // Events.
  const Json events = summary.value("events", Json::array());
  o << "<details" << (events.size() <= 20 ? " open" : "") << "><summary>" << events.size()
    << " event(s)</summary><table "
       "class=\"events\"><tr><th>tick</th><th>column</th><th>what</th></tr>\n";
  for (const Json& e : events) {
    o << "<tr><td>" << html(json_text(e.value("tick", Json(nullptr)))) << "</td><td>"
      << html(json_text(e.value("event", Json(nullptr)))) << "</td><td>"
      << html(json_text(e.contains("reason") ? e["reason"] : e.value("edge", Json(nullptr))))
      << "</td></tr>\n";
  }
  o << "</table></details>\n";
  // Constraints at the end.
  o << "<details><summary>constraints at the end</summary><table class=\"constraints\"><tr><th>"
       "constraint</th><th>relation</th><th>final value</th><th>final "
       "error</th><th>met</th></tr>\n";
  for (const Json& c : v.value("constraints", Json::array())) {
    const bool judged = c.value("judged", true);
    o << "<tr><td>" << html(c.value("name", std::string())) << "</td><td>"
      << html(c.value("relation", std::string())) << (c.value("guard", false) ? " (guard)" : "")
      << "</td><td>" << html(json_text(c.value("final_value", Json(nullptr)))) << "</td><td>"
      << html(json_text(c.value("final_error", Json(nullptr)))) << "</td><td>"
      << (judged ? (c.value("satisfied", false) ? "yes" : "no") : "not judged (no tolerance)")
      << "</td></tr>\n";
  }
  o << "</table></details>\n</section>\n";
  return o.str();
}

}  // namespace

std::string dygraphs_dir() {
  const char* env = std::getenv("MOSPEC_DYGRAPHS_DIR");
  return env && *env ? env : "/usr/share/javascript/dygraphs";
}

std::string render(const Input& in) {
  if (in.runs.empty()) throw Error("report", "mospec report: no run to report");
  const std::string dir = dygraphs_dir();
  std::string js, css;
  try {
    js = read_file(dir + "/dygraph.min.js");
    css = read_file(dir + "/dygraph.min.css");
  } catch (const Error& e) {
    throw Error("report", std::string("mospec report: the page needs dygraphs from Debian's "
                                      "libjs-dygraphs (run scripts/install-deps): ") +
                              e.what());
  }
  std::vector<plot::Table> logs;
  std::vector<Json> summaries;
  for (const Run& r : in.runs) {
    logs.push_back(plot::read_csv(r.log_path));
    summaries.push_back(read_summary(r.summary_path));
    if (!logs.back().find("t"))
      throw Error("report", r.log_path + ": a run log has a `t` column; this one has none");
  }
  for (const plot::Table& l : logs) {
    if (l.columns != logs.front().columns)
      throw Error("report", l.path + ": its columns differ from " + logs.front().path +
                                "'s; trials of one report come from one app");
  }

  std::ostringstream o;
  o << "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n<title>"
    << html(in.title) << "</title>\n<style>\n"
    << css << "\n"
    << "body{font-family:sans-serif;margin:1.5em;max-width:75em;color:#222}"
       "h1{font-size:1.5em}h2{font-size:1.2em;border-bottom:1px solid #ccc}"
       "h3{font-size:1.05em}.status.ok{color:#070}.status.failed{color:#b00}"
       "table{border-collapse:collapse;margin:.5em 0}td,th{border:1px solid #ddd;padding:2px 6px;"
       "font-size:.9em;text-align:left}td.bar,th.bar{width:30em}"
       ".run{height:.8em;background:#48a}.chart{width:100%;height:260px;margin:.5em 0 2em}"
       ".note{color:#666;font-size:.9em}\n</style>\n</head><body>\n";
  o << "<h1>" << html(in.title) << "</h1>\n";
  o << "<h2>Model</h2>\n<p class=\"model " << (in.model_ok ? "ok" : "failed") << "\">"
    << html(in.model_verdict) << "</p>\n";
  if (!in.entities.empty()) {
    o << "<details><summary>" << in.entities.size()
      << " constraints, monitors, controllers and motions</summary><table class=\"entities\">"
         "<tr><th>kind</th><th>entity</th><th>where</th></tr>\n";
    for (const Entity& e : in.entities) {
      o << "<tr><td>" << html(e.kind) << "</td><td>" << html(e.iri) << "</td><td>";
      if (!e.file.empty()) {
        o << "<a href=\"" << html(e.url.empty() ? e.file : e.url) << "\">" << html(e.file) << ":"
          << e.line << "</a>";
      }
      o << "</td></tr>\n";
    }
    o << "</table></details>\n";
  }
  o << "<h2>" << (in.runs.size() == 1 ? "Verdict" : "Verdicts of the trials") << "</h2>\n";
  for (size_t i = 0; i < in.runs.size(); ++i) o << verdict_html(in.runs[i].name, summaries[i]);

  // The video of the (first) run.
  for (const Run& r : in.runs) {
    if (r.video_path.empty()) continue;
    const std::string bytes = read_file(r.video_path);
    o << "<h2>Video</h2>\n";
    if (ends_with(r.video_path, ".gif")) {
      o << "<img class=\"video\" alt=\"the run of " << html(r.name)
        << "\" src=\"data:image/gif;base64," << base64(bytes) << "\">\n";
    } else {
      o << "<video class=\"video\" controls muted src=\"data:video/mp4;base64," << base64(bytes)
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
  const std::vector<Group> groups = group_columns(logs.front());
  for (size_t g = 0; g < groups.size(); ++g) {
    size_t step = 1;
    Json labels = Json::array({"t"});
    for (size_t c : groups[g].columns) labels.push_back(logs.front().columns[c]);
    Json chart;
    chart["id"] = "chart-" + std::to_string(g);
    chart["title"] = groups[g].title;
    chart["labels"] = labels;
    chart["steps"] = groups[g].steps;
    chart["trials"] = in.runs.size() > 1;
    chart["data"] = chart_data(logs, groups[g], step);
    o << "<h3>" << html(groups[g].title) << " <span class=\"note\">(" << html(groups[g].unit_hint)
      << (step > 1 ? "; every " + std::to_string(step) + "th logged row" : std::string())
      << ")</span></h3>\n"
      << "<div class=\"chart\" id=\"" << chart["id"].get<std::string>() << "\"></div>\n";
    charts.push_back(std::move(chart));
  }
  o << "<script>\n"
    << js << "\n</script>\n<script>\n\"use strict\";\nconst charts = " << script_json(charts)
    << ";\nwindow.mospecCharts = charts.map(c => new Dygraph(document.getElementById(c.id), "
       "c.data, {labels: c.labels, xlabel: 't [s]', legend: 'follow', stepPlot: c.steps, "
       "errorBars: c.trials, sigma: 1, showRangeSelector: !c.trials, labelsSeparateLines: true, "
       "connectSeparatedPoints: false}));\ndocument.body.dataset.charts = "
       "String(window.mospecCharts.length);\n</script>\n</body></html>\n";
  return o.str();
}

}  // namespace mospec::report
