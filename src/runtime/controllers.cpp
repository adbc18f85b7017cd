#include "runtime/controllers.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "support/diagnostics.hpp"

namespace mospec::runtime {
namespace {

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

[[noreturn]] void reject(const char* name, const std::string& what) {
  throw Error("invalid-controller", std::string(name) + ": " + what);
}

}  // namespace

double decay_rate_from_factor_per_tick(double factor, double period) noexcept {
  return -std::log(factor) / period;
}

double decay_phi1(double a) noexcept {
  if (a == 0.0) return 1.0;
  return -std::expm1(-a) / a;
}

double decay_phi2(double a) noexcept {
  if (a < 1e-2) {
    // Σ_{n>=2} (-1)^n (n-1)/n! a^(n-2); the first omitted term is a^5/840.
    return 0.5 + a * (-1.0 / 3.0 + a * (1.0 / 8.0 + a * (-1.0 / 30.0 + a * (1.0 / 144.0))));
  }
  return (-std::expm1(-a) - a * std::exp(-a)) / (a * a);
}

Pid::Pid(const PidSpec& spec, const char* name) : spec_(spec) {
  if (!std::isfinite(spec.kp) || !std::isfinite(spec.ki) || !std::isfinite(spec.kd)) {
    reject(name, "gains must be finite, got kp " + number(spec.kp) + ", ki " + number(spec.ki) +
                     ", kd " + number(spec.kd));
  }
  if (!(spec.decay_rate >= 0.0 && spec.decay_rate <= 1.0)) {
    reject(name, "decay rate must be in [0, 1] per second (Eq. 4), got " + number(spec.decay_rate) +
                     " (a per-tick factor beta at period T is -ln(beta)/T per second)");
  }
  if (!(spec.output_min < spec.output_max)) {
    reject(name, "output limits need min < max, got min " + number(spec.output_min) + " and max " +
                     number(spec.output_max));
  }
  if (!(spec.tracking_rate >= 0.0) || !std::isfinite(spec.tracking_rate)) {
    reject(name, "tracking rate must be finite and >= 0, got " + number(spec.tracking_rate));
  }
  if (spec.anti_windup == AntiWindup::BackCalculation && spec.ki != 0.0 &&
      !(spec.tracking_rate > 0.0)) {
    reject(name, "back-calculation anti-windup needs a tracking rate > 0 [1/s]");
  }
}

PidStatus Pid::step(PidState& s, double error, double dt, double feed_forward) const noexcept {
  if (!(dt > 0.0) || !std::isfinite(dt)) return PidStatus::HeldInvalidDt;
  if (!std::isfinite(error) || !std::isfinite(feed_forward)) {
    s.fault = true;
    return PidStatus::HeldInvalidInput;
  }
  const PidSpec& p = spec_;
  const double e0 = s.has_previous ? s.previous_error : error;
  const double a = p.decay_rate * dt;
  const double decay = std::exp(-a);
  const double phi2 = decay_phi2(a);
  const double decayed = decay * s.integral;
  const double increment = dt * (phi2 * e0 + (decay_phi1(a) - phi2) * error);
  const double derivative = s.has_previous ? (error - e0) / dt : 0.0;
  const double rest = feed_forward + p.kp * error + p.kd * derivative;

  double integral = decayed + increment;
  double u = rest + p.ki * integral;
  switch (p.anti_windup) {
    case AntiWindup::None:
      break;
    case AntiWindup::ConditionalIntegration:
      if ((u > p.output_max && p.ki * increment > 0.0) ||
          (u < p.output_min && p.ki * increment < 0.0)) {
        integral = decayed;
        u = rest + p.ki * integral;
      }
      break;
    case AntiWindup::BackCalculation:
      if (p.ki != 0.0) {
        const double clamped = std::clamp(u, p.output_min, p.output_max);
        integral += -std::expm1(-p.tracking_rate * dt) * (clamped - u) / p.ki;
        u = rest + p.ki * integral;
      }
      break;
  }
  const double out = std::clamp(u, p.output_min, p.output_max);
  s.integral = integral;
  s.previous_error = error;
  s.has_previous = true;
  s.derivative = derivative;
  s.saturated = out != u;
  s.output = out;
  return PidStatus::Ok;
}

}  // namespace mospec::runtime
