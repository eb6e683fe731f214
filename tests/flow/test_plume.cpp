// Regression: a sonic jet from a straight planar duct discharging into air at rest (half plane,
// symmetry below, far field left and above, pressure outflow right), NPR 5.4, first order: the
// plume topology of the nozzle cases (plenum + nozzle + external region) in a small mesh.
// The coarse mesh converges with either far-field flux. The finer one did not with the
// Riemann-invariant far field (node updates relaxed to omega -> 0 near the jet boundary, CFL
// collapse, as on the full config3 and nasa-2dcd meshes); with the Roe flux against the free
// stream (the default) it converges.
#include <gtest/gtest.h>

#include <cmath>

#include "tfmb-flow/solver.hpp"

using namespace tfmb::flow;

namespace {

// Nodes (i, j) of an ni x nj grid; the duct wall is the one row of cells j = j_wall, i < i_exit,
// removed from the grid (a plate of finite thickness with a blunt trailing edge).
struct PlumeMesh {
  Mesh mesh;
  int ni = 0, nj = 0;
};

PlumeMesh plume_mesh(int n_duct, int n_plume, int n_in, double plate_top, double x_growth, double dy0) {
  // x: duct 0..1 (uniform), plume 1..6 (stretched); y: duct 0..0.5, plate 0.5..0.52, air above
  std::vector<double> xs, ys;
  for (int i = 0; i <= n_duct; ++i) xs.push_back(static_cast<double>(i) / n_duct);
  double dx = 1.0 / n_duct;
  for (int i = 0; i < n_plume; ++i) {
    dx *= x_growth;
    xs.push_back(xs.back() + dx);
  }
  for (int j = 0; j <= n_in; ++j) ys.push_back(0.5 * j / n_in);
  ys.push_back(plate_top);
  double dy = dy0;
  while (ys.back() < 4.0) {
    dy *= 1.12;
    ys.push_back(ys.back() + dy);
  }
  PlumeMesh pm;
  pm.ni = static_cast<int>(xs.size());
  pm.nj = static_cast<int>(ys.size());
  const int ni = pm.ni, nj = pm.nj, i_exit = n_duct, j_wall = n_in;
  Mesh& m = pm.mesh;
  auto id = [&](int i, int j) { return j * ni + i; };
  for (int j = 0; j < nj; ++j) {
    for (int i = 0; i < ni; ++i) m.points.push_back({xs[i], ys[j]});
  }
  for (int j = 0; j + 1 < nj; ++j) {
    for (int i = 0; i + 1 < ni; ++i) {
      if (j == j_wall && i < i_exit) continue;
      const std::array<int, 4> q{id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)};
      if ((i + 2 * j) % 5 == 0) {
        m.triangles.push_back({q[0], q[1], q[2]});
        m.triangles.push_back({q[0], q[2], q[3]});
      } else {
        m.quads.push_back(q);
      }
    }
  }
  BoundaryCurve sym{"symmetry", {}}, out{"outflow", {}}, far_top{"farfield_top", {}},
      far_left{"farfield_left", {}}, in{"inflow", {}}, wall{"wall", {}};
  for (int i = 0; i + 1 < ni; ++i) sym.edges.push_back({id(i, 0), id(i + 1, 0)});
  for (int j = 0; j + 1 < nj; ++j) out.edges.push_back({id(ni - 1, j), id(ni - 1, j + 1)});
  for (int i = ni - 1; i > 0; --i) far_top.edges.push_back({id(i, nj - 1), id(i - 1, nj - 1)});
  for (int j = nj - 1; j > j_wall + 1; --j) far_left.edges.push_back({id(0, j), id(0, j - 1)});
  for (int j = j_wall; j > 0; --j) in.edges.push_back({id(0, j), id(0, j - 1)});
  for (int i = 0; i < i_exit; ++i) wall.edges.push_back({id(i, j_wall), id(i + 1, j_wall)});
  wall.edges.push_back({id(i_exit, j_wall), id(i_exit, j_wall + 1)});
  for (int i = i_exit; i > 0; --i) wall.edges.push_back({id(i, j_wall + 1), id(i - 1, j_wall + 1)});
  m.boundaries = {sym, out, far_top, far_left, in, wall};
  return pm;
}

// The jet's conditions: NPR 5.4 at 750 K into air at rest; boundary conditions in the order of
// plume_mesh's curves, and first-order settings scaled to the ambient state.
struct PlumeConditions {
  PerfectGas gas;
  double p_amb = 101325.0, t_amb = 288.15, p0 = 5.4 * p_amb, t0 = 750.0;
  State w_amb{p_amb / (gas.R * t_amb), 0.0, 0.0, p_amb};
  BoundaryCondition sym, out, far, in, wall;
  PlumeConditions() {
    sym.kind = BcKind::symmetry;
    out.kind = BcKind::pressure_outflow;
    out.static_pressure = p_amb;
    far.kind = BcKind::farfield;
    far.freestream = w_amb;
    in.kind = BcKind::stagnation_inflow;
    in.total_pressure = p0;
    in.total_temperature = t0;
    wall.kind = BcKind::slip_wall;
  }
  std::vector<BoundaryCondition> bcs() const { return {sym, out, far, far, in, wall}; }
  SolverSettings first_order() const {
    SolverSettings s;
    s.order = 1;
    s.max_iterations = 400;
    const double c_amb = std::sqrt(gas.gamma * p_amb / w_amb[0]);
    s.reference_state = {w_amb[0], c_amb, c_amb, p_amb};
    return s;
  }
};

// Second stage (second_order): restarted from the first-order solution, second order with the
// downstream face a far field too.
void expect_plume_converges(const PlumeMesh& pm, bool second_order = false) {
  check_mesh(pm.mesh);
  const PlumeConditions c;
  const PerfectGas& gas = c.gas;
  const double p0 = c.p0, t0 = c.t0;
  const State& w_amb = c.w_amb;
  const BoundaryCondition &sym = c.sym, &far = c.far, &in = c.in, &wall = c.wall;
  const SolverSettings s = c.first_order();
  FlowSolver solver(pm.mesh, Geometry::planar, gas, c.bcs(), s);
  solver.set_uniform(w_amb);
  const SolveReport r = solver.solve();
  EXPECT_TRUE(r.converged) << "residual drop " << r.residual_drop << " after " << r.iterations << " iterations";
  EXPECT_LT(r.residual_drop, 1e-8);
  if (second_order) {
    SolverSettings s2 = s;
    s2.order = 2;
    FlowSolver second(pm.mesh, Geometry::planar, gas, {sym, far, far, far, in, wall}, s2);
    second.set_primitive(solver.primitive());
    const SolveReport r2 = second.solve();
    EXPECT_TRUE(r2.converged) << "second order: residual drop " << r2.residual_drop << " after " << r2.iterations
                              << " iterations";
    const double g = gas.gamma;
    const double sonic =
        p0 / std::sqrt(gas.R * t0) * std::sqrt(g) * std::pow(2.0 / (g + 1.0), (g + 1.0) / (2.0 * (g - 1.0))) * 0.5;
    EXPECT_NEAR(-second.boundary_integral(4).mass_flow / sonic, 1.0, 0.05);
    return;
  }
  // The duct chokes at its exit: the mass flow through the inflow is the sonic one,
  // rho* a* h = p0 / sqrt(R T0) sqrt(gamma) (2/(gamma+1))^((gamma+1)/(2(gamma-1))) h (h = 0.5 m),
  // within the first-order scheme's error on 10 cells across the duct.
  const double g = gas.gamma;
  const double sonic = p0 / std::sqrt(gas.R * t0) * std::sqrt(g) * std::pow(2.0 / (g + 1.0), (g + 1.0) / (2.0 * (g - 1.0))) * 0.5;
  const BoundaryIntegral inflow = solver.boundary_integral(4);
  EXPECT_NEAR(-inflow.mass_flow / sonic, 1.0, 0.05);
}

}  // namespace

TEST(FlowPlume, SonicJetIntoAirAtRestConvergesAtFirstOrder) {
  expect_plume_converges(plume_mesh(12, 30, 10, 0.52, 1.08, 0.05));
}

// With the pressure outflow downstream (its switch at the face-normal Mach number 1) the second
// order does not converge on this mesh (drop 1 after 115 iterations); with a far field there it
// converges 8 orders in about 190 iterations.
TEST(FlowPlume, SonicJetIntoAirAtRestConvergesAtSecondOrderWithFarFieldDownstream) {
  expect_plume_converges(plume_mesh(12, 30, 10, 0.52, 1.08, 0.05), true);
}

TEST(FlowPlume, FinerSonicJetIntoAirAtRestConvergesAtFirstOrder) {
  expect_plume_converges(plume_mesh(20, 50, 20, 0.505, 1.06, 0.025));
}

// The inflow ramp's hold (SolverSettings::inflow_ramp_hold_mach): an 8-iteration ramp to NPR
// 5.4 drives the inflow face of the empty duct from Mach 0.09 at iteration 2 to 0.58 at 6 and
// 0.70 at 8 (measured). With the hold at Mach 0.5 the ramp waits from iteration 6. This straight
// duct chokes at its exit, so its steady inflow is sonic and the Mach number keeps rising while
// the ramp waits (0.95 by iteration 22): the hold ends after as many iterations as the ramp has,
// and the run converges to the same choked mass flow.
TEST(FlowPlume, InflowRampHoldsWhileTheInflowRunsFast) {
  const PlumeMesh pm = plume_mesh(12, 30, 10, 0.52, 1.08, 0.05);
  const PlumeConditions c;
  auto run = [&](double hold_mach) {
    SolverSettings s = c.first_order();
    s.inflow_ramp_iterations = 8;
    s.inflow_ramp_start_pressure = c.p_amb;
    s.inflow_ramp_hold_mach = hold_mach;
    FlowSolver solver(pm.mesh, Geometry::planar, c.gas, c.bcs(), s);
    solver.set_uniform(c.w_amb);
    const SolveReport r = solver.solve();
    EXPECT_TRUE(r.converged) << "hold " << hold_mach << ": residual drop " << r.residual_drop;
    return std::pair{r, -solver.boundary_integral(4).mass_flow};
  };
  const auto [free_ramp, free_mass_flow] = run(0.0);
  const auto [held_ramp, held_mass_flow] = run(0.5);
  EXPECT_EQ(free_ramp.inflow_ramp_end, 8);
  EXPECT_EQ(free_ramp.inflow_ramp_held, 0);
  EXPECT_GT(held_ramp.inflow_ramp_held, 0);
  EXPECT_EQ(held_ramp.inflow_ramp_held, 8);
  EXPECT_EQ(held_ramp.inflow_ramp_end, 8 + 8);
  EXPECT_NEAR(held_mass_flow / free_mass_flow, 1.0, 1e-6);
}
