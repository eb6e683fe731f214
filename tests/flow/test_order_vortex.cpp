// Observed order of accuracy on the supersonic vortex (Aftosmis, Gaitonde and Tavares 1995,
// AIAA J. 33:2279): isentropic inviscid flow between two circular arcs r = 1 and r = 1.384,
// Mach 2.25 on the inner arc, with an exact solution. Second order, no limiter, three nested
// mixed meshes; the slip walls are the polygonal arcs through the boundary nodes, the inflow
// (theta = 0) and outflow (theta = 90 deg) are far-field boundaries with the exact state.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "exact_solution_run.hpp"
#include "mesh_generate.hpp"
#include "tfmb-flow/solver.hpp"

using namespace tfmb::flow;

namespace {

const PerfectGas kGas{1.4, 1.0};  // non-dimensional: rho_i = 1, c_i = 1
constexpr double kMachInner = 2.25;
constexpr double kRadiusOuter = 1.384;

State exact(Vec2 x) {
  const double g = kGas.gamma;
  const double r2 = x.x * x.x + x.y * x.y;
  const double r = std::sqrt(r2);
  const double rho = std::pow(1.0 + 0.5 * (g - 1.0) * kMachInner * kMachInner * (1.0 - 1.0 / r2), 1.0 / (g - 1.0));
  const double p = std::pow(rho, g) / g;
  const double speed = kMachInner / r;
  return {rho, -speed * x.y / r, speed * x.x / r, p};
}

double density_error(int ni, int nj, int* iterations, bool riemann_wall = true) {
  const double pi = std::acos(-1.0);
  StructuredMeshSpec spec;
  spec.ni = ni;
  spec.nj = nj;
  spec.map = [pi](double xi, double eta) {
    const double r = 1.0 + (kRadiusOuter - 1.0) * eta;
    const double t = 0.5 * pi * xi;
    return Vec2{r * std::cos(t), r * std::sin(t)};
  };
  // Quads upstream, triangles (alternating diagonals) downstream: a mixed mesh that stays
  // self-similar under refinement. (A checkerboard of 2x2 triangle blocks, whose cell-scale
  // irregularity does not refine away, shows orders 1.8 and 1.5 on these meshes.)
  spec.split = [ni](int i, int) { return 2 * i >= ni - 1; };  // same pattern under refinement
  const Mesh mesh = structured_mesh(spec);
  std::vector<State> w_exact(mesh.points.size());
  for (std::size_t k = 0; k < w_exact.size(); ++k) w_exact[k] = exact(mesh.points[k]);
  BoundaryCondition wall, far;
  wall.kind = BcKind::slip_wall;
  wall.riemann_wall = riemann_wall;
  far.kind = BcKind::farfield;
  far.node_freestream = w_exact;
  FlowSolver solver(mesh, Geometry::planar, kGas, {wall, far, wall, far},
                    exact_solution_run::unlimited_second_order());  // bottom, right, top, left
  solver.set_primitive(w_exact);
  const SolveReport r = solver.solve();
  EXPECT_TRUE(r.converged) << ni << "x" << nj;
  *iterations = r.iterations;
  return exact_solution_run::density_l2_error(solver, w_exact);
}

}  // namespace

TEST(SupersonicVortex, SecondOrderConvergence) {
  int it[3];
  const double e1 = density_error(17, 9, &it[0]);
  const double e2 = density_error(33, 17, &it[1]);
  const double e3 = density_error(65, 33, &it[2]);
  const double p12 = std::log2(e1 / e2);
  const double p23 = std::log2(e2 / e3);
  std::printf("supersonic vortex L2(rho error): %.3e %.3e %.3e, observed order %.2f %.2f (iterations %d %d %d)\n",
              e1, e2, e3, p12, p23, it[0], it[1], it[2]);
  EXPECT_GT(p23, 1.8);
  EXPECT_LT(p23, 2.5);
}

TEST(SupersonicVortex, SecondOrderConvergencePressureOnlyWallFlux) {
  int it[3];
  const double e1 = density_error(17, 9, &it[0], false);
  const double e2 = density_error(33, 17, &it[1], false);
  const double e3 = density_error(65, 33, &it[2], false);
  const double p23 = std::log2(e2 / e3);
  std::printf("supersonic vortex, pressure-only wall flux: %.3e %.3e %.3e, observed order %.2f %.2f\n", e1, e2,
              e3, std::log2(e1 / e2), p23);
  EXPECT_GT(p23, 1.8);
  EXPECT_LT(p23, 2.5);
}
