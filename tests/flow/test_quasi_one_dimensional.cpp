#include <gtest/gtest.h>

#include <cmath>

#include "mesh_generate.hpp"
#include "tfmb-flow/quasi_one_dimensional.hpp"

using namespace tfmb::flow;

namespace {

// A converging-diverging test nozzle, its height as a function of x in [0, 10]: throat at 5.
double nozzle_height(double x) {
  const double pi = std::acos(-1.0);
  return x < 5.0 ? 1.75 - 0.75 * std::cos((0.2 * x - 1.0) * pi)
                 : 1.25 - 0.25 * std::cos((0.2 * x - 1.0) * pi);
}

// The duct from y = 0 to the nozzle height, with every third cell split into triangles and
// the interior nodes moved off the grid lines.
Mesh nozzle_mesh(int ni, int nj, double jitter) {
  StructuredMeshSpec spec;
  spec.ni = ni;
  spec.nj = nj;
  spec.map = [](double xi, double eta) { return Vec2{10.0 * xi, eta * nozzle_height(10.0 * xi)}; };
  spec.split = [](int i, int j) { return (i + j) % 3 == 0; };
  spec.jitter = jitter;
  return structured_mesh(spec);
}

}  // namespace

TEST(QuasiOneDimensionalNozzle, AreaMachRelationRoundTrip) {
  for (double m : {0.1, 0.5, 0.99, 1.01, 2.0, 3.5}) {
    const double r = area_ratio_of_mach(m, 1.4);
    EXPECT_NEAR(mach_of_area_ratio(r, 1.4, m > 1.0), m, 1e-10);
  }
  // Anderson (2003) table A.1: M = 2, A/A* = 1.688, p/p0 = 0.1278
  EXPECT_NEAR(area_ratio_of_mach(2.0, 1.4), 1.688, 1e-3);
  EXPECT_NEAR(isentropic_pressure_ratio(2.0, 1.4), 0.1278, 1e-4);
  // table A.2: M1 = 2: M2 = 0.5774, p02/p01 = 0.7209
  EXPECT_NEAR(normal_shock_mach(2.0, 1.4), 0.5774, 1e-4);
  EXPECT_NEAR(normal_shock_total_pressure_ratio(2.0, 1.4), 0.7209, 1e-4);
}

TEST(QuasiOneDimensionalNozzle, ShockSolutionMatchesExitPressure) {
  const auto area = nozzle_height;
  const Quasi1dNozzle q(area, 0.0, 5.0, 10.0, 1.4, 0.75);
  ASSERT_TRUE(q.choked());
  ASSERT_TRUE(q.has_shock());
  EXPECT_GT(q.shock_position(), 5.0);
  EXPECT_LT(q.shock_position(), 10.0);
  EXPECT_NEAR(q.pressure_ratio(10.0), 0.75, 1e-9);
  EXPECT_NEAR(q.mach(5.0 - 1e-9), 1.0, 1e-3);
  const Quasi1dNozzle sub(area, 0.0, 5.0, 10.0, 1.4, 0.89);
  EXPECT_FALSE(sub.choked());
  EXPECT_NEAR(sub.pressure_ratio(10.0), 0.89, 1e-9);
  const Quasi1dNozzle sup(area, 0.0, 5.0, 10.0, 1.4, 0.16);
  EXPECT_TRUE(sup.choked());
  EXPECT_FALSE(sup.has_shock());
  EXPECT_NEAR(sup.mach(10.0), mach_of_area_ratio(1.5, 1.4, true), 1e-9);
}

TEST(DuctSections, SumTheCellsCutByEachStation) {
  // A straight channel 0.3 high: whatever the tiling (split cells, moved interior nodes), the
  // cells a station cuts add up to the height, each counted once, also where the station runs
  // along a column of cell edges (45 stations: x = (2k + 1) / 45, on the lines x = m / 15 for
  // k = 1, 4, 7, ...).
  for (const double jitter : {0.0, 0.3}) {
    StructuredMeshSpec spec;
    spec.ni = 31;
    spec.nj = 9;
    spec.map = [](double xi, double eta) { return Vec2{2.0 * xi, 0.3 * eta}; };
    spec.split = [](int i, int j) { return (i * j) % 2 == 1; };
    spec.jitter = jitter;
    const Mesh channel = structured_mesh(spec);
    const DuctSections planar = duct_sections(channel, Geometry::planar, 45);
    ASSERT_EQ(planar.x.size(), 45u);
    for (std::size_t k = 0; k < planar.x.size(); ++k)
      EXPECT_NEAR(planar.area[k], 0.3, 1e-12) << "station " << k;
    // about the axis y = 0 the same cells sweep a disc of radius 0.3
    const DuctSections disc = duct_sections(channel, Geometry::axisymmetric, 45);
    for (double a : disc.area)
      EXPECT_NEAR(a, std::acos(-1.0) * 0.09, 1e-12);
  }

  // The nozzle: sections follow the wall height to the error of its piecewise-linear mesh wall.
  const Mesh nozzle = nozzle_mesh(101, 11, 0.2);
  const DuctSections d = duct_sections(nozzle, Geometry::planar, 400);
  double worst = 0.0;
  for (std::size_t k = 0; k < d.x.size(); ++k)
    worst = std::max(worst, std::abs(d.area[k] - nozzle_height(d.x[k])) / nozzle_height(d.x[k]));
  EXPECT_LT(worst, 1e-3);
  EXPECT_GT(worst, 0.0);  // (the mesh wall is not the curve)
  EXPECT_NEAR(d.area_at(-1.0), d.area.front(), 0.0);
  EXPECT_NEAR(d.area_at(11.0), d.area.back(), 0.0);
}

TEST(QuasiOneDimensionalStart, PlacesTheThroatAndTheShockOfTheDuct) {
  const PerfectGas gas{1.4, 287.05};
  const double p0 = 1e5, t0 = 300.0;
  const Mesh mesh = nozzle_mesh(201, 11, 0.0);
  const Quasi1dStart start =
      quasi_one_dimensional_start(mesh, Geometry::planar, gas, p0, t0, 0.75 * p0);
  const Quasi1dNozzle exact(nozzle_height, 0.0, 5.0, 10.0, 1.4, 0.75);
  ASSERT_TRUE(start.choked);
  ASSERT_TRUE(start.has_shock);
  const double cell = 10.0 / 200;
  EXPECT_NEAR(start.throat_x, 5.0, cell);
  EXPECT_NEAR(start.shock_x, exact.shock_position(), cell);
  ASSERT_EQ(start.states.size(), mesh.points.size());
  for (std::size_t n = 0; n < mesh.points.size(); ++n) {
    const State& w = start.states[n];
    const double x = mesh.points[n].x;
    // the exit holds the outflow pressure; the total temperature is the inflow's everywhere
    if (x == 10.0) {
      EXPECT_NEAR(w[3], 0.75 * p0, 1e-3 * p0);
    }
    const double t = w[3] / (w[0] * gas.R);
    EXPECT_NEAR(t + 0.5 * w[1] * w[1] / gas.cp(), t0, 1e-9 * t0);
    EXPECT_EQ(w[2], 0.0);
    // the mass flow of every section is the choked throat's, upstream of the shock and behind it
    EXPECT_NEAR(w[0] * w[1] * nozzle_height(x), exact.mass_flow(p0, t0, gas.R),
                2e-3 * exact.mass_flow(p0, t0, gas.R))
        << "x = " << x;
  }
  EXPECT_NE(start.summary().find("normal shock"), std::string::npos);

  // below the exit pressure of the shock at the exit: supersonic to the exit; above the
  // subsonic branch's: not choked, the exit at the outflow pressure
  const Quasi1dStart supersonic =
      quasi_one_dimensional_start(mesh, Geometry::planar, gas, p0, t0, 0.16 * p0);
  EXPECT_TRUE(supersonic.choked);
  EXPECT_FALSE(supersonic.has_shock);
  const Quasi1dStart subsonic =
      quasi_one_dimensional_start(mesh, Geometry::planar, gas, p0, t0, 0.89 * p0);
  EXPECT_FALSE(subsonic.choked);
  for (std::size_t n = 0; n < mesh.points.size(); ++n)
    if (mesh.points[n].x == 10.0) {
      EXPECT_NEAR(subsonic.states[n][3], 0.89 * p0, 1e-3 * p0);
    }
}
