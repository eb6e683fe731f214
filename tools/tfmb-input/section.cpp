#include <cmath>

#include "model_build.hpp"

namespace tfmb::input {

Section rectangle_section(double t, double b, double e, double nu, double rho) {
  Section s;
  s.kind = "rectangle";
  s.youngs_modulus = e;
  s.poisson_ratio = nu;
  s.density = rho;
  const double g = e / (2.0 * (1.0 + nu));
  const double area = b * t;
  const double i_inplane = b * t * t * t / 12.0;   // bending of the flap in the x-y plane
  const double i_depth = t * b * b * b / 12.0;     // bending about the in-plane transverse axis
  // Saint-Venant torsion constant of a rectangle, Roark's Formulas (7th ed.) Table 10.7 case 4:
  // J = a c^3 (1/3 - 0.21 (c/a)(1 - c^4/(12 a^4))) with a >= c the long and short sides.
  const double a = std::max(b, t), c = std::min(b, t);
  const double torsion = a * c * c * c * (1.0 / 3.0 - 0.21 * (c / a) * (1.0 - std::pow(c / a, 4) / 12.0));
  const double shear_factor = 5.0 / 6.0;  // Timoshenko factor of a rectangle (Cowper 1966, nu -> 0)
  // Order: axial, shear 2 (in-plane transverse), shear 3 (depth), torsion, bending about 2
  // (out of plane), bending about 3 (in plane), as the seed's Table 1.
  s.stiffness.diagonal() << e * area, shear_factor * g * area, shear_factor * g * area, g * torsion,
      e * i_depth, e * i_inplane;
  s.mass.diagonal() << rho * area, rho * area, rho * area, rho * (i_inplane + i_depth), rho * i_depth,
      rho * i_inplane;
  return s;
}

}  // namespace tfmb::input
