#include "fibre_strain.hpp"

#include <cmath>

namespace tfmb::strain {

const char* basis_name(MechanicalBasis basis) {
  switch (basis) {
    case MechanicalBasis::strain_minus_thermal: return "strain-minus-thermal";
    case MechanicalBasis::strain: return "strain";
    case MechanicalBasis::force: return "force";
  }
  return "?";
}

double margin_of_safety(double allowable, double strain) {
  const double magnitude = std::abs(strain);
  if (magnitude * kMarginCap <= allowable) return kMarginCap;
  return allowable / magnitude - 1.0;
}

SectionStrains section_strains(const SectionInput& in, MechanicalBasis basis) {
  const double y_outer = in.outer_normal_sign * 0.5 * in.thickness;
  const double y_inner = -y_outer;
  double gamma = in.axial_strain, kappa = in.curvature;
  if (basis == MechanicalBasis::force) {
    gamma = in.axial_force / in.axial_stiffness;
    kappa = in.bending_moment / in.bending_stiffness;
  }
  SectionStrains out;
  out.thermal_inner = in.thermal_inner;
  out.thermal_outer = in.thermal_outer;
  const double fibre_inner = gamma - y_inner * kappa;
  const double fibre_outer = gamma - y_outer * kappa;
  if (basis == MechanicalBasis::strain_minus_thermal) {
    out.mechanical_inner = fibre_inner - in.thermal_inner;
    out.mechanical_outer = fibre_outer - in.thermal_outer;
  } else {
    out.mechanical_inner = fibre_inner;
    out.mechanical_outer = fibre_outer;
  }
  out.total_inner = out.mechanical_inner + out.thermal_inner;
  out.total_outer = out.mechanical_outer + out.thermal_outer;
  return out;
}

}  // namespace tfmb::strain
