// Results do not depend on the OpenMP thread count: every parallel loop writes per edge or per
// node and gathers in a fixed order, and dot products sum fixed chunks in order.
#include <gtest/gtest.h>

#include "nparc_case.hpp"

using namespace tfmb::flow;

namespace {
std::vector<State> run_with_threads(int threads) {
  const PerfectGas gas{1.4, 287.05};
  SolverSettings s;
  s.reference_state = {1.0, 300.0, 300.0, nparc::kP0};
  s.max_iterations = 8;
  s.threads = threads;
  FlowSolver solver(nparc::make_mesh(61, 17), Geometry::planar, gas, nparc::boundary_conditions(0.75), s);
  const double t = nparc::kT0 / 1.008;
  const double p = nparc::kP0 * std::pow(t / nparc::kT0, 3.5);
  solver.set_uniform({p / (gas.R * t), 0.2 * std::sqrt(1.4 * gas.R * t), 0.0, p});
  solver.solve();
  return solver.conservative();
}
}  // namespace

TEST(Threads, OneAndTwoThreadsGiveBitwiseIdenticalStates) {
  const auto a = run_with_threads(1);
  const auto b = run_with_threads(2);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    for (int v = 0; v < 4; ++v) ASSERT_EQ(a[i][v], b[i][v]) << "node " << i << " var " << v;
  }
}
