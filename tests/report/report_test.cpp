// The report page with data someone else wrote: every value escaped for the
// context it lands in, summaries type-checked with located errors, run files
// read only from the run's directory, videos only when their header says so.
#include "report/report.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>

#include "report/html.hpp"
#include "report/summary.hpp"

namespace mospec::report {
namespace {

namespace fs = std::filesystem;

// What a hostile summary or log puts into every field it can.
const std::string kHostile =
    "</script><script>document.body.dataset.pwned=1</script><!--<script>"
    "<img src=x onerror=\"document.body.dataset.pwned=1\">&'\"\x01\xff";

TEST(HtmlEscape, EscapesMarkupQuotesAndBytesThatAreNotText) {
  EXPECT_EQ(html_escape("a<b>&\"'"), "a&lt;b&gt;&amp;&quot;&#39;");
  EXPECT_EQ(html_escape("tab\tnew\nline"), "tab\tnew\nline");
  EXPECT_EQ(html_escape(std::string("nul\0x", 5)), "nul\xEF\xBF\xBDx");
  EXPECT_EQ(html_escape("\x7f"), "\xEF\xBF\xBD");
  EXPECT_EQ(html_escape("\xC3\xA9"), "\xC3\xA9");                                  // é stays
  EXPECT_EQ(html_escape("\xC3"), "\xEF\xBF\xBD");                                  // cut short
  EXPECT_EQ(html_escape("\xC0\xBC"), "\xEF\xBF\xBD\xEF\xBF\xBD");                  // overlong '<'
  EXPECT_EQ(html_escape("\xED\xA0\x80"), "\xEF\xBF\xBD\xEF\xBF\xBD\xEF\xBF\xBD");  // surrogate
  const std::string out = html_escape(kHostile);
  EXPECT_EQ(out.find('<'), std::string::npos);
  EXPECT_EQ(out.find('"'), std::string::npos);
}

TEST(UrlPathEscape, KeepsOnlyUnreservedCharactersAndSlashes) {
  EXPECT_EQ(url_path_escape("../models/sc0a/05 x.json"), "../models/sc0a/05%20x.json");
  EXPECT_EQ(url_path_escape("javascript:alert(1)"), "javascript%3Aalert%281%29");
  EXPECT_EQ(url_path_escape("a\"b?c#d"), "a%22b%3Fc%23d");
}

TEST(ScriptSafeJson, NoSequenceCanEndOrCommentOutTheBlock) {
  EXPECT_EQ(script_safe_json(R"(["</script>","<!--","&"])"),
            R"(["\u003c/script\u003e","\u003c!--","\u0026"])");
}

std::string summary_with(const std::string& verdict_fields, const std::string& top = "") {
  return R"({"scenario": "", )" + top + R"("verdict": {)" + verdict_fields + "}}";
}

// The error's text, or "" when it parses.
std::string summary_error(const std::string& text) {
  SourceFiles files;
  try {
    (void)parse_summary(text, "run/s.json", files);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(Summary, WrongTypesAreLocatedErrors) {
  EXPECT_EQ(summary_error(summary_with(R"("status": 3)")),
            "run/s.json:1:40: error: verdict.status is a number; a run summary has a string "
            "there (write summaries with `mospec run --summary`)");
  EXPECT_EQ(summary_error(summary_with(R"("status": "ok")", R"("duration": "10", )")),
            "run/s.json:1:30: error: \"duration\" is a string; a run summary has a number of "
            "seconds there (write summaries with `mospec run --summary`)");
  EXPECT_NE(summary_error(summary_with(R"("why": ["a", {"b": 1}])"))
                .find("run/s.json:1:43: "
                      "error: an element of "
                      "verdict.why is an "
                      "object"),
            std::string::npos);
  EXPECT_NE(summary_error(summary_with(R"("motions": [{"name": "m", "started_time": "0"}])"))
                .find("a motion's \"started_time\" is a string"),
            std::string::npos);
  EXPECT_NE(summary_error(summary_with(R"("constraints": [{"guard": "yes"}])"))
                .find("a constraint's \"guard\" is a string; a run summary has true or false"),
            std::string::npos);
  EXPECT_NE(summary_error(summary_with("", R"("events": [1], )")).find("an element of \"events\""),
            std::string::npos);
  EXPECT_NE(summary_error(summary_with("", R"("duration": -1, )"))
                .find("\"duration\" is -1; a run lasts a finite, non-negative number"),
            std::string::npos);
  EXPECT_NE(summary_error("[]").find("run/s.json:1:1: error: not a run summary"),
            std::string::npos);
  EXPECT_NE(summary_error(R"({"verdict": []})").find("\"verdict\" is an array"), std::string::npos);
}

TEST(Summary, NestingPastTheReadersLimitIsALocatedErrorNotACrash) {
  const std::string deep = summary_with(R"("why": )" + std::string(100000, '[') + "]");
  const std::string error = summary_error(deep);
  EXPECT_NE(error.find("run/s.json:1:"), std::string::npos) << error;
  EXPECT_NE(error.find("nesting deeper than 512 levels"), std::string::npos) << error;
}

TEST(Summary, ReadsTheFieldsThePageShows) {
  SourceFiles files;
  const Summary s =
      parse_summary(summary_with(R"("status": "failed", "why": ["w"], "motions": [{"name": "m",
        "started_time": 0.5, "ended_time": null, "ended_by": "running"}], "constraints":
        [{"name": "c", "relation": "equality", "final_value": 1, "judged": false}])",
                                 R"("controller": "generated", "duration": 2, "ticks": 2000,
        "events": [{"tick": 3, "event": "x.flag", "edge": "rising"}], )"),
                    "s.json", files);
  EXPECT_EQ(s.status, "failed");
  ASSERT_EQ(s.motions.size(), 1u);
  EXPECT_EQ(s.motions[0].started_time, 0.5);
  EXPECT_FALSE(s.motions[0].ended_time);
  ASSERT_EQ(s.constraints.size(), 1u);
  EXPECT_FALSE(s.constraints[0].judged);
  ASSERT_EQ(s.events.size(), 1u);
  EXPECT_EQ(s.events[0].what, "rising");
  EXPECT_EQ(s.ticks, 2000);
}

TEST(SniffVideo, TrustsTheHeaderNotTheName) {
  EXPECT_EQ(sniff_video(std::string("\0\0\0\x20"
                                    "ftypisom\0\0\0\0",
                                    16)),
            VideoKind::Mp4);
  EXPECT_EQ(sniff_video("GIF89a...."), VideoKind::Gif);
  EXPECT_EQ(sniff_video("GIF87a"), VideoKind::Gif);
  EXPECT_EQ(sniff_video("-----BEGIN OPENSSH PRIVATE KEY-----"), VideoKind::None);
  EXPECT_EQ(sniff_video(""), VideoKind::None);
}

TEST(LinkTo, RelativeToThePageUnlessAbsoluteIsAsked) {
  const fs::path cwd = fs::current_path();
  EXPECT_EQ(link_to("models/a b.json", "out/report.html", false), "../models/a%20b.json");
  EXPECT_EQ(link_to("models/a.json", "report.html", false), "models/a.json");
  EXPECT_EQ(link_to("models/a.json", "-", false), "models/a.json");
  EXPECT_EQ(link_to("models/a.json", "report.html", true),
            "file://" + url_path_escape((cwd / "models/a.json").generic_string()));
}

// A page built from a summary and a log that put markup everywhere they can.
Input hostile_input() {
  Input in;
  in.title = kHostile;
  in.model_verdict = kHostile;
  in.entities.push_back({kHostile, kHostile, "javascript:" + kHostile, 3});
  in.page = "report.html";
  LoadedRun r;
  r.name = kHostile;
  Summary& s = r.summary;
  s.status = kHostile;
  s.why = {kHostile};
  s.controller = kHostile;
  s.duration = 1;
  s.motions.push_back({kHostile, 0.0, 1.0, kHostile});
  s.events.push_back({1.0, kHostile, kHostile});
  s.constraints.push_back({kHostile, kHostile, false, 1.0, 0.0, true, true});
  r.log = plot::parse_csv("t,a.value,\"b\".error\n0,1,2\n1,2,3\n", "log.csv");
  r.log.columns[1] = kHostile + ".value";
  // A unit lands in a chart's title and in its axis label, which dygraphs
  // writes as HTML.
  s.log.units[kHostile + ".value"] = kHostile;
  s.log.constraints[kHostile] = {"equality", 1.0, std::nullopt, std::nullopt, 0.5};
  in.runs.push_back(std::move(r));
  return in;
}

size_t count(const std::string& text, const std::string& what) {
  size_t n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

TEST(Render, HostileDataCannotAddMarkupOrBreakTheScriptBlocks) {
  const std::string page = render(hostile_input(), {"/*js*/", "/*css*/"});
  // The template's own two script blocks, nothing else: no data can open,
  // close or comment one out.
  EXPECT_EQ(count(page, "<script"), 2u);
  EXPECT_EQ(count(page, "</script"), 2u);
  EXPECT_EQ(count(page, "<!--"), 0u);
  EXPECT_EQ(count(page, "<img"), 0u);
  const std::string markup = page.substr(0, page.rfind("<script>"));
  EXPECT_EQ(count(markup, "onerror=\""), 0u);
  // Every tag on the page is one the template writes.
  static const std::regex kTag("<(/?)([a-zA-Z0-9!]+)");
  const std::set<std::string> allowed = {"!DOCTYPE", "html",  "head", "meta", "title", "style",
                                         "body",     "h1",    "h2",   "h3",   "p",     "details",
                                         "summary",  "table", "tr",   "th",   "td",    "a",
                                         "section",  "span",  "ul",   "li",   "div",   "script"};
  for (auto it = std::sregex_iterator(page.begin(), page.end(), kTag); it != std::sregex_iterator();
       ++it)
    EXPECT_TRUE(allowed.count((*it)[2].str())) << (*it)[0].str();
  // A file named like a javascript: URL is linked as a relative path.
  EXPECT_EQ(count(page, "href=\"javascript:"), 0u);
  EXPECT_EQ(count(page, "href=\"javascript%3A"), 1u);
  // The column's name reaches the chart, as data.
  EXPECT_NE(page.find("\\u003c/script\\u003e\\u003cscript\\u003edocument.body.dataset.pwned=1"),
            std::string::npos);
}

// A run directory in a temporary directory.
class RunDir : public ::testing::Test {
 protected:
  void SetUp() override {
    char tmpl[] = "/tmp/mospec-report-XXXXXX";
    root_ = mkdtemp(tmpl);
    fs::create_directory(root_ / "run");
    write("run/r.json", summary_with(R"("status": "ok")", R"("duration": 1, )"));
    write("run/r.csv", "t,a.value\n0,1\n1,2\n");
  }
  void TearDown() override { fs::remove_all(root_); }
  void write(const std::string& name, const std::string& text) {
    std::ofstream(root_ / name, std::ios::binary) << text;
  }
  report::Run run(const std::string& video = "") const {
    report::Run r;
    r.name = "r";
    r.dir = (root_ / "run").string();
    r.summary_path = (root_ / "run/r.json").string();
    r.log_path = (root_ / "run/r.csv").string();
    if (!video.empty()) r.video_path = (root_ / "run" / video).string();
    return r;
  }
  std::string load_error(const report::Run& r) const {
    SourceFiles files;
    try {
      (void)load_run(r, files);
    } catch (const Error& e) {
      return e.what();
    }
    return "";
  }
  fs::path root_;
};

TEST_F(RunDir, ReadsARunInsideItsDirectory) {
  write("run/r.gif", "GIF89a-not-really-but-the-header-says-so");
  SourceFiles files;
  const LoadedRun r = load_run(run("r.gif"), files);
  EXPECT_EQ(r.video_kind, VideoKind::Gif);
  EXPECT_EQ(r.summary.status, "ok");
}

TEST_F(RunDir, AVideoLinkedOutOfTheRunDirectoryIsRefused) {
  write("private.gif", "GIF89a the author's private file");
  fs::create_symlink(root_ / "private.gif", root_ / "run/r.gif");
  const std::string error = load_error(run("r.gif"));
  EXPECT_NE(error.find("the run's video " + (root_ / "run/r.gif").string() + " resolves to '" +
                       (root_ / "private.gif").string() + "', outside the run's directory"),
            std::string::npos)
      << error;
  EXPECT_EQ(error.find("private file"), std::string::npos);
}

TEST_F(RunDir, ASummaryOrLogLinkedOutIsRefused) {
  write("other.csv", "t,secret\n0,42\n");
  fs::remove(root_ / "run/r.csv");
  fs::create_symlink(root_ / "other.csv", root_ / "run/r.csv");
  EXPECT_NE(load_error(run()).find("the run's log"), std::string::npos);
}

TEST_F(RunDir, AVideoWhoseHeaderIsNotItsKindIsRefused) {
  write("run/r.mp4", "-----BEGIN OPENSSH PRIVATE KEY-----");
  EXPECT_NE(load_error(run("r.mp4")).find("is not an MP4 (its first bytes say neither)"),
            std::string::npos);
  write("run/r.gif", std::string("\0\0\0\x20"
                                 "ftypisom",
                                 12));
  EXPECT_NE(load_error(run("r.gif")).find("is not a GIF (its first bytes say MP4)"),
            std::string::npos);
}

TEST_F(RunDir, ALogWithoutATimeColumnIsALocatedError) {
  write("run/r.csv", "x\n1\n");
  EXPECT_NE(load_error(run()).find("r.csv:1:1: error: a run log has a `t` column"),
            std::string::npos);
}

}  // namespace
}  // namespace mospec::report

namespace mospec::report {
namespace {

// A log of `rows` rows at 1 kHz with the given columns, each a sine of its
// own frequency.
plot::Table synthetic_log(const std::vector<std::string>& columns, size_t rows) {
  plot::Table t;
  t.path = "log.csv";
  t.columns = {"t"};
  t.data.emplace_back(rows);
  for (size_t r = 0; r < rows; ++r) t.data[0][r] = 0.001 * static_cast<double>(r);
  for (size_t c = 0; c < columns.size(); ++c) {
    t.columns.push_back(columns[c]);
    t.data.emplace_back(rows);
    for (size_t r = 0; r < rows; ++r)
      t.data.back()[r] = std::sin(0.001 * static_cast<double>(r * (c + 1))) * (1.0 + c);
  }
  return t;
}

Input input_with(plot::Table log, Summary summary = {}) {
  Input in;
  in.title = "t";
  LoadedRun r;
  r.name = "run";
  r.summary = std::move(summary);
  r.summary.status = "ok";
  r.summary.duration = log.data[0].empty() ? 0.0 : log.data[0].back();
  r.log = std::move(log);
  in.runs.push_back(std::move(r));
  return in;
}

// The page's chart data: the JSON after "const chartData = ".
std::string chart_data(const std::string& page) {
  const size_t at = page.find("const chartData = ");
  if (at == std::string::npos) return "";
  const size_t begin = at + std::string("const chartData = ").size();
  return page.substr(begin, page.find(";\n", begin) - begin);
}

std::vector<std::string> chart_titles(const std::string& page) {
  std::vector<std::string> out;
  static const std::regex kTitle("<h3>([^<]*) <span class=\"note\">\\[([^\\]]*)\\]");
  for (auto it = std::sregex_iterator(page.begin(), page.end(), kTitle);
       it != std::sregex_iterator(); ++it)
    out.push_back((*it)[1].str() + " [" + (*it)[2].str() + "]");
  return out;
}

TEST(Decimate, KeepsEverySeriesExtremesAndAtMostTwoRowsPerBucket) {
  const size_t rows = 30001;
  std::vector<double> a(rows), b(rows), c(rows, std::nan(""));
  for (size_t r = 0; r < rows; ++r) {
    a[r] = std::sin(0.01 * static_cast<double>(r));
    b[r] = std::cos(0.003 * static_cast<double>(r));
  }
  a[12345] = 40.0;   // a one-row spike
  a[23456] = -40.0;  // and its opposite
  b[7] = -3.0;
  const Decimation d = decimate({&a, &b, &c}, rows, 1000);
  ASSERT_EQ(d.time_row.size(), 2000u);
  ASSERT_EQ(d.row.size(), 3u);
  for (const auto& rs : d.row) ASSERT_EQ(rs.size(), d.time_row.size());
  const auto extreme = [&](const std::vector<double>& v, const std::vector<size_t>& rs, bool max) {
    double e = max ? -INFINITY : INFINITY;
    for (size_t r : rs) e = max ? std::max(e, v[r]) : std::min(e, v[r]);
    return e;
  };
  EXPECT_EQ(extreme(a, d.row[0], true), 40.0);
  EXPECT_EQ(extreme(a, d.row[0], false), -40.0);
  EXPECT_EQ(extreme(b, d.row[1], false), -3.0);
  EXPECT_EQ(extreme(b, d.row[1], true), *std::max_element(b.begin(), b.end()));
  // Drawn in time order, each value within its bucket (at most 31 rows from
  // the time it is drawn at).
  for (size_t i = 1; i < d.time_row.size(); ++i) EXPECT_LE(d.time_row[i - 1], d.time_row[i]);
  for (size_t k = 0; k < 3; ++k) {
    for (size_t i = 0; i < d.time_row.size(); ++i) {
      const size_t bucket = i / 2;
      EXPECT_GE(d.row[k][i], bucket * rows / 1000);
      EXPECT_LT(d.row[k][i], (bucket + 1) * rows / 1000);
    }
  }
  // A short log is kept whole.
  const Decimation whole = decimate({&a}, 1500, 1000);
  EXPECT_EQ(whole.time_row.size(), 1500u);
  EXPECT_EQ(whole.row[0], whole.time_row);
}

TEST(Render, OneUnitPerChartAndTheControlledFramesPositions) {
  Summary s;
  s.log.units = {{"d.value", "M"}, {"ang.value", "RAD"}, {"z.value", "M"},
                 {"d.error", "M"}, {"base.fx", "N"},     {"base.mz", "N-M"}};
  const std::string page =
      render(input_with(synthetic_log({"d.value", "ang.value", "z.value", "d.error", "base.fx",
                                       "base.mz", "right_ee_x", "right_ee_y", "right_ee_z",
                                       "ground_fx", "ground_mz", "base_x", "base_yaw"},
                                      100),
                        s),
             {"/*js*/", "/*css*/"});
  const std::vector<std::string> titles = chart_titles(page);
  const std::vector<std::string> expected = {
      "Constraint values [m]",
      "Constraint values [rad]",
      "Constraint errors [m]",
      "Platform twist and wrench [N]",
      "Platform twist and wrench [N·m]",
      "Controlled frames&#39; positions in W (simulator) [m]",
      "Contact and ground forces (simulator) [N]",
      "Contact and ground forces (simulator) [N·m]",
      "Base pose (simulator) [m]",
      "Base pose (simulator) [rad]",
  };
  EXPECT_EQ(titles, expected);
  EXPECT_NE(page.find(R"("labels":["t","d.value","z.value"])"), std::string::npos);
  EXPECT_NE(page.find(R"("labels":["t","right_ee_x","right_ee_y","right_ee_z"])"),
            std::string::npos);
  // Every chart has its legend, always shown.
  EXPECT_EQ(count(page, "class=\"legend\""), titles.size());
  EXPECT_NE(page.find("legend: \"always\""), std::string::npos);
}

TEST(Render, ThresholdsAreBandsFromTheLogOrTheModel) {
  Summary s;
  s.log.units = {{"tube.value", "M"}, {"set.value", "M"}, {"lim.value", "M"}};
  s.log.constraints["set"] = {"equality", 1.0, std::nullopt, std::nullopt, 0.25};
  s.log.constraints["lim"] = {"less-than", std::nullopt, std::nullopt, 0.5, 0.0};
  const std::string page = render(
      input_with(
          synthetic_log({"tube.value", "tube.lower", "tube.upper", "set.value", "lim.value"}, 50),
          s),
      {"/*js*/", "/*css*/"});
  // The tube's logged thresholds are hidden series of its chart, drawn as its band.
  EXPECT_NE(
      page.find(
          R"("labels":["t","tube.value","set.value","lim.value","tube.lower","tube.upper"],"visible":[true,true,true,false,false])"),
      std::string::npos)
      << page;
  EXPECT_NE(page.find(R"({"s":0,"lo":null,"hi":null,"loS":3,"hiS":4})"), std::string::npos);
  // The setpoint ± its tolerance; the limit up to its threshold.
  EXPECT_NE(page.find(R"({"s":1,"lo":0.75,"hi":1.25,"loS":null,"hiS":null})"), std::string::npos);
  EXPECT_NE(page.find(R"({"s":2,"lo":null,"hi":0.5,"loS":null,"hiS":null})"), std::string::npos);
}

TEST(Render, MotionsInTheOrderTheyStart) {
  Summary s;
  s.motions.push_back({"second", 2.0, 3.0, "until"});
  s.motions.push_back({"never", std::nullopt, std::nullopt, "never-started"});
  s.motions.push_back({"first", 0.0, 2.0, "until"});
  plot::Table log = synthetic_log({"never.running", "second.running", "first.running"}, 4);
  log.data[1] = {0, 0, 0, 0};
  log.data[2] = {0, 0, 1, 1};
  log.data[3] = {1, 1, 0, 0};
  const std::string page = render(input_with(std::move(log), s), {"/*js*/", "/*css*/"});
  const size_t first = page.find("<tr><td>first</td>"), second = page.find("<tr><td>second</td>"),
               never = page.find("<tr><td>never</td>");
  ASSERT_NE(first, std::string::npos);
  EXPECT_LT(first, second);
  EXPECT_LT(second, never);
  EXPECT_NE(page.find(R"("labels":["t","first.running","second.running","never.running"])"),
            std::string::npos);
}

TEST(Render, ALongRunsDataStaysUnderOneMegabyte) {
  // 30 s at 1 kHz, 160 columns: two 7-joint arms' q, qd, tau, the world's
  // columns and a hundred of the controller's.
  std::vector<std::string> columns;
  for (const char* arm : {"right_", "left_"}) {
    for (const char* f : {"q", "qd", "tau"}) {
      for (int j = 0; j < 7; ++j) {
        std::string name = arm;
        name.append(f).append(1, static_cast<char>('0' + j));
        columns.push_back(std::move(name));
      }
    }
  }
  for (int c = 0; c < 100; ++c)
    columns.push_back(std::string("c").append(std::to_string(c)).append(".value"));
  for (int c = 0; c < 18; ++c) columns.push_back(std::string("ground_f").append(std::to_string(c)));
  const plot::Table log = synthetic_log(columns, 30001);
  const std::string page = render(input_with(log), {"/*js*/", "/*css*/"});
  const std::string data = chart_data(page);
  ASSERT_FALSE(data.empty());
  EXPECT_LE(data.size(), 1000u * 1000u);
  EXPECT_GT(data.size(), 100u * 1000u);  // still hundreds of points per series
  EXPECT_NE(page.find("30001 logged rows drawn as each series' minimum and maximum over"),
            std::string::npos);
}

}  // namespace
}  // namespace mospec::report
