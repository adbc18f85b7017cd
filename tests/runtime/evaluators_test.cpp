// Constraint evaluators: the error sign table, tolerances, NaN and setup checks.
#include "runtime/evaluators.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "support/diagnostics.hpp"

namespace mospec::runtime {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::string error_of(const ConstraintSpec& spec, const char* name) {
  try {
    ConstraintEvaluator e(spec, name);
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), "invalid-constraint");
    return e.diagnostic().message;
  }
  return "(no error)";
}

TEST(Evaluators, EqualityErrorIsReferenceMinusMeasured) {
  const ConstraintEvaluator eq(
      {.kind = ConstraintKind::Equality, .reference = 0.5, .tolerance = 0.01});
  EXPECT_DOUBLE_EQ(eq.evaluate(0.3).error, 0.2);
  EXPECT_DOUBLE_EQ(eq.evaluate(0.3).output, 0.2);
  EXPECT_DOUBLE_EQ(eq.evaluate(0.7).error, -0.2);
  EXPECT_FALSE(eq.evaluate(0.3).satisfied);
  EXPECT_TRUE(eq.evaluate(0.495).satisfied);
  EXPECT_TRUE(eq.evaluate(0.5).satisfied);
  EXPECT_FALSE(eq.evaluate(0.52).satisfied);
}

TEST(Evaluators, InequalitiesAreZeroWhenSatisfied) {
  const ConstraintEvaluator lt({.kind = ConstraintKind::LessThan, .threshold = 2.0});
  EXPECT_EQ(lt.evaluate(1.0).error, 0.0);
  EXPECT_EQ(lt.evaluate(2.0).error, 0.0);
  EXPECT_TRUE(lt.evaluate(2.0).satisfied);
  EXPECT_DOUBLE_EQ(lt.evaluate(2.5).error, -0.5);  // too high: decrease
  EXPECT_FALSE(lt.evaluate(2.5).satisfied);

  const ConstraintEvaluator gt({.kind = ConstraintKind::GreaterThan, .threshold = 2.0});
  EXPECT_EQ(gt.evaluate(3.0).error, 0.0);
  EXPECT_DOUBLE_EQ(gt.evaluate(1.25).error, 0.75);  // too low: increase
  EXPECT_FALSE(gt.evaluate(1.25).satisfied);
}

TEST(Evaluators, BilateralIsTheSignedDistanceToTheNearestBound) {
  const ConstraintEvaluator tube(
      {.kind = ConstraintKind::Bilateral, .lower = 0.4, .upper = 0.6, .tolerance = 0.05});
  for (double m : {0.4, 0.45, 0.5, 0.6}) {
    EXPECT_EQ(tube.evaluate(m).error, 0.0) << m;
    EXPECT_TRUE(tube.evaluate(m).satisfied) << m;
  }
  EXPECT_NEAR(tube.evaluate(0.1).error, 0.3, 1e-15);
  EXPECT_NEAR(tube.evaluate(0.9).error, -0.3, 1e-15);
  EXPECT_FALSE(tube.evaluate(0.9).satisfied);
  // Outside, but within the tolerance.
  EXPECT_TRUE(tube.evaluate(0.63).satisfied);
  EXPECT_FALSE(tube.evaluate(0.66).satisfied);
  // The error is continuous across the bounds and monotone non-increasing.
  double previous = tube.evaluate(-1.0).error;
  for (double m = -1.0; m <= 2.0; m += 1e-3) {
    const double e = tube.evaluate(m).error;
    EXPECT_LE(e, previous + 1e-12);
    EXPECT_NEAR(e, previous, 1.1e-3);
    previous = e;
  }
}

TEST(Evaluators, AssignmentOutputsTheReference) {
  const ConstraintEvaluator ff({.kind = ConstraintKind::Assignment, .reference = -12.5});
  const Evaluation e = ff.evaluate(kNaN);
  EXPECT_EQ(e.output, -12.5);
  EXPECT_EQ(e.error, 0.0);
  EXPECT_TRUE(e.satisfied);
}

TEST(Evaluators, NanMeasurementGivesNanErrorAndNotSatisfied) {
  for (ConstraintKind kind : {ConstraintKind::Equality, ConstraintKind::LessThan,
                              ConstraintKind::GreaterThan, ConstraintKind::Bilateral}) {
    const ConstraintEvaluator e(
        {.kind = kind, .lower = -1, .upper = 1, .tolerance = std::numeric_limits<double>::max()});
    EXPECT_TRUE(std::isnan(e.evaluate(kNaN).error));
    EXPECT_FALSE(e.evaluate(kNaN).satisfied);
  }
}

TEST(Evaluators, SetupChecksNameTheConstraint) {
  EXPECT_EQ(error_of({.kind = ConstraintKind::Bilateral, .lower = 0.6, .upper = 0.4}, "cstr-dist"),
            "cstr-dist: bilateral constraint needs lower < upper, got lower 0.59999999999999998 "
            "and upper 0.40000000000000002");
  EXPECT_EQ(error_of({.kind = ConstraintKind::Bilateral, .lower = 0.5, .upper = 0.5}, "c"),
            "c: bilateral constraint needs lower < upper, got lower 0.5 and upper 0.5");
  EXPECT_EQ(error_of({.kind = ConstraintKind::Equality, .reference = kNaN}, "c"),
            "c: reference must be finite, got nan");
  EXPECT_EQ(error_of({.kind = ConstraintKind::LessThan, .threshold = INFINITY}, "c"),
            "c: threshold must be finite, got inf");
  EXPECT_EQ(error_of({.kind = ConstraintKind::Equality, .tolerance = -1}, "c"),
            "c: tolerance must be finite and >= 0, got -1");
}

}  // namespace
}  // namespace mospec::runtime
