// The loop check's linear algebra (runtime/transfer.hpp): polynomial roots,
// the controllers' laws as transfers (checked against their own step()), the
// second-order identification and the closed-loop poles.
#include "runtime/transfer.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <vector>

#include "runtime/controllers.hpp"

namespace mospec::runtime {
namespace {

using Roots = std::vector<std::complex<double>>;

// Sorted by real part, then imaginary part.
Roots sorted(Roots r) {
  std::sort(r.begin(), r.end(), [](auto a, auto b) {
    return a.real() != b.real() ? a.real() < b.real() : a.imag() < b.imag();
  });
  return r;
}

TEST(Transfer, RootsOfKnownPolynomials) {
  // (z - 2)(z + 0.5) = z^2 - 1.5 z - 1
  Roots r = sorted(roots({-1.0, -1.5, 1.0}));
  ASSERT_EQ(r.size(), 2u);
  EXPECT_NEAR(r[0].real(), -0.5, 1e-12);
  EXPECT_NEAR(r[1].real(), 2.0, 1e-12);
  // z^2 + 1: +-i; a leading zero coefficient is dropped.
  r = sorted(roots({1.0, 0.0, 1.0, 0.0}));
  ASSERT_EQ(r.size(), 2u);
  EXPECT_NEAR(r[0].imag(), -1.0, 1e-12);
  EXPECT_NEAR(r[1].imag(), 1.0, 1e-12);
  EXPECT_TRUE(roots({3.0}).empty());
  EXPECT_TRUE(roots({}).empty());
  EXPECT_DOUBLE_EQ(spectral_radius(roots({-1.0, -1.5, 1.0})), 2.0);
}

TEST(Transfer, PolynomialArithmetic) {
  const Polynomial a = {1.0, 2.0}, b = {-1.0, 0.0, 3.0};
  EXPECT_EQ(a * b, (Polynomial{-1.0, -2.0, 3.0, 6.0}));
  EXPECT_EQ(a + b, (Polynomial{0.0, 2.0, 3.0}));
  EXPECT_EQ(a - b, (Polynomial{2.0, 2.0, -3.0}));
  EXPECT_EQ(2.0 * a, (Polynomial{2.0, 4.0}));
}

// Runs the difference equation den(z) y = num(z) u (y_k from the past of y and
// u, as the transfer says) on `u`, from rest.
std::vector<double> filter(const Transfer& t, const std::vector<double>& u) {
  const size_t n = t.den.size() - 1;  // den's degree; den[n] is the leading coefficient
  std::vector<double> y(u.size(), 0.0);
  for (size_t k = 0; k < u.size(); ++k) {
    // sum_i den[i] y[k - n + i] = sum_i num[i] u[k - n + i]
    double acc = 0.0;
    for (size_t i = 0; i < t.num.size(); ++i)
      if (k + i >= n) acc += t.num[i] * u[k + i - n];
    for (size_t i = 0; i < n; ++i)
      if (k + i >= n) acc -= t.den[i] * y[k + i - n];
    y[k] = acc / t.den[n];
  }
  return y;
}

// An error sequence that is not special (no steps only, no zeros only).
std::vector<double> wiggle(size_t n) {
  std::vector<double> e(n);
  for (size_t k = 0; k < n; ++k) e[k] = std::sin(0.37 * k) + 0.2 * std::cos(1.3 * k) + 0.1;
  return e;
}

TEST(Transfer, PidTransferIsWhatStepComputes) {
  const double h = 0.002;
  for (const PidSpec spec : {PidSpec{.kp = 3.0, .ki = 40.0, .kd = 0.05, .decay_rate = 0.99},
                             PidSpec{.kp = 3.0, .ki = 40.0, .kd = 0.0, .decay_rate = 0.0},
                             PidSpec{.kp = -2.0, .ki = 0.0, .kd = 0.3}}) {
    const Pid pid(spec);
    const std::vector<double> e = wiggle(200);
    // From rest: the error was 0 before the first sample, as the transfer assumes.
    PidState state;
    Pid::reset(state, 0.0);
    std::vector<double> u(e.size());
    for (size_t k = 0; k < e.size(); ++k) {
      pid.step(state, e[k], h);
      u[k] = state.output;
    }
    const std::vector<double> predicted = filter(pid.transfer(h), e);
    for (size_t k = 0; k < e.size(); ++k) ASSERT_NEAR(predicted[k], u[k], 1e-9) << "sample " << k;
  }
}

TEST(Transfer, ImpedanceTransferIsWhatStepComputes) {
  const double h = 0.001;
  const Impedance impedance({.stiffness = 500.0, .damping = 20.0});
  const std::vector<double> e = wiggle(100);
  ImpedanceState state;
  state.has_previous = true;  // from rest: the error was 0
  std::vector<double> u(e.size());
  for (size_t k = 0; k < e.size(); ++k) {
    impedance.step(state, e[k], h);
    u[k] = state.output;
  }
  const std::vector<double> predicted = filter(impedance.transfer(h), e);
  for (size_t k = 0; k < e.size(); ++k) ASSERT_NEAR(predicted[k], u[k], 1e-9) << "sample " << k;
}

// The response to a held unit step of `plant`, k = 0..n-1.
std::vector<double> step_response(const Transfer& plant, size_t n) {
  return filter(plant, std::vector<double>(n, 1.0));
}

TEST(Transfer, IdentifiesSecondOrderPlantsFromTheirStepResponse) {
  const double h = 0.001;
  // A double integrator (a position driven by a force): (h^2/2)(z + 1) / (z - 1)^2.
  const Transfer position{.num = {h * h / 2, h * h / 2}, .den = {1.0, -2.0, 1.0}};
  // An integrator with a lag (a velocity driven by an acceleration, damped).
  const Transfer velocity{.num = {0.0, h}, .den = {0.9, -1.9, 1.0}};
  // A damped mode.
  const Transfer mode{.num = {0.01, 0.02}, .den = {0.81, -1.2, 1.0}};
  for (const Transfer& truth : {position, velocity, mode}) {
    const std::vector<double> s = step_response(truth, 20);
    ASSERT_EQ(s[0], 0.0);  // strictly proper: the step acts through the next tick
    const IdentifiedPlant fit = identify_second_order(s);
    EXPECT_LT(fit.misfit, 1e-9);
    const std::vector<double> again = step_response(fit.plant, 40);
    const std::vector<double> expected = step_response(truth, 40);  // beyond the fit's window too
    for (size_t k = 0; k < again.size(); ++k)
      EXPECT_NEAR(again[k], expected[k], 1e-9 * (1 + std::abs(expected[k]))) << "sample " << k;
  }
  // A pure integrator: its constant increments fit many recursions (a1 + a2 =
  // 1), each giving the same response; the fit's small ridge picks one of
  // least norm, a hair inside that line.
  const Transfer integrator{.num = {h}, .den = {-1.0, 1.0}};
  const IdentifiedPlant fit = identify_second_order(step_response(integrator, 20));
  EXPECT_LT(fit.misfit, 1e-9);
  const std::vector<double> again = step_response(fit.plant, 40);
  for (size_t k = 0; k < again.size(); ++k) EXPECT_NEAR(again[k], h * k, 1e-6 * h * k);
  // Too short, or no response at all: a misfit of 1 (not identified).
  EXPECT_EQ(identify_second_order({0.0, 1.0, 2.0}).misfit, 1.0);
  EXPECT_EQ(identify_second_order(std::vector<double>(20, 0.0)).misfit, 1.0);
}

TEST(Transfer, ClosedLoopPolesOfAProportionalVelocityLoop) {
  // e_{k+1} = e_k + g u_k with u = K e: the pole is 1 + g K, stable for
  // -2 < g K < 0 and diverging past either end.
  const double g = -0.001;
  const Transfer plant{.num = {g}, .den = {-1.0, 1.0}};
  for (const double kp : {100.0, 1900.0, -100.0, 2100.0}) {
    const Pid pid({.kp = kp});
    const Roots poles = closed_loop_poles(plant, pid.transfer(0.001));
    EXPECT_NEAR(spectral_radius(poles), std::abs(1 + g * kp), 1e-9) << "kp " << kp;
  }
}

}  // namespace
}  // namespace mospec::runtime
