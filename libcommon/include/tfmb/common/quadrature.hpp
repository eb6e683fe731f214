// Gauss-Legendre rules shared by the stages that integrate along lines (heat's element and
// boundary terms, loads' tractions). Numerics, no physics.
#pragma once

#include <utility>
#include <vector>

namespace tfmb::quadrature {

struct Rule1D {
  std::vector<double> points;   // on [-1, 1], increasing
  std::vector<double> weights;  // sum to 2
};

// n-point Gauss-Legendre rule on [-1, 1], exact for polynomials of degree 2n - 1 (n in 1..20;
// std::invalid_argument otherwise). Abramowitz & Stegun (1964) 25.4.29.
Rule1D gauss_legendre(int n);

// The same rule mapped to [0, 1]: (point, weight) pairs, weights summing to 1.
std::vector<std::pair<double, double>> gauss_legendre_unit(int n);

}  // namespace tfmb::quadrature
