// PID with the paper's decaying integral (Eq. 4): closed-form responses,
// variable dt, invalid dt and inputs, saturation and anti-windup. The damping
// and impedance controllers: their laws, saturation, invalid inputs and
// refused descriptions.
#include "runtime/controllers.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "runtime/steps.hpp"
#include "support/diagnostics.hpp"

namespace mospec::runtime {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

std::string error_of(const PidSpec& spec) {
  try {
    Pid pid(spec, "ctrl-dist");
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), "invalid-controller");
    return e.diagnostic().message;
  }
  return "(no error)";
}

TEST(Pid, ProportionalAndFeedForward) {
  const Pid pid({.kp = 2.0});
  PidState s;
  EXPECT_EQ(pid.step(s, 0.25, 1e-3, 1.0), PidStatus::Ok);
  EXPECT_DOUBLE_EQ(s.output, 1.5);
  EXPECT_FALSE(s.saturated);
}

TEST(Pid, ConstantErrorIntegralGrowsLinearlyWhateverTheTicks) {
  const Pid pid({.ki = 3.0});
  PidState s;
  std::mt19937 rng(1);
  std::uniform_real_distribution<> dt(1e-4, 5e-3);
  double t = 0;
  for (int k = 0; k < 2000; ++k) {
    const double h = dt(rng);
    t += h;
    ASSERT_EQ(pid.step(s, 0.5, h), PidStatus::Ok);
    ASSERT_NEAR(s.integral, 0.5 * t, 1e-12 * (1 + t));
  }
  EXPECT_NEAR(s.output, 3.0 * 0.5 * t, 1e-10);
}

TEST(Pid, TrapezoidalIntegralIsExactForARamp) {
  // ε(t) = c t: ∫ = c t² / 2, exact with the first-order hold.
  const Pid pid({.ki = 1.0});
  PidState s;
  Pid::reset(s, 0.0);
  double t = 0;
  for (int k = 1; k <= 1000; ++k) {
    const double h = (k % 3 == 0) ? 2e-3 : 0.5e-3;
    t += h;
    pid.step(s, 0.7 * t, h);
  }
  EXPECT_NEAR(s.integral, 0.7 * t * t / 2, 1e-12);
}

TEST(Pid, DecayingIntegralUnderConstantErrorMatchesTheClosedForm) {
  // I(t) = ε (1 - e^{-λt}) / λ, converging to ε / λ.
  const double lambda = 0.99, eps = 0.2;
  const Pid pid({.ki = 1.0, .decay_rate = lambda});
  PidState s;
  std::mt19937 rng(2);
  std::uniform_real_distribution<> dt(1e-4, 2e-2);
  double t = 0;
  while (t < 30.0) {
    const double h = dt(rng);
    t += h;
    pid.step(s, eps, h);
    ASSERT_NEAR(s.integral, eps * (1 - std::exp(-lambda * t)) / lambda, 1e-12);
  }
  EXPECT_NEAR(s.integral, eps / lambda, 1e-13 + eps / lambda * std::exp(-lambda * t));
}

TEST(Pid, DecayingIntegralIsExactForARamp) {
  // ε(t) = c t: I(t) = c [t/λ - (1 - e^{-λt})/λ²].
  const double lambda = 0.6, c = 1.5;
  const Pid pid({.ki = 1.0, .decay_rate = lambda});
  PidState s;
  Pid::reset(s, 0.0);
  double t = 0;
  for (int k = 1; k <= 3000; ++k) {
    const double h = (k % 2 == 0) ? 3e-3 : 1e-3;
    t += h;
    pid.step(s, c * t, h);
  }
  EXPECT_NEAR(s.integral, c * (t / lambda - (1 - std::exp(-lambda * t)) / (lambda * lambda)),
              1e-11);
}

TEST(Pid, DecayingIntegralFadesOnceTheErrorIsZero) {
  // The paper's tube: once inside, the error is zero and the integral decays
  // as e^{-λt}, where a plain integral keeps its value.
  const double lambda = 0.99;
  const Pid decaying({.ki = 1.0, .decay_rate = lambda});
  const Pid plain({.ki = 1.0});
  PidState a, b;
  Pid::reset(a, 0.0);  // inside the tube: zero error from the start of the decay
  Pid::reset(b, 0.0);
  a.integral = 1.0;
  b.integral = 1.0;
  for (int k = 0; k < 5000; ++k) {
    decaying.step(a, 0.0, 1e-3);
    plain.step(b, 0.0, 1e-3);
  }
  EXPECT_NEAR(a.integral, std::exp(-lambda * 5.0), 1e-12);
  EXPECT_DOUBLE_EQ(b.integral, 1.0);
}

TEST(Pid, PhiFunctionsAreAccurateAcrossTheSeriesSwitch) {
  for (double a : {0.0, 1e-12, 1e-6, 1e-3, 9.999e-3, 1e-2, 0.1, 0.999, 1.0, 1.001, 3.0, 30.0}) {
    // Reference values in long double: the Taylor series for a < 1 (40 terms),
    // the closed form above (no cancellation there).
    const long double al = a;
    long double phi1 = 0, phi2 = 0;
    if (a < 1) {
      long double power = 1, factorial = 1;
      for (int n = 0; n < 40; ++n) {
        factorial *= (n + 1);  // (n+1)!
        phi1 += (n % 2 == 0 ? 1 : -1) * power / factorial;
        phi2 += (n % 2 == 0 ? 1 : -1) * (n + 1) * power / (factorial * (n + 2));
        power *= al;
      }
    } else {
      const long double e = std::exp(-al);
      phi1 = (1.0L - e) / al;
      phi2 = (1.0L - (1.0L + al) * e) / (al * al);
    }
    EXPECT_NEAR(decay_phi1(a), static_cast<double>(phi1), 4e-16) << a;
    EXPECT_NEAR(decay_phi2(a), static_cast<double>(phi2), 4e-16) << a;
  }
}

TEST(Pid, DerivativeUsesTheMeasuredDt) {
  const Pid pid({.kd = 2.0});
  PidState s;
  pid.step(s, 1.0, 1e-3);
  EXPECT_EQ(s.output, 0.0);  // first step: no previous error, no derivative
  pid.step(s, 1.5, 0.25);
  EXPECT_DOUBLE_EQ(s.derivative, 2.0);
  EXPECT_DOUBLE_EQ(s.output, 4.0);
  pid.step(s, 1.0, 0.1);
  EXPECT_DOUBLE_EQ(s.derivative, -5.0);
}

TEST(Pid, InvalidDtHoldsEverything) {
  const Pid pid({.kp = 1.0, .ki = 1.0, .kd = 1.0});
  PidState s;
  pid.step(s, 1.0, 1e-3);
  pid.step(s, 2.0, 1e-3);
  const PidState before = s;
  for (double dt : {0.0, -1e-3, kNaN, kInf, -kInf}) {
    EXPECT_EQ(pid.step(s, 100.0, dt), PidStatus::HeldInvalidDt) << dt;
    EXPECT_EQ(s.output, before.output);
    EXPECT_EQ(s.integral, before.integral);
    EXPECT_EQ(s.previous_error, before.previous_error);
    EXPECT_FALSE(s.fault);
  }
  EXPECT_EQ(pid.step(s, 2.0, 1e-3), PidStatus::Ok);
  EXPECT_TRUE(std::isfinite(s.output));
}

TEST(Pid, NanInputHoldsTheOutputAndLatchesTheFault) {
  const Pid pid({.kp = 1.0, .ki = 10.0, .kd = 0.1, .decay_rate = 0.5});
  PidState s;
  pid.step(s, 1.0, 1e-3);
  const double held = s.output, integral = s.integral;
  EXPECT_EQ(pid.step(s, kNaN, 1e-3), PidStatus::HeldInvalidInput);
  EXPECT_EQ(pid.step(s, kInf, 1e-3), PidStatus::HeldInvalidInput);
  EXPECT_EQ(pid.step(s, 1.0, 1e-3, kNaN), PidStatus::HeldInvalidInput);
  EXPECT_EQ(s.output, held);
  EXPECT_EQ(s.integral, integral);
  EXPECT_TRUE(s.fault);
  // Valid input again: finite output, the fault stays latched until reset.
  EXPECT_EQ(pid.step(s, 1.0, 1e-3), PidStatus::Ok);
  EXPECT_TRUE(std::isfinite(s.output) && std::isfinite(s.integral));
  EXPECT_TRUE(s.fault);
  Pid::reset(s);
  EXPECT_FALSE(s.fault);
}

TEST(Pid, SaturationClampsTheOutput) {
  const Pid pid({.kp = 100.0, .output_min = -5.0, .output_max = 5.0});
  PidState s;
  pid.step(s, 1.0, 1e-3);
  EXPECT_EQ(s.output, 5.0);
  EXPECT_TRUE(s.saturated);
  pid.step(s, -1.0, 1e-3);
  EXPECT_EQ(s.output, -5.0);
  pid.step(s, 0.01, 1e-3);
  EXPECT_DOUBLE_EQ(s.output, 1.0);
  EXPECT_FALSE(s.saturated);
}

// Windup: a long saturated phase, then the error reverses. Without anti-windup
// the output stays pinned for a long time; with either scheme it leaves the
// limit at once.
double time_pinned_after_reversal(AntiWindup aw) {
  const Pid pid({.kp = 1.0,
                 .ki = 5.0,
                 .output_min = -1.0,
                 .output_max = 1.0,
                 .anti_windup = aw,
                 .tracking_rate = 50.0});
  PidState s;
  const double h = 1e-3;
  for (int k = 0; k < 5000; ++k) pid.step(s, 2.0, h);  // 5 s pushing up, saturated
  EXPECT_EQ(s.output, 1.0);
  double t = 0;
  while (s.output >= 1.0 && t < 100) {
    pid.step(s, -0.5, h);
    t += h;
  }
  return t;
}

TEST(Pid, AntiWindupReleasesTheLimitPromptly) {
  const double none = time_pinned_after_reversal(AntiWindup::None);
  const double conditional = time_pinned_after_reversal(AntiWindup::ConditionalIntegration);
  const double back = time_pinned_after_reversal(AntiWindup::BackCalculation);
  EXPECT_GT(none, 15.0);  // the integral of 2 × 5 s must be unwound at 0.5/s
  EXPECT_LT(conditional, 0.5);
  EXPECT_LT(back, 0.5);
}

TEST(Pid, ConditionalIntegrationFreezesOnlyTheIncrementThatWindsUp) {
  const Pid pid({.ki = 1.0, .output_max = 1.0});
  PidState s;
  for (int k = 0; k < 3000; ++k) pid.step(s, 1.0, 1e-3);
  // Integrates until the output would pass the limit (I = 1), then holds just
  // below it: the increment that would wind up is dropped.
  EXPECT_NEAR(s.integral, 1.0, 1.1e-3);
  EXPECT_LE(s.output, 1.0);
  // An error that unwinds integrates immediately.
  // (The first such step averages +1 and -1 over the interval: no change.)
  const double before = s.integral;
  pid.step(s, -1.0, 1e-3);
  pid.step(s, -1.0, 1e-3);
  EXPECT_NEAR(s.integral, before - 1e-3, 1e-15);
}

TEST(Pid, BackCalculationTracksTheLimit) {
  // With the error held, the unclamped output relaxes to the limit at rate k_b.
  const double kb = 20.0;
  const Pid pid({.kp = 1.0,
                 .ki = 2.0,
                 .output_max = 1.0,
                 .anti_windup = AntiWindup::BackCalculation,
                 .tracking_rate = kb});
  PidState s;
  for (int k = 0; k < 5000; ++k) pid.step(s, 3.0, 1e-3);
  // Steady state of the per-step map: each step adds ki ε h, and the tracking
  // removes the fraction f = 1 - e^{-k_b h} of the excess, so the unclamped
  // output settles at limit + (1 - f) ki ε h / f.
  const double f = 1 - std::exp(-kb * 1e-3);
  EXPECT_NEAR(1.0 * 3.0 + 2.0 * s.integral, 1.0 + (1 - f) * 2.0 * 3.0 * 1e-3 / f, 1e-9);
  EXPECT_EQ(s.output, 1.0);
}

TEST(Pid, FirstOrderPlantClosedLoopMatchesTheAnalyticStepResponse) {
  // Plant τ ẏ = -y + K u; PI with ki/kp = 1/τ cancels the pole, so the closed
  // loop is first order: y(t) = r (1 - e^{-K kp t / τ}).
  const double tau = 0.5, K = 2.0, kp = 1.5, r = 0.3;
  const Pid pid({.kp = kp, .ki = kp / tau});
  PidState s;
  const double h = 1e-4;
  double y = 0, t = 0, worst = 0;
  Pid::reset(s, r - y);
  for (int k = 0; k < 20000; ++k) {
    pid.step(s, r - y, h);
    // Exact plant step with u held over h.
    const double yss = K * s.output;
    y = yss + (y - yss) * std::exp(-h / tau);
    t += h;
    worst = std::max(worst, std::abs(y - r * (1 - std::exp(-K * kp * t / tau))));
  }
  RecordProperty("worst_deviation", std::to_string(worst));
  EXPECT_LT(worst, 5e-4);
}

TEST(Pid, ConvertsAPerTickFactor) {
  EXPECT_NEAR(decay_rate_from_factor_per_tick(0.99, 1e-3), 10.050335853501, 1e-9);
  EXPECT_EQ(decay_rate_from_factor_per_tick(1.0, 1e-3), 0.0);
}

TEST(Pid, SetupChecksNameTheController) {
  EXPECT_EQ(error_of({.decay_rate = 1.5}),
            "ctrl-dist: decay rate must be in [0, 1] per second (Eq. 4), got 1.5 (a per-tick "
            "factor beta at period T is -ln(beta)/T per second)");
  EXPECT_EQ(error_of({.decay_rate = -0.1}).substr(0, 40),
            "ctrl-dist: decay rate must be in [0, 1] ");
  EXPECT_EQ(error_of({.kp = kNaN}), "ctrl-dist: gains must be finite, got kp nan, ki 0, kd 0");
  EXPECT_EQ(error_of({.output_min = 1, .output_max = 1}),
            "ctrl-dist: output limits need min < max, got min 1 and max 1");
  EXPECT_EQ(error_of({.ki = 1, .anti_windup = AntiWindup::BackCalculation}),
            "ctrl-dist: back-calculation anti-windup needs a tracking rate > 0 [1/s]");
  EXPECT_EQ(error_of({.tracking_rate = -1}),
            "ctrl-dist: tracking rate must be finite and >= 0, got -1");
  EXPECT_EQ(error_of({.kp = 450, .ki = 65.5, .kd = 80, .decay_rate = 0.99}), "(no error)");
}

template <class Controller, class Spec>
std::string refusal(const Spec& spec) {
  try {
    Controller c(spec, "ctrl");
  } catch (const Error& e) {
    EXPECT_EQ(e.code(), "invalid-controller");
    return e.diagnostic().message;
  }
  return "(no error)";
}

TEST(Damping, OpposesTheVelocityLinearlyUpToTheMaximumForce) {
  // v_max 0.2 m/s calls for F_max 10 N: b = 50 N s/m.
  const Damping damper({.maximum_velocity = 0.2, .maximum_force = 10.0});
  EXPECT_DOUBLE_EQ(damper.coefficient(), 50.0);
  EXPECT_DOUBLE_EQ(damper.force(0.0), 0.0);
  EXPECT_DOUBLE_EQ(damper.force(0.1), -5.0);
  EXPECT_DOUBLE_EQ(damper.force(-0.1), 5.0);
  EXPECT_DOUBLE_EQ(damper.force(0.2), -10.0);
  EXPECT_DOUBLE_EQ(damper.force(3.0), -10.0);  // saturated
  EXPECT_DOUBLE_EQ(damper.force(-kInf), 0.0);  // not finite: no force
  EXPECT_DOUBLE_EQ(damper.force(kNaN), 0.0);
}

TEST(Damping, InactiveCommandsNothing) {
  const Damping damper({.maximum_velocity = 1.0, .maximum_force = 2.0});
  EXPECT_DOUBLE_EQ(steps::damping(damper, 0.5, true), -1.0);
  EXPECT_DOUBLE_EQ(steps::damping(damper, 0.5, false), 0.0);
}

TEST(Damping, RefusesLimitsThatAreNotPositiveAndFinite) {
  EXPECT_EQ(refusal<Damping>(DampingSpec{.maximum_velocity = 0.0, .maximum_force = 1.0}),
            "ctrl: a damping controller needs a finite maximum velocity > 0 and a finite maximum "
            "force > 0, got maximum velocity 0 and maximum force 1");
  EXPECT_NE(refusal<Damping>(DampingSpec{.maximum_velocity = 1.0, .maximum_force = -1.0}),
            "(no error)");
  EXPECT_NE(refusal<Damping>(DampingSpec{.maximum_velocity = kInf, .maximum_force = 1.0}),
            "(no error)");
  EXPECT_NE(refusal<Damping>(DampingSpec{.maximum_velocity = 1.0, .maximum_force = kNaN}),
            "(no error)");
}

TEST(Impedance, SpringAndDamperOnTheError) {
  const Impedance imp({.stiffness = 300.0, .damping = 20.0});
  ImpedanceState s;
  imp.step(s, 0.01, 1e-3);  // first step: no rate yet
  EXPECT_DOUBLE_EQ(s.output, 3.0);
  imp.step(s, 0.011, 1e-3);  // de/dt = 1 m/s
  EXPECT_NEAR(s.rate, 1.0, 1e-9);
  EXPECT_NEAR(s.output, 300.0 * 0.011 + 20.0 * 1.0, 1e-9);
}

TEST(Impedance, EqualsAPdControllerWithTheSameGains) {
  const Impedance imp({.stiffness = 40.0, .damping = 3.0});
  const Pid pd({.kp = 40.0, .kd = 3.0});
  ImpedanceState si;
  PidState sp;
  for (int k = 0; k < 100; ++k) {
    const double e = std::sin(0.05 * k), dt = 1e-3 * (1 + k % 3);
    imp.step(si, e, dt);
    pd.step(sp, e, dt);
    EXPECT_DOUBLE_EQ(si.output, sp.output) << "step " << k;
  }
}

TEST(Impedance, HoldsOnInvalidDtAndInputsAndResetsWhenInactive) {
  const Impedance imp({.stiffness = 1.0, .damping = 1.0});
  ImpedanceState s;
  EXPECT_DOUBLE_EQ(steps::impedance(imp, s, 2.0, 0.5, true), 2.0);
  EXPECT_DOUBLE_EQ(steps::impedance(imp, s, 3.0, 0.0, true), 2.0);   // dt 0: held
  EXPECT_DOUBLE_EQ(steps::impedance(imp, s, kNaN, 0.5, true), 2.0);  // held, fault latched
  EXPECT_TRUE(s.fault);
  EXPECT_DOUBLE_EQ(steps::impedance(imp, s, 3.0, 0.5, true), 3.0 + 2.0);
  EXPECT_DOUBLE_EQ(steps::impedance(imp, s, 3.0, 0.5, false), 0.0);
  EXPECT_FALSE(s.fault);
  EXPECT_FALSE(s.has_previous);
}

TEST(Impedance, RefusesANegativeOrAbsentSpringAndDamper) {
  EXPECT_EQ(refusal<Impedance>(ImpedanceSpec{.stiffness = -1.0, .damping = 1.0}),
            "ctrl: an impedance controller needs a finite stiffness >= 0 and a finite damping >= 0 "
            "(a negative spring or damper is not passive), got stiffness -1 and damping 1");
  EXPECT_EQ(refusal<Impedance>(ImpedanceSpec{.stiffness = 0.0, .damping = 0.0}),
            "ctrl: an impedance controller with stiffness 0 and damping 0 commands nothing");
  EXPECT_NE(refusal<Impedance>(ImpedanceSpec{.stiffness = 1.0, .damping = kInf}), "(no error)");
}

}  // namespace
}  // namespace mospec::runtime
