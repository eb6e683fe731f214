#include <gtest/gtest.h>

#include "tfmb-flow/solver.hpp"
#include "test_meshes.hpp"

using namespace tfmb::flow;

namespace {
const PerfectGas kAir{1.4, 287.05};

double max_relative_residual(FlowSolver& solver, const State& w) {
  // residual relative to the flux scale (rho c, rho c^2, rho c^3) times the dual-cell size
  const auto res = solver.residual();
  const double c = kAir.sound_speed(w);
  const double scale[4] = {w[0] * c, w[0] * c * c, w[0] * c * c, w[0] * c * c * c};
  double worst = 0.0;
  const auto area = solver.node_area();
  for (std::size_t i = 0; i < res.size(); ++i) {
    const double face = std::sqrt(area[i]);  // size of the dual cell's faces
    for (int v = 0; v < 4; ++v) worst = std::max(worst, std::abs(res[i][v]) / (scale[v] * face));
  }
  return worst;
}
}  // namespace

TEST(FreeStream, PreservedOnDistortedMixedMeshSecondOrderWithLimiter) {
  const Mesh mesh = test_meshes::distorted_mixed_mesh();
  const State w{1.1, 230.0, 55.0, 9.0e4};
  BoundaryCondition far;
  far.kind = BcKind::farfield;
  far.freestream = w;
  SolverSettings s;
  s.order = 2;
  s.reference_state = {1.0, 300.0, 300.0, 1e5};
  FlowSolver solver(mesh, Geometry::planar, kAir, {far, far, far, far}, s);
  solver.set_uniform(w);
  EXPECT_LT(max_relative_residual(solver, w), 1e-13);
}

TEST(FreeStream, PreservedWithStagnationInflowAndPressureOutflow) {
  // uniform subsonic flow along x between slip walls; inflow and outflow are consistent with it
  const Mesh mesh = test_meshes::distorted_mixed_mesh();
  // make the boundary-normal boundaries straight: use an undistorted rectangle instead
  StructuredMeshSpec spec;
  spec.ni = 13;
  spec.nj = 9;
  spec.split = [](int i, int j) { return (i + 2 * j) % 3 == 0; };
  spec.jitter = 0.3;
  const Mesh rect = structured_mesh(spec);
  const double m = 0.5, t0 = 300.0, p0 = 2.0e5;
  const double t = t0 / (1.0 + 0.2 * m * m);
  const double p = p0 * std::pow(t / t0, 3.5);
  const State w{p / (kAir.R * t), m * std::sqrt(1.4 * kAir.R * t), 0.0, p};
  BoundaryCondition wall, in, out;
  in.kind = BcKind::stagnation_inflow;
  in.total_pressure = p0;
  in.total_temperature = t0;
  out.kind = BcKind::pressure_outflow;
  out.static_pressure = p;
  for (Geometry g : {Geometry::planar, Geometry::axisymmetric}) {
    SolverSettings s;
    s.reference_state = {1.0, 300.0, 300.0, 1e5};
    FlowSolver solver(rect, g, kAir, {wall, out, wall, in}, s);  // bottom, right, top, left
    solver.set_uniform(w);
    EXPECT_LT(max_relative_residual(solver, w), 1e-12) << (g == Geometry::planar ? "planar" : "axisymmetric");
  }
}
