// Unit tests of the fibre strain and margin formulas.
#include <gtest/gtest.h>

#include "tfmb-strain/fibre_strain.hpp"

using namespace tfmb::strain;

namespace {
SectionInput section(int outer_sign) {
  SectionInput in;
  in.thickness = 0.004;
  in.outer_normal_sign = outer_sign;
  in.axial_stiffness = 2.2e8;
  in.bending_stiffness = 293.0;
  return in;
}
}  // namespace

TEST(FibreStrain, PureTensionIsUniform) {
  SectionInput in = section(1);
  in.axial_strain = 1.2e-3;
  const SectionStrains s = section_strains(in, MechanicalBasis::mechanical);
  EXPECT_DOUBLE_EQ(s.mechanical_inner, 1.2e-3);
  EXPECT_DOUBLE_EQ(s.mechanical_outer, 1.2e-3);
  EXPECT_DOUBLE_EQ(s.total_outer, 1.2e-3);
}

TEST(FibreStrain, PureBendingFollowsTheSignConvention) {
  // kappa3 > 0 turns the section counter-clockwise: fibres on the left (y2 > 0) shorten.
  for (int sign : {1, -1}) {
    SectionInput in = section(sign);
    in.curvature = 0.5;
    const SectionStrains s = section_strains(in, MechanicalBasis::mechanical);
    EXPECT_DOUBLE_EQ(s.mechanical_outer, -sign * 0.002 * 0.5);
    EXPECT_DOUBLE_EQ(s.mechanical_inner, sign * 0.002 * 0.5);
  }
}

TEST(FibreStrain, BasesAgreeForAnElasticBeamWithThermalStrain) {
  // A beam loaded by N, M and a thermal eigenstrain (linear through the thickness here, so no
  // self-equilibrated part): kinematic = mechanical + eigenstrain, forces from the mechanical part.
  SectionInput in = section(-1);
  const double n = 3e4, m = 2.0;
  in.thermal_inner = 1.0e-3;
  in.thermal_outer = 1.4e-3;
  in.thermal_section = 1.2e-3;
  in.thermal_curvature = (in.thermal_outer - in.thermal_inner) / in.thickness;
  const double kappa3_thermal = -in.outer_normal_sign * in.thermal_curvature;
  in.axial_force = n;
  in.bending_moment = m;
  SectionInput mech = in, kin = in;
  mech.axial_strain = n / in.axial_stiffness;
  mech.curvature = m / in.bending_stiffness;
  kin.axial_strain = mech.axial_strain + in.thermal_section;
  kin.curvature = mech.curvature + kappa3_thermal;
  const SectionStrains a = section_strains(mech, MechanicalBasis::mechanical);
  const SectionStrains b = section_strains(kin, MechanicalBasis::kinematic);
  const SectionStrains c = section_strains(in, MechanicalBasis::force);
  // Mechanical fibre strain = N/EA - y2 M/EI at the surfaces (y2 of the outer = -t/2 here).
  const double y_outer = -0.5 * in.thickness;
  EXPECT_NEAR(a.mechanical_outer, mech.axial_strain - y_outer * mech.curvature, 1e-15);
  EXPECT_NEAR(a.mechanical_inner, mech.axial_strain + y_outer * mech.curvature, 1e-15);
  for (const SectionStrains* s : {&b, &c}) {
    EXPECT_NEAR(s->mechanical_inner, a.mechanical_inner, 1e-15);
    EXPECT_NEAR(s->mechanical_outer, a.mechanical_outer, 1e-15);
    EXPECT_NEAR(s->total_outer, a.total_outer, 1e-15);
  }
  EXPECT_NEAR(a.total_outer, a.mechanical_outer + 1.4e-3, 1e-15);
}

TEST(Margin, AllowableOverActualMinusOne) {
  EXPECT_DOUBLE_EQ(margin_of_safety(6e-3, 2e-3), 2.0);
  EXPECT_DOUBLE_EQ(margin_of_safety(6e-3, -3e-3), 1.0);
  EXPECT_DOUBLE_EQ(margin_of_safety(6e-3, 0.0), kMarginCap);
  EXPECT_LT(margin_of_safety(6e-3, 7e-3), 0.0);
}
