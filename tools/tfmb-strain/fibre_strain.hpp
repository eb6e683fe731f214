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
// Mechanical strain, three ways of obtaining it from the beam solution:
//   strain_minus_thermal: the beam's sectional strain is its kinematic strain, which includes
//     the free thermal expansion (the beam was loaded with the thermal strains of
//     materials.h5): mechanical = kinematic - thermal, fibre by fibre;
//   strain: the beam's sectional strain is purely mechanical (the beam ignored temperature,
//     as in the seed): mechanical = sectional strain;
//   force: from the sectional forces and the section stiffness at temperature,
//     gamma11 = N / EA, kappa3 = M3 / EI3 (independent of how the beam treated temperature).
// Total = mechanical + thermal (the seed's total strain module).
//
// Margin of safety (Bruhn, Analysis and Design of Flight Vehicle Structures, 1973):
//   MS = allowable / |strain| - 1, capped at kMarginCap where the strain vanishes.
#pragma once

#include <string>

namespace tfmb::strain {

enum class MechanicalBasis { strain_minus_thermal, strain, force };
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
};

SectionStrains section_strains(const SectionInput& in, MechanicalBasis basis);

}  // namespace tfmb::strain
