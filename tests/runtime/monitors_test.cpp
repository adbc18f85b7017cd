// Monitors on sequences: level flags, edge events, hysteresis, NaN, setup checks.
#include "runtime/monitors.hpp"

#include <gtest/gtest.h>

#include <array>
#include <limits>
#include <vector>

#include "runtime/steps.hpp"
#include "support/diagnostics.hpp"

namespace mospec::runtime {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::vector<bool> levels(const LevelMonitor& m, const std::vector<double>& values) {
  MonitorState s;
  std::vector<bool> out;
  for (double v : values) out.push_back(m.update(s, v));
  return out;
}

std::vector<Event> events(const EdgeMonitor& m, const std::vector<double>& values,
                          MonitorState s = {}) {
  std::vector<Event> out;
  for (double v : values) out.push_back(m.update(s, v));
  return out;
}

constexpr Event N = Event::None, R = Event::Rising, F = Event::Falling;

TEST(LevelMonitor, FlagFollowsAPlainThreshold) {
  const LevelMonitor below({.sense = Sense::Below, .enter = 1.0, .leave = 1.0});
  EXPECT_EQ(levels(below, {3, 2, 1, 0.5, 1.0000001, 0}),
            (std::vector<bool>{false, false, true, true, false, true}));
  const LevelMonitor above({.sense = Sense::Above, .enter = 10.0, .leave = 10.0});
  EXPECT_EQ(levels(above, {0, 9.99, 10, 11, 9}),
            (std::vector<bool>{false, false, true, true, false}));
}

TEST(LevelMonitor, HysteresisKeepsTheFlagBetweenThresholds) {
  // Satisfied below 0.01, and stays so until above 0.02.
  const LevelMonitor m({.sense = Sense::Below, .enter = 0.01, .leave = 0.02});
  EXPECT_EQ(levels(m, {0.05, 0.015, 0.01, 0.015, 0.019, 0.02, 0.021, 0.015, 0.009}),
            (std::vector<bool>{false, false, true, true, true, true, false, false, true}));
  const LevelMonitor a({.sense = Sense::Above, .enter = 5.0, .leave = 4.0});
  EXPECT_EQ(levels(a, {4.5, 5.0, 4.5, 4.0, 3.99, 4.5}),
            (std::vector<bool>{false, true, true, true, false, false}));
}

TEST(LevelMonitor, NoisySignalChattersWithoutHysteresisOnly) {
  std::vector<double> noisy;
  for (int k = 0; k < 100; ++k) noisy.push_back(1.0 + ((k % 2) != 0 ? 0.004 : -0.004));
  auto toggles = [](const std::vector<bool>& l) {
    int n = 0;
    for (size_t k = 1; k < l.size(); ++k) n += l[k] != l[k - 1];
    return n;
  };
  EXPECT_EQ(toggles(levels(LevelMonitor({.enter = 1.0, .leave = 1.0}), noisy)), 99);
  EXPECT_EQ(toggles(levels(LevelMonitor({.enter = 1.0, .leave = 1.01}), noisy)), 0);
}

TEST(LevelMonitor, NanLowersTheFlagAndRaisesFault) {
  const LevelMonitor m({.enter = 1.0, .leave = 2.0});
  MonitorState s;
  EXPECT_TRUE(m.update(s, 0.0));
  EXPECT_FALSE(m.update(s, kNaN));
  EXPECT_TRUE(s.fault);
  EXPECT_FALSE(m.update(s, 1.5));  // re-entering needs the enter threshold
  EXPECT_FALSE(s.fault);
  EXPECT_TRUE(m.update(s, 0.5));
}

TEST(LevelMonitor, FollowsABoolean) {
  MonitorState s;
  EXPECT_TRUE(LevelMonitor::update(s, true));
  EXPECT_FALSE(LevelMonitor::update(s, false));
}

TEST(EdgeMonitor, EventsOnTheConfiguredEdges) {
  const MonitorThresholds t{.sense = Sense::Below, .enter = 1.0, .leave = 1.0};
  const std::vector<double> seq{2, 0, 0, 2, 2, 0, 2};
  EXPECT_EQ(events(EdgeMonitor(t, Edges::Both), seq), (std::vector<Event>{N, R, N, F, N, R, F}));
  EXPECT_EQ(events(EdgeMonitor(t, Edges::Rising), seq), (std::vector<Event>{N, R, N, N, N, R, N}));
  EXPECT_EQ(events(EdgeMonitor(t, Edges::Falling), seq), (std::vector<Event>{N, N, N, F, N, N, F}));
}

TEST(EdgeMonitor, InitialLevelDecidesTheFirstEdge) {
  const EdgeMonitor m({.enter = 1.0, .leave = 1.0}, Edges::Both);
  // Satisfied from the first sample: a rising event when starting unsatisfied,
  // none when starting satisfied.
  EXPECT_EQ(events(m, {0, 0}), (std::vector<Event>{R, N}));
  EXPECT_EQ(events(m, {0, 0}, MonitorState{.satisfied = true}), (std::vector<Event>{N, N}));
  EXPECT_EQ(events(m, {5}, MonitorState{.satisfied = true}), (std::vector<Event>{F}));
}

TEST(EdgeMonitor, HysteresisGivesOneEventPerCrossing) {
  // A distance entering a tube and leaving it, with noise around the threshold.
  const EdgeMonitor m({.sense = Sense::Below, .enter = 0.10, .leave = 0.12}, Edges::Both);
  EXPECT_EQ(events(m, {0.2, 0.101, 0.099, 0.101, 0.099, 0.11, 0.119, 0.121, 0.119, 0.121}),
            (std::vector<Event>{N, N, R, N, N, N, N, F, N, N}));
}

TEST(EdgeMonitor, NanIsAFallingEdgeWhenSatisfied) {
  const EdgeMonitor m({.enter = 1.0, .leave = 1.0}, Edges::Both);
  EXPECT_EQ(events(m, {0, kNaN, kNaN, 0}), (std::vector<Event>{R, F, N, R}));
}

TEST(EdgeMonitor, FollowsABoolean) {
  const EdgeMonitor m({}, Edges::Rising);
  MonitorState s;
  EXPECT_EQ(m.update(s, true), R);
  EXPECT_EQ(m.update(s, true), N);
  EXPECT_EQ(m.update(s, false), N);
  EXPECT_EQ(m.update(s, true), R);
}

TEST(Monitors, SetupChecks) {
  auto message = [](const MonitorThresholds& t) {
    try {
      LevelMonitor m(t, "mon-contact");
    } catch (const Error& e) {
      EXPECT_EQ(e.code(), "invalid-monitor");
      return e.diagnostic().message;
    }
    return std::string("(no error)");
  };
  EXPECT_EQ(message({.sense = Sense::Below, .enter = 2, .leave = 1}),
            "mon-contact: a monitor satisfied below its threshold needs enter <= leave for "
            "hysteresis, got enter 2 and leave 1");
  EXPECT_EQ(message({.sense = Sense::Above, .enter = 1, .leave = 2}),
            "mon-contact: a monitor satisfied above its threshold needs enter >= leave for "
            "hysteresis, got enter 1 and leave 2");
  EXPECT_EQ(message({.enter = kNaN, .leave = 1}),
            "mon-contact: thresholds must not be NaN (enter nan, leave 1)");
  EXPECT_EQ(message({.enter = 1, .leave = 1}), "(no error)");
}

// The IR's kernels (steps.hpp): an edge monitor's event codes on an error
// signal, within a tolerance, for each configuration of edges.
TEST(EdgeMonitorStep, ReportsItsEdgesAsCodes) {
  const std::vector<double> errors = {0.5, 0.009, -0.01, 0.02, 0.0, 0.3};
  //                       satisfied:  no   yes    yes    no    yes  no
  const auto codes = [&](Edges edges) {
    MonitorState s;
    std::vector<int> out;
    for (double e : errors) out.push_back(steps::edge_monitor(s, e, 0.01, edges, true));
    return out;
  };
  EXPECT_EQ(codes(Edges::Rising), (std::vector<int>{0, 1, 0, 0, 1, 0}));
  EXPECT_EQ(codes(Edges::Falling), (std::vector<int>{0, 0, 0, 2, 0, 2}));
  EXPECT_EQ(codes(Edges::Both), (std::vector<int>{0, 1, 0, 2, 1, 2}));
  // Satisfied at the first sample: a rising edge (never a falling one).
  MonitorState s;
  EXPECT_EQ(steps::edge_monitor(s, 0.0, 0.0, Edges::Both, true), 1);
  // Listed by a handler: it reports while the motion runs and in the tick it
  // ends (a falling edge there is seen), then no more.
  MonitorState g;
  EXPECT_EQ(steps::edge_monitor(g, 0.0, 0.0, Edges::Falling, true), 0);
  EXPECT_EQ(steps::edge_monitor(g, 1.0, 0.0, Edges::Falling, false), 2);
  EXPECT_EQ(steps::edge_monitor(g, 0.0, 0.0, Edges::Both, false), 0);
}

// A guarded motion: starts when its `when` holds, ends through an `until`
// (code 1) or, while running, through a violated `while` (code 2); the until
// wins in the tick both happen; a violated while before the start is not
// checked.
TEST(GuardedMotionStep, EndsThroughUntilOrAViolatedWhile) {
  using steps::MotionState;
  struct Tick {
    bool when, whiles, until;
  };
  const auto run = [](const std::vector<Tick>& ticks) {
    MotionState state = MotionState::Idle;
    std::vector<std::pair<bool, int>> out;
    for (const Tick& t : ticks) {
      const std::array<bool, 1> when{t.when}, whiles{t.whiles}, until{t.until};
      std::uint8_t ended = 9;
      const bool running = steps::guarded_motion(state, when, whiles, until, ended);
      out.emplace_back(running, ended);
    }
    return std::make_pair(out, state);
  };
  using R = std::vector<std::pair<bool, int>>;
  // Not started while `when` fails, although its while is violated.
  auto [a, sa] = run({{false, false, false},
                      {true, true, false},
                      {true, true, false},
                      {false, false, false},
                      {true, true, false}});
  EXPECT_EQ(a, (R{{false, 0}, {true, 0}, {true, 0}, {false, 2}, {false, 0}}));
  EXPECT_EQ(sa, MotionState::Aborted);
  // An until ends it normally, even in a tick its while is violated.
  auto [b, sb] = run({{true, true, false}, {true, false, true}, {true, true, false}});
  EXPECT_EQ(b, (R{{true, 0}, {false, 1}, {false, 0}}));
  EXPECT_EQ(sb, MotionState::Done);
  // A while violated in the tick the motion starts aborts it at once.
  auto [c, sc] = run({{true, false, false}});
  EXPECT_EQ(c, (R{{false, 2}}));
  EXPECT_EQ(sc, MotionState::Aborted);
}

}  // namespace
}  // namespace mospec::runtime
