// Monitors on sequences: level flags, edge events, hysteresis, NaN, setup checks.
#include "runtime/monitors.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <vector>

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

}  // namespace
}  // namespace mospec::runtime
