#include "runtime/controllers.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>

#include "support/diagnostics.hpp"

namespace mospec::runtime {
namespace {

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

namespace {
// Taylor coefficients of φ2: (-1)^n (n+1) / (n+2)!, n = 0..17. At a = 1 the
// first omitted term is below 1e-17.
constexpr std::array<double, 18> kPhi2Series = [] {
  std::array<double, 18> c{};
  double factorial = 2.0;  // (n+2)!
  for (int n = 0; n < 18; ++n) {
    if (n > 0) factorial *= n + 2;
    c[n] = (n % 2 == 0 ? 1.0 : -1.0) * (n + 1) / factorial;
  }
  return c;
}();
}  // namespace

double decay_phi2(double a) noexcept {
  if (a < 1.0) {
    // The closed form cancels catastrophically for small a (1 - (1+a)e^{-a}
    // is about a²/2); the series does not.
    double sum = 0.0;
    for (int n = 17; n >= 0; --n) sum = sum * a + kPhi2Series[n];
    return sum;
  }
  return (-std::expm1(-a) - a * std::exp(-a)) / (a * a);
}

Pid::Pid(const PidSpec& spec, const char* name) : spec_(spec) {
  if (!std::isfinite(spec.kp) || !std::isfinite(spec.ki) || !std::isfinite(spec.kd)) {
    reject(name, "gains must be finite, got kp " + exact_number(spec.kp) + ", ki " +
                     exact_number(spec.ki) + ", kd " + exact_number(spec.kd));
  }
  if (!(spec.decay_rate >= 0.0 && spec.decay_rate <= 1.0)) {
    reject(name, "decay rate must be in [0, 1] per second (Eq. 4), got " +
                     exact_number(spec.decay_rate) +
                     " (a per-tick factor beta at period T is -ln(beta)/T per second)");
  }
  if (!(spec.output_min < spec.output_max)) {
    reject(name, "output limits need min < max, got min " + exact_number(spec.output_min) +
                     " and max " + exact_number(spec.output_max));
  }
  if (!(spec.tracking_rate >= 0.0) || !std::isfinite(spec.tracking_rate)) {
    reject(name, "tracking rate must be finite and >= 0, got " + exact_number(spec.tracking_rate));
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

Transfer Pid::transfer(double period) const {
  const PidSpec& p = spec_;
  const double h = period;
  const Polynomial z = {0.0, 1.0};
  const Polynomial z_minus_1 = {-1.0, 1.0};
  // Kp + Kd (z - 1) / (h z), over z.
  Transfer c{.num = p.kp * z + (p.kd / h) * z_minus_1, .den = z};
  if (p.ki == 0.0) return c;  // no integral: no pole at e^{-λh} to cancel
  const double a = p.decay_rate * h;
  const double decay = std::exp(-a);
  const double phi1 = decay_phi1(a), phi2 = decay_phi2(a);
  // I(z) = h ((φ1 - φ2) z + φ2) / (z - e^{-λh}) E(z): step()'s first-order hold.
  const Polynomial integral = {p.ki * h * phi2, p.ki * h * (phi1 - phi2)};
  const Polynomial pole = {-decay, 1.0};
  return {.num = c.num * pole + integral * z, .den = z * pole};
}

Damping::Damping(const DampingSpec& spec, const char* name) : spec_(spec) {
  if (!(spec.maximum_velocity > 0.0) || !std::isfinite(spec.maximum_velocity) ||
      !(spec.maximum_force > 0.0) || !std::isfinite(spec.maximum_force)) {
    reject(name,
           "a damping controller needs a finite maximum velocity > 0 and a finite maximum "
           "force > 0, got maximum velocity " +
               exact_number(spec.maximum_velocity) + " and maximum force " +
               exact_number(spec.maximum_force));
  }
  coefficient_ = spec.maximum_force / spec.maximum_velocity;
}

double Damping::force(double velocity) const noexcept {
  if (!std::isfinite(velocity)) return 0.0;
  return std::clamp(-coefficient_ * velocity, -spec_.maximum_force, spec_.maximum_force);
}

Impedance::Impedance(const ImpedanceSpec& spec, const char* name) : spec_(spec) {
  if (!(spec.stiffness >= 0.0) || !std::isfinite(spec.stiffness) || !(spec.damping >= 0.0) ||
      !std::isfinite(spec.damping)) {
    reject(name,
           "an impedance controller needs a finite stiffness >= 0 and a finite damping >= 0 "
           "(a negative spring or damper is not passive), got stiffness " +
               exact_number(spec.stiffness) + " and damping " + exact_number(spec.damping));
  }
  if (spec.stiffness == 0.0 && spec.damping == 0.0) {
    reject(name, "an impedance controller with stiffness 0 and damping 0 commands nothing");
  }
}

Transfer Impedance::transfer(double period) const {
  const double h = period;
  // K + D (z - 1) / (h z) = (D / h (z - 1) + K z) / z
  return {.num = Polynomial{-spec_.damping / h, spec_.stiffness + spec_.damping / h},
          .den = Polynomial{0.0, 1.0}};
}

void Impedance::step(ImpedanceState& s, double error, double dt) const noexcept {
  if (!(dt > 0.0) || !std::isfinite(dt)) return;
  if (!std::isfinite(error)) {
    s.fault = true;
    return;
  }
  const double rate = s.has_previous ? (error - s.previous_error) / dt : 0.0;
  s.rate = rate;
  s.previous_error = error;
  s.has_previous = true;
  s.output = spec_.stiffness * error + spec_.damping * rate;
}

}  // namespace mospec::runtime
