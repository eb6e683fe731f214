// Laminar pipe flow, axisymmetric Navier-Stokes (hoop stress and r-weighted fluxes): far
// enough from the inlet the velocity profile is the Hagen-Poiseuille parabola
// u/u_axis = 1 - (r/R)^2 and the pressure gradient is dp/dx = -8 mu U_bulk / R^2 (White 2006,
// eqs. 3-52, 3-55). Re_D about 12, Mach about 0.02, constant viscosity; the slow density change
// along the pipe is allowed for by using the local bulk velocity. Tolerances: profile 2 % of
// u_axis, pressure gradient 3 %.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "mesh_generate.hpp"
#include "tfmb-flow/solver.hpp"

using namespace tfmb::flow;

TEST(PipePoiseuille, AxisymmetricLaminarProfileAndPressureGradient) {
  const int ni = 81, nj = 21;
  const double radius = 0.01, length = 0.2, mu = 0.0158;
  StructuredMeshSpec spec;
  spec.ni = ni;
  spec.nj = nj;
  spec.map = [&](double xi, double eta) { return Vec2{length * xi, radius * eta}; };
  spec.split = [](int i, int j) { return j < 8 && (i + j) % 2 == 0; };  // triangles near the axis
  spec.bottom = "axis";
  spec.right = "outlet";
  spec.top = "wall";
  spec.left = "inlet";
  const PerfectGas gas{1.4, 287.05};
  BoundaryCondition axis, out, wall, in;
  axis.kind = BcKind::symmetry;
  out.kind = BcKind::pressure_outflow;
  out.static_pressure = 1.0e5;
  wall.kind = BcKind::wall_adiabatic;
  in.kind = BcKind::stagnation_inflow;
  in.total_pressure = 1.02e5;
  in.total_temperature = 300.0;
  SolverSettings s;
  s.viscous = true;
  s.viscosity.constant_mu = mu;
  s.limiter = false;
  s.max_iterations = 400;
  s.reference_state = {1.2, 350.0, 350.0, 1.0e5};
  FlowSolver solver(structured_mesh(spec), Geometry::axisymmetric, gas, {axis, out, wall, in}, s);
  solver.set_uniform({1.17, 5.0, 0.0, 1.01e5});
  const SolveReport r = solver.solve();
  std::printf("pipe: %d iterations, %ld linear, %.2f s, drop %.1e\n", r.iterations, r.linear_iterations,
              r.wall_time, r.residual_drop);
  ASSERT_TRUE(r.converged);
  const auto w = solver.primitive();
  const auto& x = solver.node_coords();
  auto node = [&](int i, int j) { return j * ni + i; };
  const int i0 = 56;  // x = 0.14 m = 7 diameters
  // profile and bulk velocity at column i0 (trapezoidal rule in r dr)
  const double u_axis = w[node(i0, 0)][1];
  double profile_error = 0.0, flux = 0.0, area = 0.0;
  for (int j = 0; j < nj; ++j) {
    const double rr = x[node(i0, j)].y / radius;
    profile_error = std::max(profile_error, std::abs(w[node(i0, j)][1] / u_axis - (1.0 - rr * rr)));
    if (j + 1 < nj) {
      const double r0 = x[node(i0, j)].y, r1 = x[node(i0, j + 1)].y;
      flux += 0.5 * (w[node(i0, j)][1] * r0 + w[node(i0, j + 1)][1] * r1) * (r1 - r0);
      area += 0.5 * (r0 + r1) * (r1 - r0);
    }
  }
  const double u_bulk = flux / area;
  const double dpdx = (w[node(i0 + 1, 0)][3] - w[node(i0 - 1, 0)][3]) / (x[node(i0 + 1, 0)].x - x[node(i0 - 1, 0)].x);
  const double dpdx_exact = -8.0 * mu * u_bulk / (radius * radius);
  std::printf("  u_axis %.3f m/s, u_bulk %.3f m/s (ratio %.4f, exact 2), Re_D %.1f\n", u_axis, u_bulk,
              u_axis / u_bulk, w[node(i0, 0)][0] * u_bulk * 2.0 * radius / mu);
  std::printf("  profile error %.2f %% of u_axis; dp/dx %.1f Pa/m, Hagen-Poiseuille %.1f (%.2f %%)\n",
              100.0 * profile_error, dpdx, dpdx_exact, 100.0 * (dpdx - dpdx_exact) / dpdx_exact);
  EXPECT_LT(profile_error, 0.02);
  EXPECT_NEAR(dpdx / dpdx_exact, 1.0, 0.03);
}
