#include "runtime/transfer.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

namespace mospec::runtime {

Polynomial operator+(const Polynomial& a, const Polynomial& b) {
  Polynomial r(std::max(a.size(), b.size()), 0.0);
  for (size_t i = 0; i < a.size(); ++i) r[i] += a[i];
  for (size_t i = 0; i < b.size(); ++i) r[i] += b[i];
  return r;
}

Polynomial operator*(double k, const Polynomial& a) {
  Polynomial r = a;
  for (double& c : r) c *= k;
  return r;
}

Polynomial operator-(const Polynomial& a, const Polynomial& b) {
  return a + (-1.0) * b;
}

Polynomial operator*(const Polynomial& a, const Polynomial& b) {
  if (a.empty() || b.empty()) return {};
  Polynomial r(a.size() + b.size() - 1, 0.0);
  for (size_t i = 0; i < a.size(); ++i)
    for (size_t j = 0; j < b.size(); ++j) r[i + j] += a[i] * b[j];
  return r;
}

std::vector<std::complex<double>> roots(const Polynomial& p) {
  size_t n = p.size();
  while (n > 0 && p[n - 1] == 0.0) --n;
  if (n <= 1) return {};
  const Eigen::Index degree = static_cast<Eigen::Index>(n - 1);
  // The companion matrix of the monic p / p[n-1]: its eigenvalues are p's roots.
  Eigen::MatrixXd companion = Eigen::MatrixXd::Zero(degree, degree);
  for (Eigen::Index i = 1; i < degree; ++i) companion(i, i - 1) = 1.0;
  for (Eigen::Index i = 0; i < degree; ++i)
    companion(i, degree - 1) = -p[static_cast<size_t>(i)] / p[n - 1];
  const Eigen::EigenSolver<Eigen::MatrixXd> solver(companion, false);
  const Eigen::VectorXcd values = solver.eigenvalues();
  return {values.data(), values.data() + values.size()};
}

IdentifiedPlant identify_second_order(const std::vector<double>& step) {
  IdentifiedPlant result;
  if (step.size() < 5) return result;
  std::vector<double> g(step.size(), 0.0);
  for (size_t k = 1; k < step.size(); ++k) g[k] = step[k] - step[k - 1];
  // Normal equations of g_k = a1 g_{k-1} + a2 g_{k-2}, k >= 3.
  double m11 = 0, m12 = 0, m22 = 0, r1 = 0, r2 = 0, gg = 0;
  for (size_t k = 3; k < g.size(); ++k) {
    m11 += g[k - 1] * g[k - 1], m12 += g[k - 1] * g[k - 2], m22 += g[k - 2] * g[k - 2];
    r1 += g[k] * g[k - 1], r2 += g[k] * g[k - 2], gg += g[k] * g[k];
  }
  if (!(gg > 0.0) || !std::isfinite(gg)) return result;
  // Of the recursions that fit equally well when the columns are collinear
  // (an integrator's constant increments fit any a1 + a2 = 1), the one of
  // least norm (the pseudo-inverse): its extra root (z + a2) cancels against
  // the numerator, whichever it is.
  double a1 = 0.0, a2 = 0.0;
  const double mean = (m11 + m22) / 2, spread = std::hypot((m11 - m22) / 2, m12);
  const double large = mean + spread, small = mean - spread;
  if (!(large > 0.0)) return result;
  if (small > 1e-10 * large) {
    const double det = m11 * m22 - m12 * m12;
    a1 = (r1 * m22 - r2 * m12) / det;
    a2 = (m11 * r2 - m12 * r1) / det;
  } else {
    // The eigenvector of the large eigenvalue.
    double v1 = m12, v2 = large - m11;
    if (std::abs(v1) + std::abs(v2) == 0.0) v1 = 1.0, v2 = 0.0;
    const double norm = std::hypot(v1, v2);
    v1 /= norm, v2 /= norm;
    const double along = (v1 * r1 + v2 * r2) / large;
    a1 = along * v1, a2 = along * v2;
  }
  double rr = 0;
  for (size_t k = 3; k < g.size(); ++k) {
    const double r = g[k] - a1 * g[k - 1] - a2 * g[k - 2];
    rr += r * r;
  }
  result.misfit = std::sqrt(rr / gg);
  // g_1 = b1 and g_2 = a1 b1 + b2: the impulse response's first two samples.
  result.plant = {.num = Polynomial{g[2] - a1 * g[1], g[1]}, .den = Polynomial{-a2, -a1, 1.0}};
  return result;
}

std::vector<std::complex<double>> closed_loop_poles(const Transfer& plant,
                                                    const Transfer& controller) {
  return roots(plant.den * controller.den - plant.num * controller.num);
}

double spectral_radius(const std::vector<std::complex<double>>& poles) {
  double r = 0.0;
  for (const std::complex<double>& p : poles) r = std::max(r, std::abs(p));
  return r;
}

}  // namespace mospec::runtime
