#include "runtime/evaluators.hpp"

#include <cstdio>
#include <string>

#include "support/diagnostics.hpp"

namespace mospec::runtime {
namespace {

[[noreturn]] void reject(const char* name, const std::string& what) {
  throw Error("invalid-constraint", std::string(name) + ": " + what);
}

void require_finite(const char* name, const char* field, double v) {
  if (!std::isfinite(v))
    reject(name, std::string(field) + " must be finite, got " + exact_number(v));
}

}  // namespace

ConstraintEvaluator::ConstraintEvaluator(const ConstraintSpec& spec, const char* name)
    : spec_(spec) {
  if (!(spec.tolerance >= 0.0) || !std::isfinite(spec.tolerance)) {
    reject(name, "tolerance must be finite and >= 0, got " + exact_number(spec.tolerance));
  }
  switch (spec.kind) {
    case ConstraintKind::Equality:
    case ConstraintKind::Assignment:
      require_finite(name, "reference", spec.reference);
      break;
    case ConstraintKind::LessThan:
    case ConstraintKind::GreaterThan:
      require_finite(name, "threshold", spec.threshold);
      break;
    case ConstraintKind::Bilateral:
      require_finite(name, "lower threshold", spec.lower);
      require_finite(name, "upper threshold", spec.upper);
      if (!(spec.lower < spec.upper)) {
        reject(name, "bilateral constraint needs lower < upper, got lower " +
                         exact_number(spec.lower) + " and upper " + exact_number(spec.upper));
      }
      break;
  }
}

}  // namespace mospec::runtime
