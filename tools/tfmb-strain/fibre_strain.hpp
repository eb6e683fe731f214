// Fibre strains of a planar beam section and margins of safety.
//
// Beam strain at a fibre a distance y2 from the reference line along e2 (the left normal of
// the reference direction), in-plane bending only:
//   eps(y2) = gamma11 - y2 kappa3
// (Hodges, Nonlinear Composite Beam Theory, 2006, eq. 4.43 with x3 = 0; kappa3 > 0 turns the
// section counter-clockwise, compressing the left fibres). The inner and outer surfaces of a
// section of thickness t centred on the reference line are at y2 = -+ s t/2, s the side of the
// outer wall (+1: left).
//
// The fibre's mechanical strain is its kinematic strain minus its free thermal expansion:
//   mech(y2) = eps_kin(y2) - eps_th,fibre
// with eps_th,fibre the free thermal strain at that surface (materials.h5
// thermal_strain_inner/outer). The beam's kinematic strain is obtained, by `basis`, from
//   mechanical (default; what tfmb-beam writes): the sectional strain is mechanical, the
//     kinematic strain minus the section's thermal eigenstrain (thermal_strain, and
//     kappa3_th = -outer_normal_sign thermal_curvature), so eps_kin = sectional + eigenstrain;
//     a beam run without thermal loads (the seed) fits here too;
//   kinematic: the sectional strain is the kinematic strain itself;
//   force: eps_kin = N / EA + thermal_strain, kappa3 = M3 / EI3 + kappa3_th (the elastic law
//     with the section stiffness at temperature).
// For an elastic beam all three agree. Because eps_th,fibre is the exact free expansion and the
// beam's eigenstrain only its linear part, the mechanical fibre strain includes the
// self-equilibrated thermal strain a beam cannot carry (Boley & Weiner, Theory of Thermal
// Stresses, 1960, sec. 9.3). Total = mechanical + thermal = kinematic.
//
// Margin of safety (Bruhn, Analysis and Design of Flight Vehicle Structures, 1973):
//   MS = allowable / |strain| - 1, capped at kMarginCap where the strain vanishes.
#pragma once

#include <string>

namespace tfmb::strain {

enum class MechanicalBasis { mechanical, kinematic, force };
const char* basis_name(MechanicalBasis basis);

inline constexpr double kMarginCap = 1e6;

double margin_of_safety(double allowable, double strain);

struct SectionStrains {
  double mechanical_inner = 0.0, mechanical_outer = 0.0;
  double thermal_inner = 0.0, thermal_outer = 0.0;
  double total_inner = 0.0, total_outer = 0.0;
};

struct SectionInput {
  double axial_strain = 0.0;     // gamma11 from the beam [1]
  double curvature = 0.0;        // kappa3 from the beam [1/m]
  double axial_force = 0.0;      // N [N]
  double bending_moment = 0.0;   // M3 [N m]
  double axial_stiffness = 0.0;  // EA [N]
  double bending_stiffness = 0.0;  // EI3 [N m^2]
  double thickness = 0.0;        // t [m]
  int outer_normal_sign = 1;     // +1: the outer surface is at y2 = +t/2
  double thermal_inner = 0.0, thermal_outer = 0.0;  // free thermal strain at the surfaces
  double thermal_section = 0.0;    // the section's axial thermal eigenstrain [1]
  double thermal_curvature = 0.0;  // per unit distance towards the outer surface [1/m]
};

SectionStrains section_strains(const SectionInput& in, MechanicalBasis basis);

}  // namespace tfmb::strain
