#include "tfmb-heat/quadrature.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace tfmb::heat {

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
