// Axisymmetric inviscid verification with an exact solution: supersonic source flow in a 15 deg
// cone (the flow a conical nozzle approaches downstream of its throat region; Back, Massier and
// Gier's nozzle diverges at 15 deg). Between the spheres R = 1 and R = 2 about the cone's apex
// the flow is radial and isentropic, its Mach number fixed by the area law A/A* = (R/R*)^2
// (quasi-one-dimensional, exact here because the spherical caps are the stream surfaces'
// normals; Anderson, Modern Compressible Flow, eq. 5.20). Mach 2 at R = 1. The axis is the
// symmetry boundary, the cone a slip wall, both spherical faces far fields with the exact state.
// Second order, no limiter, three nested mixed meshes: observed order of the density error, and
// the largest wall-pressure error on the finest mesh.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "exact_solution_run.hpp"
#include "mesh_generate.hpp"
#include "tfmb-flow/solver.hpp"

using namespace tfmb::flow;

namespace {

const PerfectGas kGas{1.4, 1.0};  // non-dimensional: rho0 = 1, c0 = 1 (stagnation state)
constexpr double kMachInner = 2.0;
constexpr double kRadiusOuter = 2.0;
constexpr double kConeDeg = 15.0;

// A/A* of isentropic flow at Mach m (Anderson, eq. 5.20).
double area_ratio(double m) {
  const double g = kGas.gamma;
  return std::pow(2.0 / (g + 1.0) * (1.0 + 0.5 * (g - 1.0) * m * m), 0.5 * (g + 1.0) / (g - 1.0)) /
         m;
}

// Supersonic root of area_ratio(m) = a by bisection (area_ratio grows with m above 1).
double supersonic_mach(double a) {
  double lo = 1.0, hi = 20.0;
  for (int k = 0; k < 200; ++k) {
    const double mid = 0.5 * (lo + hi);
    (area_ratio(mid) < a ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

State exact(Vec2 x) {
  const double g = kGas.gamma;
  const double radius = std::hypot(x.x, x.y);
  const double m = supersonic_mach(area_ratio(kMachInner) * radius * radius);
  const double t = 1.0 / (1.0 + 0.5 * (g - 1.0) * m * m);  // T/T0
  const double rho = std::pow(t, 1.0 / (g - 1.0));
  const double p = rho * t / g;  // p0 = rho0 c0^2 / gamma
  const double speed = m * std::sqrt(t);
  return {rho, speed * x.x / radius, speed * x.y / radius, p};
}

struct Errors {
  double density_l2 = 0.0;
  double wall_pressure_max = 0.0;  // relative
  int iterations = 0;
};

Errors solve(int ni, int nj) {
  const double cone = kConeDeg * std::acos(-1.0) / 180.0;
  StructuredMeshSpec spec;
  spec.ni = ni;
  spec.nj = nj;
  spec.map = [cone](double xi, double eta) {
    const double radius = 1.0 + (kRadiusOuter - 1.0) * xi;
    const double polar = cone * eta;
    return Vec2{radius * std::cos(polar), radius * std::sin(polar)};
  };
  spec.split = [ni](int i, int) { return 2 * i >= ni - 1; };  // quads, then triangles
  const Mesh mesh = structured_mesh(spec);
  std::vector<State> w_exact(mesh.points.size());
  for (std::size_t k = 0; k < w_exact.size(); ++k)
    w_exact[k] = exact(mesh.points[k]);
  BoundaryCondition axis, wall, far;
  axis.kind = BcKind::symmetry;
  wall.kind = BcKind::slip_wall;
  far.kind = BcKind::farfield;
  far.node_freestream = w_exact;
  FlowSolver solver(mesh, Geometry::axisymmetric, kGas, {axis, far, wall, far},  // bottom, right, top, left
                    exact_solution_run::unlimited_second_order());
  // Start from a uniform state (the inner far-field state) so the test sees the solver build the
  // radial expansion itself.
  solver.set_uniform(w_exact[0]);
  const SolveReport r = solver.solve();
  EXPECT_TRUE(r.converged) << ni << "x" << nj;
  Errors e;
  e.iterations = r.iterations;
  e.density_l2 = exact_solution_run::density_l2_error(solver, w_exact);
  const WallTrace wall_trace = solver.wall_trace(2);
  for (std::size_t k = 0; k < wall_trace.x.size(); ++k) {
    const double p_exact = exact({wall_trace.x[k], wall_trace.y[k]})[3];
    e.wall_pressure_max =
        std::max(e.wall_pressure_max, std::abs(wall_trace.pressure[k] - p_exact) / p_exact);
  }
  return e;
}

}  // namespace

TEST(ConicalSourceFlow, AxisymmetricSecondOrderConvergence) {
  const Errors e1 = solve(17, 9), e2 = solve(33, 17), e3 = solve(65, 33);
  const double p12 = std::log2(e1.density_l2 / e2.density_l2);
  const double p23 = std::log2(e2.density_l2 / e3.density_l2);
  std::printf(
      "conical source flow L2(rho error): %.3e %.3e %.3e, observed order %.2f %.2f (iterations %d "
      "%d %d)\n",
      e1.density_l2, e2.density_l2, e3.density_l2, p12, p23, e1.iterations, e2.iterations,
      e3.iterations);
  std::printf("  largest wall p error: %.3f %% %.3f %% %.3f %%\n", 100.0 * e1.wall_pressure_max,
              100.0 * e2.wall_pressure_max, 100.0 * e3.wall_pressure_max);
  EXPECT_GT(p23, 1.8);
  EXPECT_LT(p23, 2.5);
  // The wall pressure of the 65 x 33 mesh (3 cells per degree of the cone) within 0.5 %: an
  // order of magnitude below the 3 % tolerance of the Back-Massier-Gier comparison.
  EXPECT_LT(e3.wall_pressure_max, 0.005);
}
