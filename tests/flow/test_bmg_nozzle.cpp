// Back, Massier and Gier (1965) 30-15 degree conical nozzle, axisymmetric inviscid flow, wall
// p/pt against the experiment (refdata/flow/bmg_conical_nozzle_wall_p_gdtk.csv). Geometry as in
// the gdtk example the data file cites: throat radius 0.775 in, throat wall curvature radius
// 1.55 in, 15 deg cone downstream, 30 deg cone upstream from a 1.5955 in tube (the fillet
// between tube and cone is left sharp). Tolerance 3 % of p/pt (issue 4), x >= 0.125 in.
//
// DISABLED (the experiment disagrees downstream, see below and the viscous version at the end of
// this file, which shows that an attached turbulent boundary layer does not explain it): the
// inviscid solution (mesh converged:
// 141 x 31 and 281 x 61 nodes agree to 0.1 %) matches the experiment within 1 % on
// 0.375 <= x <= 0.875 in but is 7.6 % high at x = 0.25 in (transonic region) and up to 17 %
// low at x = 2.5 in, where the measured pressure levels off as a growing boundary layer would
// make it. The test runs with --gtest_also_run_disabled_tests and prints the comparison.
// Measured (second order, 141 x 31): +4.0 % at 0.125 in, +7.8 % at 0.25 in, -1.4..+1.9 % on
// 0.375-1.0 in, +2.1..+6.2 % on 1.125-2.0 in, -5.2..-16.9 % on 2.125-2.5 in. On 0.125-2.0 in the
// computed curve passes within 0.083 in (2.1 mm) along the wall of every measured point (within
// 0.035 in up to 1.0 in), the scale of reading a figure; the points scatter by that much about
// any smooth curve (the measured drop per 0.125 in alternates 0.015, 0.008, 0.011, 0.007 on
// 1.0-1.5 in). The axisymmetric discretisation itself is verified against an exact solution in
// test_source_flow_axi.cpp (conical source flow, wall p within 0.2 %, order 1.9).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>

#include "mesh_generate.hpp"
#include "tfmb-flow/quasi_one_dimensional.hpp"
#include "tfmb-flow/solver.hpp"

using namespace tfmb::flow;

namespace {

constexpr double kInch = 0.0254;
constexpr double kThroat = 0.775, kCurve = 1.55, kTube = 1.5955;  // [in]
constexpr double kInlet = -2.5, kExit = 3.0;                      // [in]

double wall_radius_in(double x) {
  const double pi = std::acos(-1.0);
  const double div = 15.0 * pi / 180.0, conv = 30.0 * pi / 180.0;
  if (x >= 0.0) {
    const double xa = kCurve * std::sin(div);
    if (x <= xa)
      return kThroat + kCurve - std::sqrt(kCurve * kCurve - x * x);
    return kThroat + kCurve * (1.0 - std::cos(div)) + (x - xa) * std::tan(div);
  }
  const double xa = -kCurve * std::sin(conv);
  if (x >= xa)
    return kThroat + kCurve - std::sqrt(kCurve * kCurve - x * x);
  const double r = kThroat + kCurve * (1.0 - std::cos(conv)) + (xa - x) * std::tan(conv);
  return std::min(r, kTube);
}

std::vector<std::array<double, 2>> read_reference() {
  const std::vector<std::filesystem::path> candidates = {
      std::filesystem::path(TFMB_SOURCE_DIR) / "refdata/flow/bmg_conical_nozzle_wall_p_gdtk.csv"};
  std::vector<std::array<double, 2>> data;  // x [in], p/pt
  for (const auto& path : candidates) {
    std::ifstream in(path);
    if (!in)
      continue;
    std::string line;
    while (std::getline(in, line)) {
      if (line.empty() || line[0] == '#' || line[0] == 'x')
        continue;
      std::istringstream s(line);
      double x_in, x_m, p;
      char c;
      if (s >> x_in >> c >> x_m >> c >> p)
        data.push_back({x_in, p});
    }
    break;
  }
  return data;
}

// Wall p/pt at the reference stations x >= x_from (linear between trace nodes), printed; returns
// the largest relative error on x_from <= x <= x_to and where it is.
struct Comparison {
  double worst = 0.0;
  double where = 0.0;  // [in]
};
Comparison compare_wall_pressure(const WallTrace& trace, double p0,
                                 const std::vector<std::array<double, 2>>& reference, double x_from,
                                 double x_to) {
  Comparison c;
  for (const auto& [x_in, p_ref] : reference) {
    if (x_in < x_from)
      continue;
    const double x = x_in * kInch;
    std::size_t k = 1;
    while (k + 1 < trace.x.size() && trace.x[k] < x)
      ++k;
    const double f = (x - trace.x[k - 1]) / (trace.x[k] - trace.x[k - 1]);
    const double p_wall = ((1.0 - f) * trace.pressure[k - 1] + f * trace.pressure[k]) / p0;
    const double err = std::abs(p_wall - p_ref) / p_ref;
    if (x_in <= x_to + 1e-9 && err > c.worst)
      c = {err, x_in};
    // The data were read off a figure (refdata header): also print how far along the wall the
    // computed curve reaches the measured value (nearest crossing), where p falls steeply a
    // fairer measure of the disagreement than the difference at equal x.
    double shift = 1e300;
    for (std::size_t j = 1; j < trace.x.size(); ++j) {
      const double a = trace.pressure[j - 1] / p0 - p_ref, b = trace.pressure[j] / p0 - p_ref;
      if (a * b > 0.0 || a == b)
        continue;
      const double x_cross = trace.x[j - 1] + a / (a - b) * (trace.x[j] - trace.x[j - 1]);
      if (std::abs(x_cross - x) < std::abs(shift))
        shift = x_cross - x;
    }
    std::printf(
        "  x %.3f in  p/pt %.4f  experiment %.3f  (%+.1f %%; computed reaches it %+.3f in away)\n",
        x_in, p_wall, p_ref, 100.0 * (p_wall - p_ref) / p_ref, shift / kInch);
  }
  return c;
}

}  // namespace

TEST(BackMassierGier, DISABLED_AxisymmetricWallPressure) {
  const auto reference = read_reference();
  if (reference.empty())
    GTEST_SKIP() << "refdata/flow/bmg_conical_nozzle_wall_p_gdtk.csv not found";
  const int ni = 141, nj = 31;
  StructuredMeshSpec spec;
  spec.ni = ni;
  spec.nj = nj;
  spec.map = [](double xi, double eta) {
    const double x = kInlet + (kExit - kInlet) * xi;
    return Vec2{x * kInch, eta * wall_radius_in(x) * kInch};
  };
  spec.split = [](int i, int j) { return j > 20 && (i + j) % 2 == 0; };
  spec.bottom = "axis";
  spec.right = "outlet";
  spec.top = "wall";
  spec.left = "inlet";
  const Mesh mesh = structured_mesh(spec);
  const PerfectGas gas{1.4, 287.05};
  const double p0 = 5.0e5, t0 = 300.0;
  BoundaryCondition axis, out, wall, in;
  axis.kind = BcKind::symmetry;
  out.kind = BcKind::pressure_outflow;
  out.static_pressure = 0.01 * p0;
  wall.kind = BcKind::slip_wall;
  in.kind = BcKind::stagnation_inflow;
  in.total_pressure = p0;
  in.total_temperature = t0;
  SolverSettings s;
  const double rho0 = p0 / (gas.R * t0), c0 = std::sqrt(1.4 * gas.R * t0);
  s.reference_state = {rho0, c0, c0, p0};
  s.max_iterations = 400;
  FlowSolver solver(mesh, Geometry::axisymmetric, gas, {axis, out, wall, in}, s);
  const double t = t0 / 1.008, p = p0 * std::pow(t / t0, 3.5);
  solver.set_uniform({p / (gas.R * t), 0.2 * std::sqrt(1.4 * gas.R * t), 0.0, p});
  const SolveReport r = solver.solve();
  std::printf("BMG nozzle (axisymmetric, %d nodes): %d iterations, %ld linear, %.2f s, drop %.1e\n",
              mesh.num_points(), r.iterations, r.linear_iterations, r.wall_time, r.residual_drop);
  ASSERT_TRUE(r.converged);
  const Comparison c = compare_wall_pressure(solver.wall_trace(2), p0, reference, 0.125, 1e9);
  const double worst = c.worst;
  std::printf("  worst |error| for x >= 0.125 in: %.2f %%\n", 100.0 * worst);
  EXPECT_LT(worst, 0.03);
}

// ---------------------------------------------------------------------------------------------
// Viscous version (issue 5): Spalart-Allmaras RANS, no-slip adiabatic wall, same geometry.
// Conditions: p_t 500 kPa, T_t 300 K, air (gamma 1.4, R 287.05, Sutherland), those of the gdtk
// example that the data file was transcribed from; BMG's runs were at a p_t of that order (the
// data file does not say which run), and the Reynolds number (~8e7 per m at the throat) puts the
// wall layer well into the turbulent range either way. The wall boundary layer starts at the
// inflow face, 2.5 in upstream of the throat (the experiment's upstream tube is not modelled).
// Outflow: static pressure of the isentropic flow at the exit area ratio (the core is
// supersonic and extrapolated; only the subsonic part of the exit boundary layer sees it).
// Mesh: ni x nj nodes, uniform in x, radial nodes clustered to the wall by a one-sided tanh
// with the first spacing dy1 at every column (5e-7 m is y+ ~ 1 at the throat: u_tau ~ 12 m/s
// for Cf ~ 0.0025, nu_w ~ 5.8e-6 m^2/s; measured 1.17).
// Scheme: first order by default (BMG_ORDER=2 BMG_MATRIX_FREE=1: second order restarted from it;
// with the first-order Jacobian alone the second-order run diverged: 141 x 81, omega -> 0 by
// iteration 50 at the wall node next to the sharp tube/cone corner, x = -1.87 in).
//
// Measured (141 x 81 = 11,421 nodes, first order, one thread): 121 iterations, 20 s, density
// residual down 8 orders; wall p/pt within 3.2 % of the experiment on 0.125 <= x <= 2.0 in
// except 5.6 % at 0.25 in, then -6.4, -10.9, -16.5, -17.1 % at x = 2.125 ... 2.5 in. The same
// mesh and scheme inviscid (slip wall, BMG_INVISCID=1) gives -19.3 % at 2.5 in: the boundary
// layer's displacement raises the wall pressure by 1-2.6 % only. The levelling-off of the
// measured pressure from x ~ 2 in is not an attached-boundary-layer effect; BMG report
// separated runs, so it is most likely the experiment's back pressure (not modelled: the exit
// here is supersonic). p_t 482.6 kPa (70 psia) instead of 500 kPa: p/pt within 0.08 %.
// On 281 x 81 (BMG_NI=281) p/pt rises by up to 1.9 %: within 1.4 % on
// 0.375-1.0 in, +7.1 % at 0.25 in, -16.6 % at 2.5 in. Tolerance 3 % (issue 4) on 0.125 <= x <= 2.5
// in: the test fails (17 %), hence DISABLED; BMG_NI, BMG_NJ, BMG_ORDER, BMG_ITER, BMG_PRINT,
// BMG_INVISCID, BMG_P0 [Pa] change the run.
namespace {

struct ViscousRun {
  SolveReport first_order;  // the first-order run (also the result when order = 1)
  SolveReport report;
  WallTrace trace;
  int nodes = 0;
  double y_plus_throat = 0.0;
};

ViscousRun run_viscous(int ni, int nj, double dy1, int order, int max_iterations, int print_every,
                       bool viscous = true, double p0 = 5.0e5, bool matrix_free = false,
                       const std::function<void(SolverSettings&)>& adjust = {}) {
  StructuredMeshSpec spec;
  spec.ni = ni;
  spec.nj = nj;
  const double deta = 1.0 / (nj - 1);
  spec.map = [=](double xi, double eta) {
    const double x = kInlet + (kExit - kInlet) * xi;
    const double r_wall = wall_radius_in(x) * kInch;
    // r(eta) = R tanh(beta eta) / tanh(beta); beta such that R - r(1 - deta) = dy1
    auto first = [&](double beta) {
      return r_wall * (1.0 - std::tanh(beta * (1.0 - deta)) / std::tanh(beta));
    };
    double lo = 1e-3, hi = 30.0;
    for (int it = 0; it < 200; ++it) {
      const double mid = 0.5 * (lo + hi);
      (first(mid) > dy1 ? lo : hi) = mid;
    }
    const double beta = 0.5 * (lo + hi);
    return Vec2{x * kInch, r_wall * std::tanh(beta * eta) / std::tanh(beta)};
  };
  spec.bottom = "axis";
  spec.right = "outlet";
  spec.top = "wall";
  spec.left = "inlet";
  const Mesh mesh = structured_mesh(spec);
  const PerfectGas gas{1.4, 287.05};
  const double t0 = 300.0;
  const double exit_ratio = std::pow(wall_radius_in(kExit) / kThroat, 2);
  BoundaryCondition axis, out, wall, in;
  axis.kind = BcKind::symmetry;
  out.kind = BcKind::pressure_outflow;
  out.static_pressure =
      p0 * isentropic_pressure_ratio(mach_of_area_ratio(exit_ratio, 1.4, true), 1.4);
  wall.kind = viscous ? BcKind::wall_adiabatic : BcKind::slip_wall;
  in.kind = BcKind::stagnation_inflow;
  in.total_pressure = p0;
  in.total_temperature = t0;
  SolverSettings s;
  const double rho0 = p0 / (gas.R * t0), c0 = std::sqrt(1.4 * gas.R * t0);
  s.reference_state = {rho0, c0, c0, p0};
  s.max_iterations = max_iterations;
  s.order = order;
  s.viscous = viscous;
  s.turbulent = viscous;
  s.print_every = print_every;
  s.matrix_free = matrix_free ? MatrixFree::on : MatrixFree::off;
  // A/B hooks for the solver benchmark: BMG_COUPLING 0 segregated, 1 coupled, 2 automatic
  // (default); BMG_SA_EXACT 0 the M-matrix part of the nu_tilde linearisation
  if (const char* c = std::getenv("BMG_COUPLING")) {
    const int k = std::atoi(c);
    s.turbulence_coupling = k == 0   ? TurbulenceCoupling::segregated
                            : k == 1 ? TurbulenceCoupling::coupled
                                     : TurbulenceCoupling::automatic;
  }
  if (const char* c = std::getenv("BMG_SA_EXACT"))
    s.sa_exact_jacobian = std::atoi(c) != 0;
  if (const char* c = std::getenv("BMG_LINES"))  // 1: --node-ordering lines
    s.renumber_lines = std::atoi(c) == 1;
  if (const char* c = std::getenv("BMG_NU_TILDE_LIMIT"))  // 1: --turbulence-step-limit nu-tilde
    s.limit_turbulence_alone = std::atoi(c) == 1;
  if (const char* c = std::getenv("BMG_ILU_FILL"))
    s.ilu_fill_level = std::atoi(c);
  if (const char* c = std::getenv("BMG_ROE_JACOBIAN"))  // 0 frozen, 1 exact-first-order, 2 exact
    s.roe_jacobian = std::atoi(c) == 0   ? RoeJacobian::frozen
                     : std::atoi(c) == 1 ? RoeJacobian::exact_first_order
                                         : RoeJacobian::exact;
  if (const char* c = std::getenv("BMG_CFL_MAX"))  // --cfl-max
    s.cfl_max = std::atof(c);
  // BMG_MATRIX_FREE=2: --matrix-free auto; BMG_FIRST_DROP: end the first-order stage at this
  // drop at the CFL ceiling, as tfmb-flow's first-order start does (--first-order-start-drop)
  if (std::getenv("BMG_MATRIX_FREE") && std::atoi(std::getenv("BMG_MATRIX_FREE")) == 2)
    s.matrix_free = MatrixFree::after_limiter_freeze;
  if (adjust)
    adjust(s);
  // first order from a uniform low-speed state; second order restarted from the converged
  // first-order solution (the way tfmb-flow --restart runs it)
  SolverSettings first_settings = s;
  first_settings.order = 1;
  if (const char* c = std::getenv("BMG_FIRST_DROP"); c && order >= 2)
    first_settings = first_order_start_settings(s, std::atof(c));
  FlowSolver first(mesh, Geometry::axisymmetric, gas, {axis, out, wall, in}, first_settings);
  const double t = t0 / 1.008, p = p0 * std::pow(t / t0, 3.5);
  first.set_uniform({p / (gas.R * t), 0.2 * std::sqrt(1.4 * gas.R * t), 0.0, p});
  ViscousRun run;
  run.nodes = mesh.num_points();
  run.first_order = first.solve();
  if (std::getenv("BMG_FIRST_DROP"))
    s.residual_reference = run.first_order.residual_reference;  // as tfmb-flow's second stage
  FlowSolver solver(mesh, Geometry::axisymmetric, gas, {axis, out, wall, in}, s);
  if (order == 1) {
    run.report = run.first_order;
    solver.set_primitive(first.primitive());
    solver.set_nu_tilde(first.nu_tilde());
  } else {
    solver.set_primitive(first.primitive());
    solver.set_nu_tilde(first.nu_tilde());
    run.report = solver.solve();
  }
  run.trace = solver.wall_trace(2);
  // y+ of the first node off the wall at the throat column
  const auto w = solver.primitive();
  const auto& tr = run.trace;
  std::size_t k = 0;
  while (k + 1 < tr.x.size() && tr.x[k] < 0.0)
    ++k;
  const int node_wall = tr.node[k];
  const int i = node_wall % ni;
  const int node_first = (nj - 2) * ni + i;
  const double mu_w = s.viscosity.viscosity(gas.temperature(w[node_wall]));
  const double u_tau = std::sqrt(std::abs(tr.shear_stress[k]) / w[node_wall][0]);
  const double dy = norm(solver.node_coords()[node_first] - solver.node_coords()[node_wall]);
  run.y_plus_throat = w[node_wall][0] * u_tau * dy / mu_w;
  return run;
}

int env_int(const char* name, int fallback) {
  const char* v = std::getenv(name);
  return v ? std::atoi(v) : fallback;
}

}  // namespace

TEST(BackMassierGier, DISABLED_AxisymmetricViscousWallPressure) {
  const auto reference = read_reference();
  if (reference.empty())
    GTEST_SKIP() << "refdata/flow/bmg_conical_nozzle_wall_p_gdtk.csv not found";
  const int ni = env_int("BMG_NI", 141), nj = env_int("BMG_NJ", 81),
            order = env_int("BMG_ORDER", 1);
  const double p0 = env_int("BMG_P0", 500000);  // [Pa]
  const ViscousRun r =
      run_viscous(ni, nj, 5e-7, order, env_int("BMG_ITER", 600), env_int("BMG_PRINT", 0),
                  env_int("BMG_INVISCID", 0) == 0, p0, env_int("BMG_MATRIX_FREE", 0) != 0);
  std::printf(
      "BMG nozzle, SA, order %d (%d x %d = %d nodes, y+ %.2f at the throat): %d iterations, %ld "
      "linear, "
      "%.1f s, drop %.1e, converged %d\n",
      order, ni, nj, r.nodes, r.y_plus_throat, r.report.iterations, r.report.linear_iterations,
      r.report.wall_time, r.report.residual_drop, int(r.report.converged));
  if (order > 1) {
    std::printf("  (first order: %d iterations, %.1f s, drop %.1e, converged %d)\n",
                r.first_order.iterations, r.first_order.wall_time, r.first_order.residual_drop,
                int(r.first_order.converged));
  }
  ASSERT_TRUE(r.report.converged);
  const Comparison c = compare_wall_pressure(r.trace, p0, reference, 0.125, 2.5);
  std::printf("  largest |error| for 0.125 <= x <= 2.5 in: %.2f %% at x = %.3f in\n",
              100.0 * c.worst, c.where);
  EXPECT_LT(c.worst, 0.03);
}

// Quick coarse version for the default suite (regression): 71 x 41 nodes, same wall spacing,
// first order, 131 iterations, ~3 s. Checks that the run converges and that the wall p/pt at the 21
// stations stays within 0.5 % of the values this mesh gave when the test was written (a change of
// scheme, boundary condition or SA term moves them by more); prints the experiment comparison.
TEST(BackMassierGier, ViscousCoarseRegression) {
  const auto reference = read_reference();
  if (reference.empty())
    GTEST_SKIP() << "refdata/flow/bmg_conical_nozzle_wall_p_gdtk.csv not found";
  const ViscousRun r = run_viscous(71, 41, 5e-7, 1, 600, 0);
  std::printf(
      "BMG nozzle, SA, first order, 71 x 41 (y+ %.2f at the throat): %d iterations, %.1f s, drop "
      "%.1e\n",
      r.y_plus_throat, r.report.iterations, r.report.wall_time, r.report.residual_drop);
  ASSERT_TRUE(r.report.converged);
  EXPECT_GT(r.y_plus_throat, 0.3);
  EXPECT_LT(r.y_plus_throat, 3.0);
  const Comparison c = compare_wall_pressure(r.trace, 5.0e5, reference, 0.125, 2.5);
  std::printf(
      "  largest |error| against the experiment for 0.125 <= x <= 2.5 in: %.2f %% at x = %.3f in\n",
      100.0 * c.worst, c.where);
  // recorded p/pt at x = 0.125, 0.25, ..., 2.5 in
  const double recorded[20] = {0.3504, 0.2706, 0.2079, 0.1775, 0.1622, 0.1479, 0.1346,
                               0.1225, 0.1114, 0.1015, 0.0924, 0.0843, 0.0770, 0.0705,
                               0.0646, 0.0593, 0.0545, 0.0503, 0.0464, 0.0429};
  for (int k = 0; k < 20; ++k) {
    const double x = 0.125 * (k + 1) * kInch;
    std::size_t m = 1;
    while (m + 1 < r.trace.x.size() && r.trace.x[m] < x)
      ++m;
    const double f = (x - r.trace.x[m - 1]) / (r.trace.x[m] - r.trace.x[m - 1]);
    const double p = ((1.0 - f) * r.trace.pressure[m - 1] + f * r.trace.pressure[m]) / 5.0e5;
    EXPECT_NEAR(p / recorded[k], 1.0, 0.005) << "x " << 0.125 * (k + 1) << " in";
  }
}

// The Newton-Krylov phase's CFL number follows the residual's drop past the ceiling
// (SolverSettings::newton_cfl_follows_drop) only when the turbulence equation is in the Newton
// step: with the segregated SA step, which lags the mean flow's and needs its pseudo-time term,
// the ceiling holds. The second-order stage from the first-order state, the limiter frozen at a
// drop of 1e-2, 60 iterations.
TEST(BackMassierGier, NewtonPhaseCflPassesTheCeilingOnlyWithCoupledTurbulence) {
  double largest_after_freeze[2] = {0.0, 0.0};
  const TurbulenceCoupling couplings[2] = {TurbulenceCoupling::segregated,
                                           TurbulenceCoupling::coupled};
  const double ceiling = SolverSettings{}.cfl_max;
  for (int k = 0; k < 2; ++k) {
    const ViscousRun r =
        run_viscous(71, 41, 5e-7, 2, 60, 0, true, 5.0e5, false, [&](SolverSettings& s) {
          s.matrix_free = MatrixFree::after_limiter_freeze;
          s.limiter_freeze_drop = 1e-2;
          s.turbulence_coupling = couplings[k];
        });
    ASSERT_GT(r.report.newton_from, 0) << "coupling " << k << ": the limiter never froze";
    for (const IterationRecord& step : r.report.history) {
      if (step.iteration >= r.report.newton_from)
        largest_after_freeze[k] = std::max(largest_after_freeze[k], step.cfl);
    }
    std::printf(
        "BMG 71 x 41, SA %s: limiter frozen at iteration %d, largest CFL after it %.2g, "
        "drop %.1e after %d iterations\n",
        k == 0 ? "segregated" : "coupled", r.report.newton_from, largest_after_freeze[k],
        r.report.residual_drop, r.report.iterations);
  }
  EXPECT_LE(largest_after_freeze[0], ceiling);
  EXPECT_GT(largest_after_freeze[1], 10.0 * ceiling);
}

// The line search with coupled SA steps: nu_tilde's step is halved with the mean flow's. This
// run (the coupled one above) has no step whose pseudo-time residual rises; asked for a fall to
// 0.7 of the residual before each step (line_search_rise), it halves some defect-correction steps
// (2 steps, 6 halvings, measured) and still converges, to the wall pressures of the run without
// the line search within 1e-5 p0 (3.5e-6 measured: the limiter froze at the same iteration on a
// slightly different state).
TEST(BackMassierGier, LineSearchHalvesCoupledStepsToTheSameSolution) {
  ViscousRun runs[2];
  const double p0 = 5.0e5;
  for (int k = 0; k < 2; ++k) {
    runs[k] = run_viscous(71, 41, 5e-7, 2, 200, 0, true, p0, false, [&](SolverSettings& s) {
      s.matrix_free = MatrixFree::after_limiter_freeze;
      s.limiter_freeze_drop = 1e-2;
      s.turbulence_coupling = TurbulenceCoupling::coupled;
      s.line_search_halvings = k == 0 ? 0 : 3;
      s.line_search_rise = 0.7;
    });
    ASSERT_TRUE(runs[k].report.converged) << "line search " << k;
  }
  EXPECT_EQ(runs[0].report.steps_shortened, 0);
  EXPECT_GE(runs[1].report.steps_shortened, 1);
  ASSERT_EQ(runs[0].trace.pressure.size(), runs[1].trace.pressure.size());
  double largest = 0.0;
  for (std::size_t i = 0; i < runs[0].trace.pressure.size(); ++i)
    largest = std::max(largest, std::abs(runs[0].trace.pressure[i] - runs[1].trace.pressure[i]));
  EXPECT_LT(largest, 1e-5 * p0);
}

// Second order on a curved, kinked wall with a y+ 1 layer (71 x 41, SA), restarted from first
// order: converges only with the wall-aligned reconstruction and the matrix-free second-order
// Jacobian (tools/tfmb-flow/README.md, "Nozzle plume convergence"). Without them (Cartesian
// stencil, first-order Jacobian) this run diverged at the tube/cone corner. Measured: 164
// iterations (1,960 linear), 8 orders, 7 s on one thread (282 iterations, ~15 s with the
// matrix-free GMRES solved to 0.02 instead of the default 0.4).
TEST(BackMassierGier, ViscousSecondOrderConverges) {
  const auto reference = read_reference();
  if (reference.empty())
    GTEST_SKIP() << "refdata/flow/bmg_conical_nozzle_wall_p_gdtk.csv not found";
  const ViscousRun r = run_viscous(71, 41, 5e-7, 2, 500, 0, true, 5.0e5, true);
  std::printf(
      "BMG nozzle, SA, second order, matrix-free, 71 x 41 (y+ %.2f at the throat): %d iterations, "
      "%ld linear, "
      "%.1f s, drop %.1e\n",
      r.y_plus_throat, r.report.iterations, r.report.linear_iterations, r.report.wall_time,
      r.report.residual_drop);
  ASSERT_TRUE(r.report.converged);
  EXPECT_LT(r.report.residual_drop, 1e-8);
  const Comparison c = compare_wall_pressure(r.trace, 5.0e5, reference, 0.125, 2.5);
  std::printf(
      "  largest |error| against the experiment for 0.125 <= x <= 2.5 in: %.2f %% at x = %.3f in\n",
      100.0 * c.worst, c.where);
}
