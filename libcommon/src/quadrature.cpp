#include "tfmb/common/quadrature.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace tfmb::quadrature {

Rule1D gauss_legendre(int n) {
  if (n < 1 || n > 20)
    throw std::invalid_argument("gauss_legendre: n must be in [1, 20]");
  // Roots of P_n by Newton from the Chebyshev-like guess; weights 2 / ((1 - x^2) P_n'(x)^2).
  // Abramowitz & Stegun (1964) 25.4.29.
  Rule1D rule;
  rule.points.resize(static_cast<std::size_t>(n));
  rule.weights.resize(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    double x = std::cos(std::numbers::pi * (i + 0.75) / (n + 0.5));
    double derivative = 1.0;
    for (int iteration = 0; iteration < 100; ++iteration) {
      double p0 = 1.0, p1 = x;
      for (int k = 2; k <= n; ++k) {
        const double p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      derivative = n * (x * p1 - p0) / (x * x - 1.0);
      const double dx = p1 / derivative;
      x -= dx;
      if (std::abs(dx) < 1e-16)
        break;
    }
    rule.points[static_cast<std::size_t>(n - 1 - i)] = x;
    rule.weights[static_cast<std::size_t>(n - 1 - i)] =
        2.0 / ((1.0 - x * x) * derivative * derivative);
  }
  return rule;
}

std::vector<std::pair<double, double>> gauss_legendre_unit(int n) {
  const Rule1D rule = gauss_legendre(n);
  std::vector<std::pair<double, double>> unit;
  for (std::size_t i = 0; i < rule.points.size(); ++i)
    unit.emplace_back(0.5 * (rule.points[i] + 1.0), 0.5 * rule.weights[i]);
  return unit;
}

}  // namespace tfmb::quadrature
