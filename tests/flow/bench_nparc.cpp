// Benchmark and study driver for the NPARC CDV nozzle: prints iterations, linear iterations,
// wall time and errors against the exact quasi-1D solution.
// Sample run: bench_nparc <pe/p0> <ni> <nj> [threads] [limiter_freeze_drop] [venkat_k] [print_every]
//             [cfl_max] [linear_tolerance]   e.g. bench_nparc 0.75 321 81 1
#include <cstdio>
#include <cstdlib>

#include "nparc_case.hpp"

using namespace tfmb::flow;

int main(int argc, char** argv) {
  const double pe = argc > 1 ? std::atof(argv[1]) : 0.75;
  const int ni = argc > 2 ? std::atoi(argv[2]) : 121;
  const int nj = argc > 3 ? std::atoi(argv[3]) : 31;
  const int threads = argc > 4 ? std::atoi(argv[4]) : 1;
  const PerfectGas gas{1.4, 287.05};
  SolverSettings s;
  s.reference_state = {1.0, 300.0, 300.0, nparc::kP0};
  s.print_every = 10;
  s.threads = threads;
  s.max_iterations = 1000;
  if (argc > 5) s.limiter_freeze_drop = std::atof(argv[5]);
  std::printf("threads %d\n", threads);
  if (argc > 6) s.venkat_k = std::atof(argv[6]);
  if (argc > 7) s.print_every = std::atoi(argv[7]);
  if (argc > 8) s.cfl_max = std::atof(argv[8]);
  if (argc > 9) s.linear_tolerance = std::atof(argv[9]);
  if (std::getenv("NORENUMBER")) s.renumber = false;
  FlowSolver solver(nparc::make_mesh(ni, nj), Geometry::planar, gas, nparc::boundary_conditions(pe), s);
  const double t = nparc::kT0 / (1.0 + 0.2 * 0.04);
  const double p = nparc::kP0 * std::pow(t / nparc::kT0, 3.5);
  solver.set_uniform({p / (gas.R * t), 0.2 * std::sqrt(1.4 * gas.R * t), 0.0, p});
  const SolveReport r = solver.solve();
  const Quasi1dNozzle exact(nparc::area_in, 0.0, 5.0, 10.0, gas.gamma, pe);
  const double mdot_exact = exact.mass_flow(nparc::kP0, nparc::kT0, gas.R) * nparc::kInch;
  const double mdot_out = solver.boundary_integral(1).mass_flow;
  const double mdot_in = -solver.boundary_integral(3).mass_flow;
  std::printf("pe/p0 %.2f mesh %dx%d nodes %d: converged %d iterations %d linear %ld backoffs %d time %.2f s drop %.1e\n",
              pe, ni, nj, ni * nj, r.converged, r.iterations, r.linear_iterations, r.backoffs, r.wall_time,
              r.residual_drop);
  std::printf("mass flow in %.6e out %.6e exact %.6e  error %.3f %%\n", mdot_in, mdot_out, mdot_exact,
              100.0 * (mdot_out - mdot_exact) / mdot_exact);
  const auto cols = nparc::column_averages(solver.primitive(), solver.node_coords(), gas, ni, nj);
  for (std::size_t i = 0; i < cols.size(); i += std::max<std::size_t>(1, cols.size() / 20)) {
    std::printf("x %6.3f  p/p0 %.4f (exact %.4f)  M %.4f (exact %.4f)\n", cols[i].x_in, cols[i].p_ratio,
                exact.pressure_ratio(cols[i].x_in), cols[i].mach, exact.mach(cols[i].x_in));
  }
  if (exact.has_shock()) std::printf("exact shock at x = %.4f in\n", exact.shock_position());
  return 0;
}
