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
  const SectionStrains s = section_strains(in, MechanicalBasis::strain);
  EXPECT_DOUBLE_EQ(s.mechanical_inner, 1.2e-3);
  EXPECT_DOUBLE_EQ(s.mechanical_outer, 1.2e-3);
  EXPECT_DOUBLE_EQ(s.total_outer, 1.2e-3);
}

TEST(FibreStrain, PureBendingFollowsTheSignConvention) {
  // kappa3 > 0 turns the section counter-clockwise: fibres on the left (y2 > 0) shorten.
  for (int sign : {1, -1}) {
    SectionInput in = section(sign);
    in.curvature = 0.5;
    const SectionStrains s = section_strains(in, MechanicalBasis::strain);
    EXPECT_DOUBLE_EQ(s.mechanical_outer, -sign * 0.002 * 0.5);
    EXPECT_DOUBLE_EQ(s.mechanical_inner, sign * 0.002 * 0.5);
  }
}

TEST(FibreStrain, BasesAgreeForAnElasticBeamWithThermalStrain) {
  // A beam loaded by N, M and a linear thermal strain: kinematic strain = mechanical + thermal.
  SectionInput in = section(-1);
  const double n = 3e4, m = 2.0;
  const double th_in = 1.0e-3, th_out = 1.4e-3;  // thermal curvature 0.1 /m towards outer
  const double kappa_th = -in.outer_normal_sign * (th_out - th_in) / in.thickness;  // in kappa3
  in.axial_force = n;
  in.bending_moment = m;
  in.axial_strain = n / in.axial_stiffness + 0.5 * (th_in + th_out);
  in.curvature = m / in.bending_stiffness + kappa_th;
  in.thermal_inner = th_in;
  in.thermal_outer = th_out;
  const SectionStrains a = section_strains(in, MechanicalBasis::strain_minus_thermal);
  const SectionStrains b = section_strains(in, MechanicalBasis::force);
  EXPECT_NEAR(a.mechanical_inner, b.mechanical_inner, 1e-15);
  EXPECT_NEAR(a.mechanical_outer, b.mechanical_outer, 1e-15);
  EXPECT_NEAR(a.total_outer, b.total_outer, 1e-15);
}

TEST(Margin, AllowableOverActualMinusOne) {
  EXPECT_DOUBLE_EQ(margin_of_safety(6e-3, 2e-3), 2.0);
  EXPECT_DOUBLE_EQ(margin_of_safety(6e-3, -3e-3), 1.0);
  EXPECT_DOUBLE_EQ(margin_of_safety(6e-3, 0.0), kMarginCap);
  EXPECT_LT(margin_of_safety(6e-3, 7e-3), 0.0);
}
