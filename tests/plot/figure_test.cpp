// The figure logic behind `mospec plot`: the log parser's located errors, which
// columns each figure picks, and the trials' statistics (checked by hand).
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>

#include "plot/csv.hpp"
#include "plot/figure.hpp"
#include "support/diagnostics.hpp"

namespace mospec::plot {
namespace {

std::string error_of(std::string_view text) {
  try {
    parse_csv(text, "run.csv");
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(PlotCsv, ReadsColumnsNonFiniteValuesAndLineEnds) {
  const Table t = parse_csv("t,a, b\r\n0,1,nan\r\n0.5,-2e-3,inf\n1,3,-inf\n\n", "run.csv");
  ASSERT_EQ(t.columns, (std::vector<std::string>{"t", "a", "b"}));
  ASSERT_EQ(t.rows(), 3u);
  EXPECT_EQ(t.data[1][1], -2e-3);
  EXPECT_TRUE(std::isnan(t.data[2][0]));
  EXPECT_EQ(t.data[2][1], std::numeric_limits<double>::infinity());
  EXPECT_EQ(t.data[2][2], -std::numeric_limits<double>::infinity());
  EXPECT_EQ(t.find("b"), 2u);
  EXPECT_FALSE(t.find("c"));
}

TEST(PlotCsv, ErrorsAreLocated) {
  EXPECT_EQ(error_of(""),
            "run.csv:1:1: error: the file is empty (expected a header line of column names)");
  EXPECT_EQ(error_of("t,,x\n"), "run.csv:1:3: error: column 2 has an empty name");
  EXPECT_EQ(error_of("t,x,t\n"), "run.csv:1:5: error: column name 't' appears twice");
  EXPECT_EQ(error_of("t,x\n0,1\n1\n"),
            "run.csv:3:2: error: expected 2 fields (as in the header), got 1");
  EXPECT_EQ(error_of("t,x\n0,1\n1,2,3\n"),
            "run.csv:3:5: error: expected 2 fields (as in the header), got 3");
  EXPECT_EQ(error_of("t,x\n0,1\n1,1O\n"), "run.csv:3:3: error: column 'x': '1O' is not a number");
  EXPECT_EQ(error_of("t,x\n0,1\n\n1,2\n"), "run.csv:3:1: error: empty line between rows");
}

TEST(PlotCsv, AnEmptyLineBetweenRowsIsACsvError) {
  try {
    parse_csv("t,a\n0,1\n\n0.5,2\n", "run.csv");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), "csv");
    EXPECT_STREQ(e.what(), "run.csv:3:1: error: empty line between rows");
  }
}

TEST(PlotCsv, MissingColumnListsTheAvailableOnes) {
  const Table t = parse_csv("t,a\n0,1\n", "run.csv");
  try {
    t.require("b", "--force");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), "missing-column");
    EXPECT_STREQ(e.what(), "run.csv:1:1: error: no column 'b' (--force); the columns are: t, a");
  }
}

const char* const kDistances =
    "t,cstr-dist-leftarm-shoulder-ee.value,cstr-dist-leftarm-shoulder-ee.lower,"
    "cstr-dist-leftarm-shoulder-ee.upper,cstr-dist-rightarm-shoulder-ee.value,"
    "cstr-dist-rightarm-shoulder-ee.lower,cstr-dist-rightarm-shoulder-ee.upper,"
    "ctrl-dist-leftarm-shoulder-ee.output,ctrl-dist-rightarm-shoulder-ee.output";

std::vector<std::string> labels(const Panel& p) {
  std::vector<std::string> out;
  for (const Curve& c : p.curves) out.push_back(c.titled ? c.label : "-");
  return out;
}

TEST(PlotFigure, OneRunWithAPlatformWrenchShowsIt) {
  std::string text = kDistances;
  text.append(
      ",base-force-distribution.fx,base-force-distribution.fy,base-force-distribution.mz\n");
  text.append(
      "0,0.6,0.68,0.72,0.8,0.68,0.72,1,2,3,4,5\n0.1,0.61,0.68,0.72,0.79,0.68,0.72,1,2,3,4,5\n");
  const Figure f = run_figure(parse_csv(text, "sc1.csv"), {}, "SC1");
  ASSERT_EQ(f.panels.size(), 2u);
  // The arms share their thresholds: one titled d_thr pair.
  EXPECT_EQ(labels(f.panels[0]), (std::vector<std::string>{"d_r", "d_l", "d_{thr}", "-"}));
  EXPECT_EQ(f.panels[0].curves[0].y, (std::vector<double>{0.8, 0.79}));
  EXPECT_TRUE(f.panels[0].curves[2].dashed);
  EXPECT_EQ(labels(f.panels[1]), (std::vector<std::string>{"F_{⊥}", "F_{∥}", "τ"}));
  EXPECT_TRUE(f.panels[1].curves[2].right_axis);
  EXPECT_EQ(f.panels[1].y2label, "torque [N·m]");
  EXPECT_EQ(f.t, (std::vector<double>{0, 0.1}));
}

TEST(PlotFigure, WithoutAPlatformWrenchTheDistanceControllersOutputs) {
  std::string text = kDistances;
  text.append("\n0,0.6,0.68,0.72,0.8,0.66,0.74,1,2\n");
  const Figure f = run_figure(parse_csv(text, "sc2.csv"), {}, "SC2");
  // Different thresholds per arm: each drawn, the lower one titled.
  EXPECT_EQ(labels(f.panels[0]),
            (std::vector<std::string>{"d_r", "d_l", "d_{thr,r}", "-", "d_{thr,l}", "-"}));
  EXPECT_EQ(labels(f.panels[1]), (std::vector<std::string>{"F_{⊥,r}", "F_{⊥,l}"}));
  EXPECT_TRUE(f.panels[1].y2label.empty());
}

// Column names are matched with plain string tests: a regex engine that
// recursed per character overflowed the stack on a 100k-character name.
TEST(PlotFigure, HugeColumnNamesAreMatchedWithoutRecursion) {
  const std::string huge(100000, 'x');
  std::string text = kDistances;
  text += ",ctrl-dist-rightarm-" + huge + "-shoulder-ee.output";
  text += ",ctrl-dist-leftarm-" + huge + "-shoulder-ee.outputs";
  text.append("\n0,0.6,0.68,0.72,0.8,0.66,0.74,1,2,3,4\n");
  const Figure f = run_figure(parse_csv(text, "long.csv"), {}, "long");
  ASSERT_EQ(f.panels.size(), 2u);
  EXPECT_EQ(labels(f.panels[1]), (std::vector<std::string>{"F_{⊥,r}", "F_{⊥,r}", "F_{⊥,l}"}));
}

TEST(PlotFigure, TrialsAreMeanAndSampleStandardDeviation) {
  std::vector<Table> trials;
  for (int k = 0; k < 3; ++k) {
    std::string text = kDistances;
    // d_r = 0.7 + 0.01 k, F_perp,l = 10 k at both times.
    text.append("\n0,0.6,0.68,0.72,").append(std::to_string(0.7 + 0.01 * k)).append(",0.68,0.72,");
    text.append(std::to_string(10 * k)).append(",0\n1,0.6,0.68,0.72,0.7,0.68,0.72,");
    text.append(std::to_string(10 * k)).append(",0\n");
    trials.push_back(
        parse_csv(text, std::string("trial-").append(std::to_string(k)).append(".csv")));
  }
  const Figure f = trials_figure(trials, {}, "SC2");
  const Curve& d_r = f.panels[0].curves[0];
  ASSERT_EQ(d_r.label, "d_r");
  EXPECT_NEAR(d_r.y[0], 0.71, 1e-12);
  EXPECT_NEAR(d_r.sd[0], 0.01, 1e-12);  // sample (n - 1) standard deviation of 0.70, 0.71, 0.72
  EXPECT_NEAR(d_r.sd[1], 0.0, 1e-12);
  EXPECT_TRUE(f.panels[0].curves[2].sd.empty());  // thresholds: no band
  const Curve& f_l = f.panels[1].curves[1];
  ASSERT_EQ(f_l.label, "F_{⊥,l}");
  EXPECT_NEAR(f_l.y[1], 10.0, 1e-12);
  EXPECT_NEAR(f_l.sd[1], 10.0, 1e-12);

  // Another time base is refused at its first differing row.
  std::string skewed = kDistances;
  skewed.append("\n0,0.6,0.68,0.72,0.7,0.68,0.72,0,0\n1.5,0.6,0.68,0.72,0.7,0.68,0.72,0,0\n");
  trials.push_back(parse_csv(skewed, "trial-3.csv"));
  try {
    trials_figure(trials, {}, "SC2");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_STREQ(
        e.what(),
        "trial-3.csv:3:1: error: t = 1.5 differs from trial-0.csv's t = 1: the trials must share "
        "their time base");
  }
}

TEST(PlotScript, QuotesTitlesAndKeepsColumnNamesVerbatim) {
  std::string text = kDistances;
  text.append("\n0,0.6,0.68,0.72,0.8,0.68,0.72,1,2\n");
  Selection chosen;
  chosen.forces = {"ctrl-dist-leftarm-shoulder-ee.output", "t"};
  const Figure f = run_figure(parse_csv(text, "sc2.csv"), chosen, "it's\nhere");
  const std::string s = gnuplot_script(f, Format::Png, ".out.png");
  EXPECT_NE(s.find("title 'it''s here' font ',15' noenhanced"), std::string::npos) << s;
  EXPECT_NE(s.find("title 't' noenhanced"), std::string::npos) << s;
  EXPECT_NE(s.find("set output '.out.png'"), std::string::npos) << s;
  EXPECT_NE(s.find("pngcairo"), std::string::npos) << s;
}

// A log of `rows` rows at 0.1 s with the distances and controller outputs as
// given per row by `row(r)` (the text after "t,").
std::string log_of(int rows, const std::string& extra_header,
                   const std::function<std::string(int)>& row) {
  std::string text = kDistances;
  text.append(extra_header).append("\n");
  for (int r = 0; r < rows; ++r) {
    text.append(std::to_string(0.1 * r)).append(",").append(row(r)).append("\n");
  }
  return text;
}

// Issue #17: a threshold far outside the data is not drawn (it would sit on
// the frame or squash the curves); the others widen the range and lie inside.
TEST(PlotRange, ThresholdsAreInsideTheFrameOrNotDrawn) {
  // SC2's shape: d rises from 0.58 to 0.714; the thresholds 0.68 and 0.72.
  const std::string shared = log_of(40, "", [](int r) {
    const std::string d = std::to_string(0.714 - 0.134 * std::exp(-r / 5.0));
    return d + ",0.68,0.72," + d + ",0.68,0.72,1,2";
  });
  const Figure f = run_figure(parse_csv(shared, "sc2.csv"), {}, "SC2");
  ASSERT_EQ(labels(f.panels[0]), (std::vector<std::string>{"d_r", "d_l", "d_{thr}", "-"}));
  EXPECT_GT(f.panels[0].y.hi, 0.72);  // strictly: the threshold is not on the frame
  EXPECT_LT(f.panels[0].y.lo, 0.58);
  EXPECT_TRUE(f.panels[0].y.clipped.empty());

  // An upper bound of 50 m next to distances of 0.7 m: not drawn.
  const std::string far = log_of(40, "", [](int r) {
    const std::string d = std::to_string(0.70 + 0.001 * r);
    return d + ",0.68,50," + d + ",0.68,50,1,2";
  });
  const Figure g = run_figure(parse_csv(far, "far.csv"), {}, "far");
  ASSERT_EQ(labels(g.panels[0]), (std::vector<std::string>{"d_r", "d_l", "d_{thr}"}));
  EXPECT_EQ(g.panels[0].curves[2].y.front(), 0.68);
  EXPECT_LT(g.panels[0].y.hi, 1.0);
  EXPECT_LT(g.panels[0].y.lo, 0.68);
  const std::string script = gnuplot_script(g, Format::Svg, "far.svg");
  EXPECT_EQ(script.find(" 50 "), std::string::npos) << "the 50 m bound is not in the data block";
}

// Issue #17: the axis labels name the plotted columns and their unit.
TEST(PlotLabels, FollowThePlottedColumns) {
  const std::string text = log_of(
      3, ",base_x,right_fx,right_tau3,base-force-distribution.mz",
      [](int r) { return "0.6,0.68,0.72,0.8,0.68,0.72,1,2," + std::to_string(r) + ",3,4,5"; });
  const Table t = parse_csv(text, "run.csv");
  Selection chosen;
  chosen.distances = {"base_x"};
  chosen.forces = {"right_fx"};
  Figure f = run_figure(t, chosen, "run");
  EXPECT_EQ(f.panels[0].ylabel, "base_x [m]");
  EXPECT_EQ(f.panels[1].ylabel, "right_fx [N]");
  EXPECT_EQ(f.panels[1].y2label, "");
  chosen.forces = {"right_fx", "right_tau3", "base-force-distribution.mz"};
  f = run_figure(t, chosen, "run");
  EXPECT_EQ(f.panels[1].ylabel, "right_fx, right_tau3");  // two units: none claimed
  EXPECT_EQ(f.panels[1].y2label, "base-force-distribution.mz [N·m]");
  const std::string script = gnuplot_script(f, Format::Svg, "run.svg");
  EXPECT_NE(script.find("set ylabel 'base_x [m]' noenhanced"), std::string::npos) << script;
  EXPECT_NE(script.find("set y2label 'base-force-distribution.mz [N·m]' noenhanced"),
            std::string::npos);
  // The defaults keep the paper's quantities.
  EXPECT_EQ(run_figure(t, {}, "run").panels[0].ylabel, "shoulder-contact distance [m]");
}

TEST(PlotLabels, UnitsFromColumnNames) {
  EXPECT_EQ(unit_of("right_q0"), "rad");
  EXPECT_EQ(unit_of("left_qd6"), "rad/s");
  EXPECT_EQ(unit_of("left_tau2"), "N·m");
  EXPECT_EQ(unit_of("right_ee_z"), "m");
  EXPECT_EQ(unit_of("left_fn"), "N");
  EXPECT_EQ(unit_of("ground_mz"), "N·m");
  EXPECT_EQ(unit_of("base_yaw"), "rad");
  EXPECT_EQ(unit_of("tau_ratio"), "1");
  EXPECT_EQ(unit_of("cstr-dist-rightarm-shoulder-ee.error"), "m");
  EXPECT_EQ(unit_of("ctrl-dist-leftarm-shoulder-ee.output"), "N");
  EXPECT_EQ(unit_of("right_qx"), "");
  EXPECT_EQ(unit_of("mon-x.event"), "");
}

// Issue #17: a start-up spike does not set the scale, and the figure says so.
TEST(PlotRange, AStartUpSpikeIsClippedAndSaid) {
  // Forces about 0..10 N, but -1000 N in the first row.
  const std::string text = log_of(100, "", [](int r) {
    const double f = r == 0 ? -1000.0 : 10.0 * std::exp(-r / 20.0);
    return "0.7,0.68,0.72,0.7,0.68,0.72," + std::to_string(f) + "," + std::to_string(f);
  });
  const Figure f = run_figure(parse_csv(text, "spike.csv"), {}, "spike");
  EXPECT_EQ(f.panels[1].y.clipped, "down to -1000 N");
  EXPECT_GT(f.panels[1].y.lo, -100.0);
  EXPECT_TRUE(f.panels[0].y.clipped.empty());
  const std::string script = gnuplot_script(f, Format::Svg, "spike.svg");
  EXPECT_NE(script.find("set title 'clipped: start-up spike down to -1000 N'"), std::string::npos)
      << script;
  // The same excursion late in the run is data, not a start-up spike.
  const std::string late = log_of(100, "", [](int r) {
    const double f = r == 80 ? -1000.0 : 10.0 * std::exp(-r / 20.0);
    return "0.7,0.68,0.72,0.7,0.68,0.72," + std::to_string(f) + "," + std::to_string(f);
  });
  const Figure g = run_figure(parse_csv(late, "late.csv"), {}, "late");
  EXPECT_TRUE(g.panels[1].y.clipped.empty());
  EXPECT_LT(g.panels[1].y.lo, -1000.0);
}

// Issue #17: motion starts and ends and events are marked, labelled.
TEST(PlotMarkers, MotionStartsEndsAndEvents) {
  const std::string text =
      log_of(5, ",motion-a.running,motion-a.ended,mon-x.event,mon-x.flag", [](int r) {
        const char* running = r >= 1 && r <= 3 ? "1" : "0";
        const char* ended = r == 3 ? "1" : "0";
        const char* event = r == 3 ? "2" : r == 4 ? "1" : "0";
        return std::string("0.7,0.68,0.72,0.7,0.68,0.72,1,2,") + running + "," + ended + "," +
               event + ",1";
      });
  const Figure f = run_figure(parse_csv(text, "m.csv"), {}, "m");
  ASSERT_EQ(f.markers.size(), 3u);
  EXPECT_NEAR(f.markers[0].t, 0.1, 1e-12);
  EXPECT_EQ(f.markers[0].label, "motion-a starts");
  EXPECT_NEAR(f.markers[1].t, 0.3, 1e-12);
  EXPECT_EQ(f.markers[1].label, "motion-a ends (until), mon-x falling");
  EXPECT_EQ(f.markers[2].label, "mon-x rising");
  const std::string script = gnuplot_script(f, Format::Svg, "m.svg");
  EXPECT_NE(script.find("set arrow from first 0.1, graph 0 to first 0.1, graph 1 nohead"),
            std::string::npos)
      << script;
  EXPECT_NE(script.find("set label 'motion-a ends (until), mon-x falling' at first 0.3, graph"),
            std::string::npos)
      << script;

  // More than kMaxMarkers: the rest are counted and said.
  const std::string many = log_of(40, ",mon-y.event", [](int r) {
    return std::string("0.7,0.68,0.72,0.7,0.68,0.72,1,2,") + (r % 2 ? "1" : "0");
  });
  const Figure g = run_figure(parse_csv(many, "many.csv"), {}, "many");
  EXPECT_EQ(g.markers.size(), kMaxMarkers);
  EXPECT_EQ(g.markers_dropped, 20u - kMaxMarkers);
  EXPECT_NE(gnuplot_script(g, Format::Svg, "x.svg").find("+4 later markers not drawn"),
            std::string::npos);
}

TEST(PlotFormat, ByExtension) {
  EXPECT_EQ(format_of("a/b.SVG"), Format::Svg);
  EXPECT_EQ(format_of("b.png"), Format::Png);
  EXPECT_THROW(format_of("b.pdf"), Error);
  EXPECT_THROW(format_of("a.svg/b"), Error);
}

}  // namespace
}  // namespace mospec::plot
