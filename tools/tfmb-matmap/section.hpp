// Sectional stiffness and mass of a solid rectangle (thickness t in the plane of the nozzle,
// width w along the depth), about its centroid, in the 6x6 order of formats/model.md: axial,
// shear 2 (in-plane), shear 3, torsion, bending 2 (out of plane), bending 3 (in plane).
//
//   A = t w,  I3 = w t^3 / 12 (in-plane bending),  I2 = t w^3 / 12,
//   J = w t^3 (1/3 - 0.21 (t/w) (1 - (t/w)^4 / 12))  for w >= t (Roark's Formulas for Stress
//       and Strain, 7th ed., Table 10.7 case 4; t and w swapped if t > w),
//   shear coefficient k = 10 (1 + nu) / (12 + 11 nu) (Cowper, J. Appl. Mech. 33 (1966), Table 1),
//   stiffness diag(E A, k G A, k G A, G J, E I2, E I3),
//   mass diag(rho A, rho A, rho A, rho (I2 + I3), rho I2, rho I3) (Hodges, Nonlinear Composite
//   Beam Theory, 2006, sec. 5.5: mass per length and mass moments of inertia per length).
#pragma once

#include <Eigen/Core>

namespace tfmb::matmap {

using Matrix6 = Eigen::Matrix<double, 6, 6>;

struct RectangleSection {
  double thickness = 0.0;  // t [m]
  double width = 0.0;      // w [m]
  double area() const { return thickness * width; }
  double in_plane_inertia() const { return width * thickness * thickness * thickness / 12.0; }
  double out_of_plane_inertia() const { return thickness * width * width * width / 12.0; }
  double torsion_constant() const;
};

double shear_coefficient(double poisson_ratio);
Matrix6 section_stiffness(const RectangleSection& section, double youngs_modulus, double shear_modulus,
                          double poisson_ratio);
Matrix6 section_mass(const RectangleSection& section, double density);

}  // namespace tfmb::matmap
