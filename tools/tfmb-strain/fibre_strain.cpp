#include "fibre_strain.hpp"

#include <cmath>

namespace tfmb::strain {

const char* basis_name(MechanicalBasis basis) {
  switch (basis) {
    case MechanicalBasis::mechanical: return "mechanical";
    case MechanicalBasis::kinematic: return "kinematic";
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
  // The section's thermal eigenstrain in the beam's convention (materials.md).
  const double kappa3_thermal = -in.outer_normal_sign * in.thermal_curvature;
  double gamma = in.axial_strain, kappa = in.curvature;  // kinematic
  if (basis == MechanicalBasis::mechanical) {
    gamma += in.thermal_section;
    kappa += kappa3_thermal;
  } else if (basis == MechanicalBasis::force) {
    gamma = in.axial_force / in.axial_stiffness + in.thermal_section;
    kappa = in.bending_moment / in.bending_stiffness + kappa3_thermal;
  }
  SectionStrains out;
  out.thermal_inner = in.thermal_inner;
  out.thermal_outer = in.thermal_outer;
  out.total_inner = gamma - y_inner * kappa;
  out.total_outer = gamma - y_outer * kappa;
  out.mechanical_inner = out.total_inner - in.thermal_inner;
  out.mechanical_outer = out.total_outer - in.thermal_outer;
  return out;
}

}  // namespace tfmb::strain
