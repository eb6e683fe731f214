// The first-order Jacobian of the coupled Spalart-Allmaras system against the derivative of the
// residual itself (the difference quotient that is the matrix-free Krylov operator, first order,
// so both linearise the same residual).
//
// A planar channel, 25 x 17 nodes clustered to a no-slip wall, SA, iterated 40 steps from a
// uniform start so that it has a boundary layer with eddy viscosity, wall gradients and
// inflow/outflow. Then for directions x:
// - nu_tilde only: the mean-flow rows are exactly d(viscous flux)/d mu_t d mu_t/d nu_tilde (the
//   cross blocks; the viscous flux is affine in mu_t) and, with sa_exact_jacobian, the nu_tilde
//   row is exact (convection, diffusion with d D/d nu_tilde, the whole source derivative).
//   Without the cross blocks the mean-flow rows would be 0 (error 1); with the M-matrix part of
//   the nu_tilde linearisation the nu_tilde row is off by the dropped terms (measured 6e-2).
// - mean flow only: the nu_tilde row holds the convecting velocity and the vorticity of the
//   production (through the least-squares gradient weights); the laminar nu = mu(T)/rho in the
//   source and the diffusion is not linearised. Measured 0.32 of the largest entry (1.00, i.e.
//   nothing, with the convection terms alone: the production's vorticity dominates), so a loose
//   bound; the mean-flow rows differ by the first-order approximations of the Roe (frozen
//   dissipation) and viscous (thin-shear) Jacobians (printed).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include "mesh_generate.hpp"
#include "tfmb-flow/solver.hpp"

using namespace tfmb::flow;

namespace {

// The channel's solver with the test's settings, changed by `adjust` (e.g. the coupling).
FlowSolver channel_solver(bool exact_sa, void (*adjust)(SolverSettings&) = nullptr) {
  StructuredMeshSpec spec;
  spec.ni = 25;
  spec.nj = 17;
  spec.map = [](double xi, double eta) {
    return Vec2{0.2 * xi, 0.02 * (std::exp(3.0 * eta) - 1.0) / (std::exp(3.0) - 1.0)};
  };
  spec.split = [](int i, int j) { return (i + j) % 3 == 0; };
  spec.bottom = "wall";
  spec.right = "outlet";
  spec.top = "top";
  spec.left = "inlet";
  const PerfectGas gas{1.4, 287.05};
  BoundaryCondition wall, out, top, in;
  wall.kind = BcKind::wall_adiabatic;
  out.kind = BcKind::pressure_outflow;
  out.static_pressure = 1.0e5;
  top.kind = BcKind::symmetry;
  in.kind = BcKind::stagnation_inflow;
  in.total_pressure = 1.06e5;
  in.total_temperature = 300.0;
  SolverSettings s;
  s.order = 1;
  s.viscous = true;
  s.turbulent = true;
  s.sa_exact_jacobian = exact_sa;
  s.sa_freestream_ratio = 50.0;  // a thick eddy-viscosity layer on a coarse mesh
  s.max_iterations = 40;
  s.residual_drop = 1e-12;
  s.reference_state = {1.16, 347.0, 347.0, 1.0e5};
  if (adjust)
    adjust(s);
  return FlowSolver(structured_mesh(spec), Geometry::planar, gas, {wall, out, top, in}, s);
}

FlowSolver developed_channel(bool exact_sa) {
  FlowSolver solver = channel_solver(exact_sa);
  solver.set_uniform({1.16, 60.0, 0.0, 1.0e5});
  solver.solve();
  return solver;
}

struct RowErrors {
  double mean_flow = 0.0;  // max |assembled - difference| / max |difference| over rows 0-3
  double nu_tilde = 0.0;   // the same over the nu_tilde rows
};

// Largest |a - b| over the chosen rows (kinds of unknown) relative to the largest |b| there.
double row_error(const std::vector<double>& a, const std::vector<double>& b, int first, int last) {
  double diff = 0.0, big = 0.0;
  for (std::size_t k = 0; k < a.size(); ++k) {
    const int v = static_cast<int>(k % 5);
    if (v < first || v > last)
      continue;
    diff = std::max(diff, std::abs(a[k] - b[k]));
    big = std::max(big, std::abs(b[k]));
  }
  return diff / std::max(big, 1e-300);
}

RowErrors compare(FlowSolver& solver, bool perturb_nu_tilde) {
  const int n = static_cast<int>(solver.node_coords().size());
  std::mt19937 random(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::vector<double> x(5 * static_cast<std::size_t>(n), 0.0);
  const std::vector<double> nu_tilde = solver.nu_tilde();
  const std::vector<double> scale = {1.0, 60.0, 60.0, 2.5e5};
  for (int i = 0; i < n; ++i) {
    if (perturb_nu_tilde) {
      x[5 * i + 4] = std::abs(nu_tilde[i]) * unit(random);
    } else {
      for (int v = 0; v < 4; ++v)
        x[5 * i + v] = 1e-3 * scale[v] * unit(random);
    }
  }
  const std::vector<double> assembled = solver.jacobian_product(x, true);
  const std::vector<double> differenced = solver.jacobian_product(x, false);
  RowErrors e;
  e.nu_tilde = row_error(assembled, differenced, 4, 4);
  if (!perturb_nu_tilde) {
    e.mean_flow = row_error(assembled, differenced, 0, 3);
    return e;
  }
  // Mean-flow rows against nu_tilde by central differences of R(U, nu_tilde): the one-sided
  // quotient of the Krylov operator, with its perturbation held to 1e-6 of each node's
  // nu_tilde, carries round-off of the energy fluxes of 1e-3 here.
  const double h = 1e-3;
  std::vector<double> shifted(n);
  std::vector<double> central(x.size(), 0.0);
  for (const double sign : {1.0, -1.0}) {
    for (int i = 0; i < n; ++i)
      shifted[i] = nu_tilde[i] + sign * h * x[5 * i + 4];
    solver.set_nu_tilde(shifted);
    const std::vector<State> r = solver.residual();
    for (int i = 0; i < n; ++i) {
      for (int v = 0; v < 4; ++v)
        central[5 * i + v] += sign * r[i][v] / (2.0 * h);
    }
  }
  solver.set_nu_tilde(nu_tilde);
  // rows replaced by strong conditions (no-slip momentum) are no residual rows
  for (int i = 0; i < n; ++i) {
    for (int v = 0; v < 4; ++v) {
      if (differenced[5 * i + v] == assembled[5 * i + v])
        central[5 * i + v] = assembled[5 * i + v];
    }
  }
  e.mean_flow = row_error(assembled, central, 0, 3);
  return e;
}

}  // namespace

TEST(CoupledJacobian, NuTildeColumnsAreTheDerivativeOfTheResidual) {
  FlowSolver exact = developed_channel(true);
  FlowSolver approximate = developed_channel(false);
  const RowErrors e = compare(exact, true);
  const RowErrors a = compare(approximate, true);
  std::printf(
      "d R / d nu_tilde, assembled against differences: mean-flow rows %.2e, nu_tilde rows "
      "%.2e (exact SA linearisation), %.2e (M-matrix part)\n",
      e.mean_flow, e.nu_tilde, a.nu_tilde);
  EXPECT_LT(e.mean_flow, 1e-5);
  EXPECT_LT(e.nu_tilde, 1e-5);
  EXPECT_GT(a.nu_tilde, 10.0 * e.nu_tilde);  // the check can tell the two linearisations apart
}

TEST(CoupledJacobian, NuTildeRowsFollowTheConvectingVelocity) {
  FlowSolver solver = developed_channel(true);
  const RowErrors e = compare(solver, false);
  std::printf(
      "d R / d U, assembled against differences: mean-flow rows %.2e (first-order "
      "approximations of the Roe and viscous Jacobians), nu_tilde rows %.2e\n",
      e.mean_flow, e.nu_tilde);
  EXPECT_LT(e.nu_tilde, 0.5);
}

// The segregated nu_tilde step obeys the same physicality limit as the coupled update: nu_tilde
// changes by at most max_turbulence_update of |nu_tilde| + nu per step (nu = mu(T) / rho of the
// state the step linearises). From the developed channel with nu_tilde cut to 1e-3 of itself,
// one step at CFL 1e4 wants to restore it (production far above destruction) by far more than
// that: without the limit the largest change is many times the allowed one.
TEST(SegregatedSpalartAllmaras, StepChangesNuTildeByAtMostItsLimit) {
  FlowSolver solver = developed_channel(false);
  std::vector<double> nu_tilde = solver.nu_tilde();
  for (double& v : nu_tilde)
    v *= 1e-3;
  solver.set_nu_tilde(nu_tilde);
  const std::vector<State> w = solver.primitive();
  const PerfectGas gas{1.4, 287.05};
  const SolverSettings defaults;
  solver.set_inner_iteration_control(1, 1e-12, 1e4, 0);
  solver.solve();
  const std::vector<double> stepped = solver.nu_tilde();
  double worst = 0.0;  // largest change over its limit
  for (std::size_t i = 0; i < w.size(); ++i) {
    const double nu = defaults.viscosity.viscosity(w[i][3] / (gas.R * w[i][0])) / w[i][0];
    const double limit = defaults.max_turbulence_update * (std::abs(nu_tilde[i]) + nu);
    worst = std::max(worst, std::abs(stepped[i] - nu_tilde[i]) / limit);
  }
  std::printf("largest nu_tilde change over its limit: %.6f\n", worst);
  EXPECT_LE(worst, 1.0 + 1e-9);
  EXPECT_GT(worst, 0.5);  // the step did move nu_tilde: the limit was reached somewhere
}

// The coupled step's physicality limit on nu_tilde (max_turbulence_update of |nu_tilde| + nu per
// step) relaxes the whole node by default and nu_tilde's update alone with
// limit_turbulence_alone (--turbulence-step-limit nu-tilde). From the developed channel with
// nu_tilde cut to 1e-3 of itself, one coupled step at CFL 1e4: both keep nu_tilde's change
// within its limit; the node limit takes a small fraction of the mean flow's step where it
// binds, nu_tilde alone leaves that step whole. A limit of 3 (--turbulence-update-limit) lets
// nu_tilde change by up to 3 of its scale |nu_tilde| + nu.
TEST(CoupledSpalartAllmaras, StepLimitOnNuTildeAloneLeavesTheMeanFlowStepWhole) {
  const FlowSolver developed = developed_channel(true);
  const std::vector<State> w = developed.primitive();
  std::vector<double> nu_tilde = developed.nu_tilde();
  for (double& v : nu_tilde)
    v *= 1e-3;
  const PerfectGas gas{1.4, 287.05};
  const SolverSettings defaults;
  struct Step {
    double worst_nu_change = 0.0;  // largest nu_tilde change over its limit
    double least_relaxation = 1.0;
  };
  auto one_coupled_step = [&](void (*adjust)(SolverSettings&)) {
    FlowSolver solver = channel_solver(true, adjust);
    solver.set_primitive(w);
    solver.set_nu_tilde(nu_tilde);
    solver.set_inner_iteration_control(1, 1e-12, 1e4, 0);
    const SolveReport report = solver.solve();
    const std::vector<double> stepped = solver.nu_tilde();
    Step step;
    step.least_relaxation = report.least_relaxation;
    for (std::size_t i = 0; i < w.size(); ++i) {
      const double nu = defaults.viscosity.viscosity(w[i][3] / (gas.R * w[i][0])) / w[i][0];
      const double limit = defaults.max_turbulence_update * (std::abs(nu_tilde[i]) + nu);
      step.worst_nu_change =
          std::max(step.worst_nu_change, std::abs(stepped[i] - nu_tilde[i]) / limit);
    }
    return step;
  };
  const Step node = one_coupled_step(
      [](SolverSettings& s) { s.turbulence_coupling = TurbulenceCoupling::coupled; });
  const Step alone = one_coupled_step([](SolverSettings& s) {
    s.turbulence_coupling = TurbulenceCoupling::coupled;
    s.limit_turbulence_alone = true;
  });
  std::printf(
      "node limit: nu_tilde change %.6f of its limit, least relaxation %.3g; nu_tilde "
      "alone: %.6f, %.3g\n",
      node.worst_nu_change, node.least_relaxation, alone.worst_nu_change, alone.least_relaxation);
  EXPECT_LE(node.worst_nu_change, 1.0 + 1e-9);
  EXPECT_LE(alone.worst_nu_change, 1.0 + 1e-9);
  EXPECT_GT(alone.worst_nu_change, 0.5);  // the limit was reached somewhere
  EXPECT_LT(node.least_relaxation, 0.5);  // ... and relaxed that node's mean flow with it
  EXPECT_EQ(alone.least_relaxation, 1.0);
  // --turbulence-update-limit 3: nu_tilde may change by 3 of its scale, and does somewhere
  const Step wide = one_coupled_step([](SolverSettings& s) {
    s.turbulence_coupling = TurbulenceCoupling::coupled;
    s.limit_turbulence_alone = true;
    s.max_turbulence_update = 3.0;
  });
  std::printf("nu_tilde alone, limit 3: nu_tilde change %.6f of its scale, least relaxation %.3g\n",
              wide.worst_nu_change, wide.least_relaxation);
  EXPECT_LE(wide.worst_nu_change, 3.0 + 1e-9);
  EXPECT_GT(wide.worst_nu_change, 1.5);
  EXPECT_EQ(wide.least_relaxation, 1.0);
}
