// Discrete-time single-input single-output linear systems as rational
// functions of z, for the closed-loop check before a run (cli/loop_check):
// a controller's law at a fixed tick, linearised where nothing saturates, and
// a plant identified from its response to a held step. Setup-time code: it
// allocates and may throw; nothing here runs in a control tick.
#pragma once

#include <complex>
#include <vector>

namespace mospec::runtime {

// c[0] + c[1] z + c[2] z^2 + ... (ascending powers).
using Polynomial = std::vector<double>;

Polynomial operator+(const Polynomial& a, const Polynomial& b);
Polynomial operator-(const Polynomial& a, const Polynomial& b);
Polynomial operator*(const Polynomial& a, const Polynomial& b);
Polynomial operator*(double k, const Polynomial& a);

// The roots of `p`, as the eigenvalues of its companion matrix (leading zero
// coefficients are dropped; a constant has none).
std::vector<std::complex<double>> roots(const Polynomial& p);

// y(z) = num(z) / den(z) u(z), one sample per control tick.
struct Transfer {
  Polynomial num, den;
};

// A second-order plant identified from its response to a held unit step:
// `step[k]` is its output's change k ticks after the input stepped from 0 to
// 1 (step[0] = 0: the input acts through the next tick). Its increments g_k =
// step[k] - step[k-1] are fitted, by least squares over k >= 3, with the free
// response of
//   G(z) = (b1 z + b2) / (z^2 - a1 z - a2),
// g_k = a1 g_{k-1} + a2 g_{k-2}, from g_1 and g_2 exactly. That covers an
// integrator with a lag (a velocity driven by an acceleration), a double
// integrator (a position), a static gain and a damped mode. `misfit` is the
// RMS of the recursion's residual over the RMS of the increments it predicts:
// 0 for a response that is exactly second order. Needs at least 5 samples.
struct IdentifiedPlant {
  Transfer plant;
  double misfit = 1.0;
};
IdentifiedPlant identify_second_order(const std::vector<double>& step);

// The poles of the loop u = C e, e = G u + d (the plant's output is the
// controller's input, as the error of a constraint is the controller's input
// and its output moves the error): the roots of den_G den_C - num_G num_C.
std::vector<std::complex<double>> closed_loop_poles(const Transfer& plant,
                                                    const Transfer& controller);

// The largest |z| of `poles` (0 when there are none).
double spectral_radius(const std::vector<std::complex<double>>& poles);

}  // namespace mospec::runtime
