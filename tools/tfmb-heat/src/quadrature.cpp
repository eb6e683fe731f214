#include "tfmb/heat/quadrature.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace tfmb::heat {

QuadratureRule1D gauss_legendre(int n) {
  if (n < 1 || n > 20) throw std::invalid_argument("gauss_legendre: n must be in [1, 20]");
  // Roots of P_n by Newton from the Chebyshev-like guess; weights 2 / ((1 - x^2) P_n'(x)^2).
  // Abramowitz & Stegun (1964) 25.4.29.
  QuadratureRule1D rule;
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
      if (std::abs(dx) < 1e-16) break;
    }
    rule.points[static_cast<std::size_t>(n - 1 - i)] = x;
    rule.weights[static_cast<std::size_t>(n - 1 - i)] = 2.0 / ((1.0 - x * x) * derivative * derivative);
  }
  return rule;
}

QuadratureRule2D quad_gauss(int n) {
  const auto line = gauss_legendre(n);
  QuadratureRule2D rule;
  for (std::size_t j = 0; j < line.points.size(); ++j) {
    for (std::size_t i = 0; i < line.points.size(); ++i) {
      rule.points.push_back({line.points[i], line.points[j]});
      rule.weights.push_back(line.weights[i] * line.weights[j]);
    }
  }
  return rule;
}

namespace {
// Adds the three permutations of the area coordinates (a, a, 1 - 2a).
void add_orbit3(QuadratureRule2D& rule, double a, double weight) {
  const double b = 1.0 - 2.0 * a;
  rule.points.push_back({a, a});
  rule.points.push_back({b, a});
  rule.points.push_back({a, b});
  for (int k = 0; k < 3; ++k) rule.weights.push_back(0.5 * weight);
}
}  // namespace

QuadratureRule2D triangle_rule(int degree) {
  QuadratureRule2D rule;
  if (degree <= 1) {
    rule.points.push_back({1.0 / 3.0, 1.0 / 3.0});
    rule.weights.push_back(0.5);
  } else if (degree == 2) {
    add_orbit3(rule, 1.0 / 6.0, 1.0 / 3.0);
  } else if (degree <= 4) {
    // Dunavant (1985) rule of degree 4, 6 points.
    add_orbit3(rule, 0.445948490915965, 0.223381589678011);
    add_orbit3(rule, 0.091576213509771, 0.109951743655322);
  } else if (degree == 5) {
    // Dunavant (1985) rule of degree 5, 7 points.
    rule.points.push_back({1.0 / 3.0, 1.0 / 3.0});
    rule.weights.push_back(0.5 * 0.225);
    add_orbit3(rule, 0.470142064105115, 0.132394152788506);
    add_orbit3(rule, 0.101286507323456, 0.125939180544827);
  } else {
    throw std::invalid_argument("triangle_rule: degree above 5 is not tabulated");
  }
  return rule;
}

QuadratureRule2D stiffness_rule(ElementType type) {
  switch (type) {
    case ElementType::tri3: return triangle_rule(2);
    case ElementType::quad4: return quad_gauss(2);
    case ElementType::tri6: return triangle_rule(4);
    case ElementType::quad8:
    case ElementType::quad9: return quad_gauss(3);
  }
  throw std::logic_error("stiffness_rule: unknown element type");
}

QuadratureRule2D accurate_rule(ElementType type) {
  return is_triangle(type) ? triangle_rule(5) : quad_gauss(5);
}

}  // namespace tfmb::heat
