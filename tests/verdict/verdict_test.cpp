// A run's verdict (src/verdict), judged from a hand-built plan and what a run
// recorded, without a simulation: a motion's goal met or not when it ends, a
// run cut short of the motion's end, a clamp, and the degraded solves read
// from the log's `.degraded` columns.
#include "verdict/verdict.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <utility>

namespace mospec::verdict {
namespace {

// One motion with one equality goal; controller log columns: 0 the motion's
// running flag, 1 its `.ended` event, 2 the goal's satisfied flag, 3 the
// quantity's value, 4 its error.
VerdictPlan one_goal_plan() {
  VerdictPlan plan;
  VerdictPlan::Motion m;
  m.iri = "https://ex.org/motion-reach";
  m.name = "motion-reach";
  m.running = 0;
  m.ended = 1;
  VerdictPlan::Goal g;
  g.constraint = "https://ex.org/cstr-height";
  g.name = "cstr-height";
  g.relation = "equality";
  g.unit = "M";
  g.spec.reference = 0.7;
  g.spec.tolerance = 0.001;
  g.tolerance_source = "stated";
  g.satisfied = 2;
  g.value = 3;
  g.error = 4;
  m.goals.push_back(g);
  plan.motions.push_back(m);
  return plan;
}

// A run of 100 ticks in which the motion runs from tick 0 and, when
// `ended`, ends at tick 50 (an `until` held) with the goal at `value`.
sim::RunResult run(bool ended, double value) {
  sim::RunResult r;
  r.ticks = 100;
  r.columns = {"t",      "motion-reach.running", "motion-reach.ended", "cstr-height.satisfied",
               "height", "cstr-height.error"};
  const double error = 0.7 - value;
  const double satisfied = std::abs(error) <= 0.001 ? 1.0 : 0.0;
  r.changes.push_back({.tick = 0, .time = 0.0, .column = 1, .value = 1.0});
  if (ended) {
    r.events.push_back({.tick = 50, .time = 0.05, .column = 2, .code = 1});
    r.snapshots.push_back(
        {.taken = true, .tick = 50, .time = 0.05, .values = {satisfied, value, error}});
  } else {
    r.snapshots.push_back({});
  }
  r.last_row = {0.1, ended ? 0.0 : 1.0, 0.0, satisfied, value, error};
  r.held.push_back({});
  return r;
}

TEST(Verdict, AGoalMetWhenItsMotionEndsIsOk) {
  const VerdictPlan plan = one_goal_plan();
  const Verdict v = judge(plan, run(true, 0.7004));
  EXPECT_FALSE(v.failed) << v.text;
  EXPECT_EQ(v.text.rfind("mospec: verdict: ok\n", 0), 0u) << v.text;
  EXPECT_NE(v.text.find("goals of motion-reach when it ended (tick 50): 1 of 1 met"),
            std::string::npos)
      << v.text;
  EXPECT_EQ(v.json["status"], "ok");
  EXPECT_EQ(v.json["exit_status"], 0);
}

TEST(Verdict, AGoalNotMetWhenItsMotionEndsFails) {
  const VerdictPlan plan = one_goal_plan();
  const Verdict v = judge(plan, run(true, 0.69));
  EXPECT_TRUE(v.failed);
  ASSERT_EQ(v.why.size(), 1u) << v.text;
  EXPECT_EQ(v.why[0], "the motion 'motion-reach' did not meet 1 of its goals: cstr-height");
  EXPECT_NE(v.text.find("NOT MET: cstr-height = 0.69 M (wants = 0.7, error 0.01; tolerance "
                        "0.001 M, stated)"),
            std::string::npos)
      << v.text;
  EXPECT_EQ(v.json["exit_status"], 1);
}

TEST(Verdict, ARunCutShortOfTheMotionsEndIsOkSoFar) {
  const VerdictPlan plan = one_goal_plan();
  const Verdict v = judge(plan, run(false, 0.69));
  EXPECT_FALSE(v.failed) << v.text;
  EXPECT_EQ(v.text.rfind("mospec: verdict: ok so far: 1 goal(s) not met yet, as motion-reach "
                         "was still running when the run ended (run longer to judge them)\n",
                         0),
            0u)
      << v.text;
  EXPECT_EQ(v.json["goals_not_met_yet"], 1);
}

TEST(Verdict, AClampFailsTheRun) {
  const VerdictPlan plan = one_goal_plan();
  sim::RunResult r = run(true, 0.7);
  r.clamped = true;
  robot::ClampRecord clamp;
  clamp.ticks = 3;
  clamp.first_tick = 7;
  r.clamps.push_back(clamp);
  const Verdict v = judge(plan, r);
  EXPECT_TRUE(v.failed);
  EXPECT_NE(v.text.find("a limit was breached: commands clamped from tick 7"), std::string::npos)
      << v.text;
}

TEST(Verdict, DegradedSolvesAreReadFromTheirLogColumns) {
  sim::RunResult r;
  r.columns = {"t", "right_arm.degraded", "height", "left_arm.degraded"};
  r.flag_ticks = {4, 0, 0};
  const auto d = degraded_solves(r);
  ASSERT_EQ(d.size(), 2u);
  EXPECT_EQ(d[0], (std::pair<std::string, std::uint64_t>{"right_arm", 4}));
  EXPECT_EQ(d[1], (std::pair<std::string, std::uint64_t>{"left_arm", 0}));
}

TEST(Verdict, ConsoleNumbersHaveFourSignificantDigits) {
  EXPECT_EQ(console_number(0.012345678), "0.01235");
  EXPECT_EQ(console_number(-1234567.0), "-1.235e+06");
}

}  // namespace
}  // namespace mospec::verdict
