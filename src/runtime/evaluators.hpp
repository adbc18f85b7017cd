// Constraint evaluators (paper Sec. II-D/E): a constraint on a scalar quantity
// (a distance, an angle, one component of a twist or wrench) turned into an
// error signal and a satisfaction flag, consumed by monitors and controllers.
//
// Sign convention, the same for every kind: the error is the signed amount the
// MEASURED value must change by to satisfy the constraint,
//   error = target - measured,
// where the target is the reference (equality) or the nearest violated bound
// (inequalities); inside the feasible set the error is exactly zero. So a
// positive error means "increase the quantity", and a controller with positive
// gains on it pushes towards satisfaction.
//
//   kind          satisfied set            error
//   Equality      m = r                    r - m
//   LessThan      m <= t                   0 if m <= t, else t - m  (< 0)
//   GreaterThan   m >= t                   0 if m >= t, else t - m  (> 0)
//   Bilateral     lo <= m <= hi  (lo < hi) 0 inside; lo - m below (> 0);
//                                          hi - m above (< 0): the signed
//                                          distance to the nearest bound
//   Assignment    (feed-forward)           no error: output = r, the value to
//                                          impose (e.g. a force setpoint)
//
// Satisfied means |error| <= tolerance (tolerance >= 0, in the quantity's unit);
// Assignment is always satisfied. A NaN measurement gives a NaN error and
// "not satisfied" (a controller then holds its output and raises its fault).
// Units: those of the constrained quantity (SI).
#pragma once

#include <cmath>

namespace mospec::runtime {

// The error functions themselves, for thresholds that change every tick
// (trajectories). Preconditions (lower < upper) are the caller's; the
// ConstraintEvaluator below checks them at setup.
inline double equality_error(double reference, double measured) noexcept {
  return reference - measured;
}
// A NaN measurement fails every comparison, so it falls through to the
// "violated" branch and comes out as a NaN error.
inline double less_than_error(double threshold, double measured) noexcept {
  if (measured <= threshold) return 0.0;
  return threshold - measured;
}
inline double greater_than_error(double threshold, double measured) noexcept {
  if (measured >= threshold) return 0.0;
  return threshold - measured;
}
inline double bilateral_error(double lower, double upper, double measured) noexcept {
  if (measured >= lower && measured <= upper) return 0.0;
  return measured < lower ? lower - measured : upper - measured;
}

enum class ConstraintKind { Equality, LessThan, GreaterThan, Bilateral, Assignment };

// The constant description. Which fields are read depends on the kind:
// Equality/Assignment: reference; LessThan/GreaterThan: threshold;
// Bilateral: lower, upper.
struct ConstraintSpec {
  ConstraintKind kind = ConstraintKind::Equality;
  double reference = 0.0;
  double threshold = 0.0;
  double lower = 0.0;
  double upper = 0.0;
  double tolerance = 0.0;
};

struct Evaluation {
  double error = 0.0;   // target - measured (see the table above); Assignment: 0
  double output = 0.0;  // Assignment: the reference; otherwise the error
  bool satisfied = false;
};

class ConstraintEvaluator {
 public:
  // Throws mospec::Error("invalid-constraint") naming `name` and the offending
  // values: non-finite reference/thresholds, tolerance < 0 or NaN, or a
  // bilateral constraint with lower >= upper.
  ConstraintEvaluator(const ConstraintSpec& spec, const char* name = "constraint");

  const ConstraintSpec& spec() const { return spec_; }

  Evaluation evaluate(double measured) const noexcept {
    Evaluation e;
    switch (spec_.kind) {
      case ConstraintKind::Equality:
        e.error = equality_error(spec_.reference, measured);
        break;
      case ConstraintKind::LessThan:
        e.error = less_than_error(spec_.threshold, measured);
        break;
      case ConstraintKind::GreaterThan:
        e.error = greater_than_error(spec_.threshold, measured);
        break;
      case ConstraintKind::Bilateral:
        e.error = bilateral_error(spec_.lower, spec_.upper, measured);
        break;
      case ConstraintKind::Assignment:
        e.error = 0.0;
        e.output = spec_.reference;
        e.satisfied = true;
        return e;
    }
    e.output = e.error;
    e.satisfied = std::abs(e.error) <= spec_.tolerance;  // false for NaN
    return e;
  }

 private:
  ConstraintSpec spec_;
};

}  // namespace mospec::runtime
