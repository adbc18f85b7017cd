// The figure logic behind `mospec plot`: the log parser's located errors, which
// columns each figure picks, and the trials' statistics (checked by hand).
#include <gtest/gtest.h>

#include <cmath>
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
            "run.csv:1: error: the file is empty (expected a header line of column names)");
  EXPECT_EQ(error_of("t,,x\n"), "run.csv:1:3: error: column 2 has an empty name");
  EXPECT_EQ(error_of("t,x,t\n"), "run.csv:1:5: error: column name 't' appears twice");
  EXPECT_EQ(error_of("t,x\n0,1\n1\n"),
            "run.csv:3: error: expected 2 fields (as in the header), got 1");
  EXPECT_EQ(error_of("t,x\n0,1\n1,1O\n"), "run.csv:3:3: error: column 'x': '1O' is not a number");
  EXPECT_EQ(error_of("t,x\n0,1\n\n1,2\n"), "run.csv:3: error: empty line between rows");
}

TEST(PlotCsv, MissingColumnListsTheAvailableOnes) {
  const Table t = parse_csv("t,a\n0,1\n", "run.csv");
  try {
    t.require("b", "--force");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "run.csv: error: no column 'b' (--force); the columns are: t, a");
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
        "trial-3.csv:3: error: t = 1.5 differs from trial-0.csv's t = 1: the trials must share "
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

TEST(PlotFormat, ByExtension) {
  EXPECT_EQ(format_of("a/b.SVG"), Format::Svg);
  EXPECT_EQ(format_of("b.png"), Format::Png);
  EXPECT_THROW(format_of("b.pdf"), Error);
  EXPECT_THROW(format_of("a.svg/b"), Error);
}

}  // namespace
}  // namespace mospec::plot
