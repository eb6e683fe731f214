#include "section.hpp"

#include <algorithm>
#include <cmath>

namespace tfmb::matmap {

double RectangleSection::torsion_constant() const {
  const double a = std::max(thickness, width);  // long side
  const double b = std::min(thickness, width);  // short side
  const double r = b / a;
  return a * b * b * b * (1.0 / 3.0 - 0.21 * r * (1.0 - std::pow(r, 4) / 12.0));
}

double shear_coefficient(double nu) { return 10.0 * (1.0 + nu) / (12.0 + 11.0 * nu); }

Matrix6 section_stiffness(const RectangleSection& s, double e, double g, double nu) {
  Matrix6 k = Matrix6::Zero();
  const double ks = shear_coefficient(nu);
  k(0, 0) = e * s.area();
  k(1, 1) = ks * g * s.area();
  k(2, 2) = ks * g * s.area();
  k(3, 3) = g * s.torsion_constant();
  k(4, 4) = e * s.out_of_plane_inertia();
  k(5, 5) = e * s.in_plane_inertia();
  return k;
}

Matrix6 section_mass(const RectangleSection& s, double rho) {
  Matrix6 m = Matrix6::Zero();
  m(0, 0) = m(1, 1) = m(2, 2) = rho * s.area();
  m(3, 3) = rho * (s.out_of_plane_inertia() + s.in_plane_inertia());
  m(4, 4) = rho * s.out_of_plane_inertia();
  m(5, 5) = rho * s.in_plane_inertia();
  return m;
}

}  // namespace tfmb::matmap
