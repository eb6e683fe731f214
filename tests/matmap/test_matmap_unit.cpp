// Unit tests of tfmb-matmap: table interpolation, sections, thermal strain.
#include <gtest/gtest.h>

#include <cmath>

#include "tfmb-matmap/material_table.hpp"
#include "tfmb-matmap/section.hpp"
#include "tfmb-matmap/thermal_strain.hpp"

using namespace tfmb::matmap;

namespace {
PropertyTable table() {
  PropertyTable t;
  t.name = "youngs_modulus";
  t.units = "Pa";
  t.temperature = {300.0, 400.0, 650.0};
  t.value = {1.1e11, 1.0e11, 0.8e11};
  return t;
}
}  // namespace

TEST(MaterialTable, ExactAtTablePointsAndLinearBetween) {
  const PropertyTable t = table();
  for (std::size_t i = 0; i < t.temperature.size(); ++i) {
    const Evaluation e = evaluate(t, t.temperature[i], false);
    EXPECT_EQ(e.value, t.value[i]);  // bitwise: table points are returned as stored
    EXPECT_FALSE(e.clamped);
  }
  EXPECT_NEAR(evaluate(t, 350.0, false).value, 1.05e11, 1e-4);
  EXPECT_NEAR(evaluate(t, 400.0 + 250.0 * 0.3, false).value, 1.0e11 - 0.3 * 0.2e11, 1e-4);
}

TEST(MaterialTable, RefusesOutsideTheTableUnlessClamped) {
  const PropertyTable t = table();
  EXPECT_THROW(evaluate(t, 299.0, false), OutsideTable);
  EXPECT_THROW(evaluate(t, 650.5, false), OutsideTable);
  const Evaluation low = evaluate(t, 250.0, true);
  EXPECT_TRUE(low.clamped);
  EXPECT_EQ(low.value, 1.1e11);
  const Evaluation high = evaluate(t, 900.0, true);
  EXPECT_TRUE(high.clamped);
  EXPECT_EQ(high.value, 0.8e11);
  try {
    evaluate(t, 700.0, false);
  } catch (const OutsideTable& e) {
    EXPECT_NE(std::string(e.what()).find("[300, 650]"), std::string::npos) << e.what();
  }
}

TEST(MaterialTable, FindsMaterialsByAlias) {
  MaterialDatabase db;
  Material m;
  m.name = "Ti-6Al-4V";
  m.aliases = {"ti64", "titanium"};
  db.materials.push_back(m);
  EXPECT_NE(db.find("ti-6al-4v"), nullptr);
  EXPECT_NE(db.find("Titanium"), nullptr);
  EXPECT_NE(db.find("TI_64"), nullptr);
  EXPECT_EQ(db.find("steel"), nullptr);
}

TEST(Section, RectangleStiffnessAndMass) {
  const RectangleSection s{0.004, 0.5};
  const Matrix6 k = section_stiffness(s, 1.1e11, 4.2e10, 0.31);
  EXPECT_NEAR(k(0, 0), 1.1e11 * 0.002, 1e-3);
  EXPECT_NEAR(k(5, 5), 1.1e11 * 0.5 * std::pow(0.004, 3) / 12.0, 1e-9);
  EXPECT_NEAR(k(4, 4), 1.1e11 * 0.004 * std::pow(0.5, 3) / 12.0, 1e-3);
  // Thin strip: J -> w t^3 / 3 (1 - 0.63 t / w).
  EXPECT_NEAR(s.torsion_constant() / (0.5 * std::pow(0.004, 3) / 3.0), 1.0 - 0.63 * 0.008, 1e-6);
  EXPECT_NEAR(shear_coefficient(0.3), 10.0 * 1.3 / 15.3, 1e-15);
  const Matrix6 m = section_mass(s, 4420.0);
  EXPECT_NEAR(m(0, 0), 4420.0 * 0.002, 1e-12);
  EXPECT_NEAR(m(3, 3), m(4, 4) + m(5, 5), 1e-15);
}

TEST(ThermalStrain, MeanCoefficientConvention) {
  // alpha_mean(T) (T - Tref) relative to the reference; shifted by the strain at T0 otherwise.
  EXPECT_NEAR(thermal_strain(9.5e-6, 800.0, 9.0e-6, 273.15, 273.15), 9.5e-6 * 526.85, 1e-18);
  EXPECT_NEAR(thermal_strain(9.5e-6, 800.0, 9.0e-6, 300.0, 273.15), 9.5e-6 * 526.85 - 9.0e-6 * 26.85, 1e-18);
  EXPECT_NEAR(thermal_curvature(2e-3, 1e-3, 0.004), 0.25, 1e-15);
}
