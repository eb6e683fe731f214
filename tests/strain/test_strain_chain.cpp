// tfmb-matmap followed by tfmb-strain on a free Ti-6Al-4V flap (committed material database):
// a free beam takes the section's thermal strain and curvature as its kinematic strain and
// carries no force, so
//   - uniform temperature rise: zero mechanical strain, thermal strain alpha_mean(T)(T - T_ref)
//     - alpha_mean(T0)(T0 - T_ref) at both surfaces;
//   - linear through-thickness difference dT: a mechanical strain of minus the self-equilibrated
//     surface residual alpha' dT^2 / 6 at both surfaces, whichever basis (alpha' the slope of
//     alpha_mean in its table segment): eps_th(z) is quadratic, eps = a + b z + c z^2 with
//     c = alpha' (dT/t)^2, the linear profile through the section mean misses c t^2/6 at the
//     surfaces (Boley & Weiner 1960 sec. 9.3).
#include <gtest/gtest.h>

#include <algorithm>
#include <sstream>

#include "tfmb-matmap/material_table.hpp"
#include "tfmb-matmap/run.hpp"
#include "tfmb-strain/run.hpp"
#include "test_files.hpp"

namespace tf = tfmb::testfiles;

namespace {

const std::filesystem::path database = std::filesystem::path(TFMB_SOURCE_DIR) / "data" / "materials-db.h5";
const tfmb::Logger quiet("test", tfmb::Verbosity::quiet);

struct Chain {
  std::filesystem::path dir;
  tfmb::matmap::Result materials;
  tfmb::strain::StrainResult from_mechanical, from_kinematic, from_force;
  Chain(const std::string& name, double temperature, double delta, int outer_sign) {
    dir = tf::temp_dir(name);
    const int elements = 5;
    auto flap = tf::straight_flap("upper", {0.0, 0.1}, 0.2, 0.3, elements + 1, 11);
    if (outer_sign < 0) std::swap(flap.inner_wall, flap.outer_wall);
    tf::write_model(dir / "model.h5", {flap});
    tf::write_thermal(dir / "thermal.h5", {{"upper", {std::vector<double>(elements, temperature),
                                                       std::vector<double>(elements, delta)}}});
    tfmb::matmap::Options mo;
    mo.thermal_file = dir / "thermal.h5";
    mo.model_file = dir / "model.h5";
    mo.database_file = database;
    mo.output = dir / "materials.h5";
    std::ostringstream out;
    materials = tfmb::matmap::run(mo, quiet, out);
    // The free beam: kinematic strain = the section's thermal eigenstrain (in the beam's kappa3
    // convention, materials.md), mechanical strain (what tfmb-beam writes) and forces zero.
    const auto& e = materials.flaps.at(0).elements;
    const int sign = materials.flaps.at(0).outer_normal_sign;
    tf::TestStructureFlap kinematic, mechanical;
    kinematic.name = mechanical.name = "upper";
    kinematic.points = mechanical.points = flap.reference_curve;
    for (int k = 0; k < elements; ++k) {
      kinematic.sectional_strain.push_back({e.thermal_strain[static_cast<std::size_t>(k)], 0, 0, 0, 0,
                                            -sign * e.thermal_curvature[static_cast<std::size_t>(k)]});
      kinematic.sectional_force.push_back({0, 0, 0, 0, 0, 0});
      mechanical.sectional_strain.push_back({0, 0, 0, 0, 0, 0});
      mechanical.sectional_force.push_back({0, 0, 0, 0, 0, 0});
    }
    tf::write_structure(dir / "kinematic.h5", {kinematic});
    tf::write_structure(dir / "mechanical.h5", {mechanical});
    tfmb::strain::Options so;
    so.materials_file = mo.output;
    so.output = dir / "strain.h5";
    so.structure_file = dir / "mechanical.h5";
    from_mechanical = tfmb::strain::run(so, quiet, out);
    so.basis = tfmb::strain::MechanicalBasis::force;
    from_force = tfmb::strain::run(so, quiet, out);
    so.structure_file = dir / "kinematic.h5";
    so.basis = tfmb::strain::MechanicalBasis::kinematic;
    from_kinematic = tfmb::strain::run(so, quiet, out);
  }
};

}  // namespace

TEST(StrainChain, UniformTemperatureRiseOfAFreeFlap) {
  const Chain c("chain-uniform", 640.0, 0.0, 1);
  const auto db = tfmb::matmap::read_material_db(database);
  const auto& ti = *db.find("Ti-6Al-4V");
  const auto& alpha = ti.require("thermal_expansion");
  const double t0 = 293.15, tref = ti.reference_temperature;
  const double expected = tfmb::matmap::evaluate(alpha, 640.0, false).value * (640.0 - tref) -
                          tfmb::matmap::evaluate(alpha, t0, false).value * (t0 - tref);
  for (const auto* r : {&c.from_mechanical, &c.from_kinematic, &c.from_force}) {
    for (const auto& s : r->flaps.at(0).strains) {
      EXPECT_NEAR(s.mechanical_inner, 0.0, 1e-18);
      EXPECT_NEAR(s.mechanical_outer, 0.0, 1e-18);
      EXPECT_NEAR(s.thermal_inner, expected, 1e-15);
      EXPECT_NEAR(s.total_outer, expected, 1e-15);
    }
  }
}

TEST(StrainChain, ThroughThicknessDifferenceLeavesTheSelfEquilibratedResidual) {
  for (int sign : {1, -1}) {
    // 600 K -+ 20 K stays inside one alpha_mean segment of the table (588.7-810.9 K).
    const Chain c("chain-gradient" + std::to_string(sign), 620.0, 40.0, sign);
    EXPECT_EQ(c.materials.flaps.at(0).outer_normal_sign, sign);
    const auto db = tfmb::matmap::read_material_db(database);
    const auto& alpha = db.find("Ti-6Al-4V")->require("thermal_expansion");
    const auto upper = std::upper_bound(alpha.temperature.begin(), alpha.temperature.end(), 620.0);
    const auto i = static_cast<std::size_t>(upper - alpha.temperature.begin());
    const double slope = (alpha.value[i] - alpha.value[i - 1]) / (alpha.temperature[i] - alpha.temperature[i - 1]);
    const double residual = slope * 40.0 * 40.0 / 6.0;
    for (const auto* r : {&c.from_mechanical, &c.from_kinematic, &c.from_force}) {
      for (const auto& s : r->flaps.at(0).strains) {
        // The surfaces expand more than the linear profile: compressed by the residual.
        EXPECT_NEAR(s.mechanical_inner, -residual, 1e-15);
        EXPECT_NEAR(s.mechanical_outer, -residual, 1e-15);
        EXPECT_GT(s.thermal_outer, s.thermal_inner);  // the outer surface is hotter
      }
    }
  }
}
