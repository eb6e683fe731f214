// NPARC CDV nozzle (refdata/flow/nparc_cdv_nozzle_definition.csv), inviscid, planar channel of
// height A(x), against the exact quasi-1D solution (exact_nozzle.hpp). Mesh 81 x 21 nodes,
// one third of the quads split into triangles. Tolerances from the issue: mass flow 0.5 %,
// supersonic Mach 1 %, normal-shock position 2 % of the nozzle length.
#include <gtest/gtest.h>

#include <cstdio>

#include "nparc_case.hpp"

using namespace tfmb::flow;

namespace {

const PerfectGas kAir{1.4, 287.05};
constexpr int kNi = 81;
constexpr int kNj = 21;

struct NozzleRun {
  SolveReport report;
  double mass_flow_error;  // relative
  std::vector<nparc::Column> columns;
};

NozzleRun run_nozzle(double pe) {
  SolverSettings s;
  s.reference_state = {1.0, 300.0, 300.0, nparc::kP0};
  s.max_iterations = 600;
  FlowSolver solver(nparc::make_mesh(kNi, kNj), Geometry::planar, kAir, nparc::boundary_conditions(pe), s);
  const double t = nparc::kT0 / (1.0 + 0.2 * 0.04);  // start at rest-like M = 0.2
  const double p = nparc::kP0 * std::pow(t / nparc::kT0, 3.5);
  solver.set_uniform({p / (kAir.R * t), 0.2 * std::sqrt(1.4 * kAir.R * t), 0.0, p});
  NozzleRun r;
  r.report = solver.solve();
  const Quasi1dNozzle exact(nparc::area_in, 0.0, 5.0, 10.0, kAir.gamma, pe);
  const double mdot_exact = exact.mass_flow(nparc::kP0, nparc::kT0, kAir.R) * nparc::kInch;
  r.mass_flow_error = (solver.boundary_integral(1).mass_flow - mdot_exact) / mdot_exact;
  r.columns = nparc::column_averages(solver.primitive(), solver.node_coords(), kAir, kNi, kNj);
  std::printf("NPARC pe/p0 = %.2f: %d iterations, %ld linear, %.2f s, residual drop %.1e, mass flow error %.3f %%\n",
              pe, r.report.iterations, r.report.linear_iterations, r.report.wall_time, r.report.residual_drop,
              100.0 * r.mass_flow_error);
  return r;
}

double worst_mach_error(const NozzleRun& r, const Quasi1dNozzle& exact, double x_from, double x_to) {
  double worst = 0.0;
  for (const auto& c : r.columns) {
    if (c.x_in < x_from || c.x_in > x_to) continue;
    const double m = exact.mach(c.x_in);
    worst = std::max(worst, std::abs(c.mach - m) / m);
  }
  return worst;
}

}  // namespace

TEST(NparcNozzle, SubsonicExitPressure089) {
  const NozzleRun r = run_nozzle(0.89);
  ASSERT_TRUE(r.report.converged);
  EXPECT_LT(r.report.iterations, 300);
  EXPECT_LT(std::abs(r.mass_flow_error), 0.005);
  const Quasi1dNozzle exact(nparc::area_in, 0.0, 5.0, 10.0, kAir.gamma, 0.89);
  ASSERT_FALSE(exact.choked());
  // the flow is subsonic; Mach in the diverging part, where the channel is gentle
  const double err = worst_mach_error(r, exact, 5.0, 10.0);
  std::printf("  worst Mach error x in [5, 10]: %.3f %%\n", 100.0 * err);
  EXPECT_LT(err, 0.01);
}

TEST(NparcNozzle, NormalShockExitPressure075) {
  const NozzleRun r = run_nozzle(0.75);
  ASSERT_TRUE(r.report.converged);
  EXPECT_LT(r.report.iterations, 400);
  EXPECT_LT(std::abs(r.mass_flow_error), 0.005);
  const Quasi1dNozzle exact(nparc::area_in, 0.0, 5.0, 10.0, kAir.gamma, 0.75);
  ASSERT_TRUE(exact.has_shock());
  const double xs = exact.shock_position();
  // supersonic Mach between the throat region and the shock's smeared zone
  const double err = worst_mach_error(r, exact, 5.5, xs - 0.4);
  // shock: where the column pressure first crosses the mean of the exact jump
  const double p_mid = 0.5 * (exact.pressure_ratio(xs - 1e-9) + exact.pressure_ratio(xs + 1e-9));
  double x_shock = -1.0;
  for (std::size_t i = 1; i < r.columns.size(); ++i) {
    const auto& a = r.columns[i - 1];
    const auto& b = r.columns[i];
    if (a.x_in > 5.0 && a.p_ratio < p_mid && b.p_ratio >= p_mid) {
      x_shock = a.x_in + (p_mid - a.p_ratio) / (b.p_ratio - a.p_ratio) * (b.x_in - a.x_in);
      break;
    }
  }
  std::printf("  worst supersonic Mach error: %.3f %%; shock at x = %.3f in, exact %.3f in (%.2f %% of length)\n",
              100.0 * err, x_shock, xs, 100.0 * std::abs(x_shock - xs) / 10.0);
  EXPECT_LT(err, 0.01);
  EXPECT_LT(std::abs(x_shock - xs), 0.02 * 10.0);
}

TEST(NparcNozzle, SupersonicExitPressure016) {
  const NozzleRun r = run_nozzle(0.16);
  ASSERT_TRUE(r.report.converged);
  EXPECT_LT(r.report.iterations, 300);
  EXPECT_LT(std::abs(r.mass_flow_error), 0.005);
  const Quasi1dNozzle exact(nparc::area_in, 0.0, 5.0, 10.0, kAir.gamma, 0.16);
  const double err = worst_mach_error(r, exact, 5.5, 10.0);
  std::printf("  worst supersonic Mach error x in [5.5, 10]: %.3f %%\n", 100.0 * err);
  EXPECT_LT(err, 0.01);
}
