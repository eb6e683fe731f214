// Laminar flat plate at Mach 0.2, Re_L = 1e4, constant viscosity, adiabatic wall, against the
// Blasius skin friction Cf = 0.664 / sqrt(Re_x) (Schlichting and Gersten 2017, eq. 6.59).
// The plate starts at x = 0 behind a symmetry plane; Cf is checked on 0.2 <= x <= 0.9, away
// from the leading-edge singularity and the outflow. Tolerance 2 % (issue 4). The domain is
// 1.5 high so the displacement of the free stream (the pressure gradient it induces) stays small.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "mesh_generate.hpp"
#include "tfmb-flow/solver.hpp"

using namespace tfmb::flow;

namespace {

constexpr int kNi = 81, kNj = 49, kLeadingEdge = 16;  // node column at x = 0
constexpr double kBeta = 3.0, kHeight = 1.5, kBetaY = 7.5;

double x_of(double xi) {
  const double xi0 = static_cast<double>(kLeadingEdge) / (kNi - 1);
  return std::sinh(kBeta * (xi - xi0)) / std::sinh(kBeta * (1.0 - xi0));
}

Mesh plate_mesh() {
  StructuredMeshSpec spec;
  spec.ni = kNi;
  spec.nj = kNj;
  spec.map = [](double xi, double eta) {
    return Vec2{x_of(xi), kHeight * (std::exp(kBetaY * eta) - 1.0) / (std::exp(kBetaY) - 1.0)};
  };
  spec.split = [](int i, int j) { return j > 28 && (i + j) % 2 == 0; };  // triangles away from the wall
  Mesh mesh = structured_mesh(spec);
  // split the bottom into the symmetry plane upstream and the plate
  BoundaryCurve sym{"symmetry", {}}, plate{"plate", {}};
  for (const auto& e : mesh.boundaries[0].edges) {
    (mesh.points[e[0]].x < -1e-12 ? sym : plate).edges.push_back(e);
  }
  mesh.boundaries[0] = plate;
  mesh.boundaries.push_back(sym);
  return mesh;
}

}  // namespace

TEST(LaminarFlatPlate, BlasiusSkinFriction) {
  const PerfectGas gas{1.4, 287.05};
  const double t = 300.0, p = 1.0e5, mach = 0.2, re_l = 1.0e4;
  const double rho = p / (gas.R * t);
  const double u = mach * std::sqrt(gas.gamma * gas.R * t);
  const State w_inf{rho, u, 0.0, p};
  SolverSettings s;
  s.viscous = true;
  s.viscosity.constant_mu = rho * u * 1.0 / re_l;
  s.reference_state = {rho, u, u, p};
  s.max_iterations = 400;
  // A smooth, shock-free verification of the viscous fluxes: no limiter. (With the default
  // Venkatakrishnan-Wang limiter the Cf error on this mesh is about 2.7 %.)
  s.limiter = false;
  BoundaryCondition wall, far, out, sym, in;
  in.kind = BcKind::stagnation_inflow;
  in.total_temperature = t * (1.0 + 0.2 * mach * mach);
  in.total_pressure = p * std::pow(1.0 + 0.2 * mach * mach, 3.5);
  wall.kind = BcKind::wall_adiabatic;
  far.kind = BcKind::farfield;
  far.freestream = w_inf;
  out.kind = BcKind::pressure_outflow;
  out.static_pressure = p;
  sym.kind = BcKind::symmetry;
  // curves: plate, right, top, left, symmetry
  FlowSolver solver(plate_mesh(), Geometry::planar, gas, {wall, out, far, in, sym}, s);
  solver.set_uniform(w_inf);
  const SolveReport r = solver.solve();
  std::printf("flat plate: %d iterations, %ld linear, %.2f s, drop %.1e\n", r.iterations, r.linear_iterations,
              r.wall_time, r.residual_drop);
  ASSERT_TRUE(r.converged);
  const WallTrace trace = solver.wall_trace(0);
  double worst = 0.0;
  for (std::size_t k = 0; k < trace.x.size(); ++k) {
    const double x = trace.x[k];
    if (x < 0.2 || x > 0.9) continue;
    const double cf = trace.shear_stress[k] / (0.5 * rho * u * u);
    const double blasius = 0.664 / std::sqrt(re_l * x);
    worst = std::max(worst, std::abs(cf - blasius) / blasius);
    std::printf("  x %.3f Cf %.5f Blasius %.5f (%.2f %%) p %.1f\n", x, cf, blasius, 100.0 * (cf - blasius) / blasius, trace.pressure[k]);
  }
  std::printf("  worst Cf error on 0.2 <= x <= 0.9: %.2f %%\n", 100.0 * worst);
  EXPECT_LT(worst, 0.02);
}
