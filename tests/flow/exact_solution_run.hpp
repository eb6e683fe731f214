// Shared by the order-of-accuracy tests against exact solutions (test_order_vortex.cpp,
// test_source_flow_axi.cpp): the scheme they measure and the error norm they measure it in.
#pragma once

#include <cmath>
#include <vector>

#include "tfmb-flow/solver.hpp"

namespace tfmb::flow::exact_solution_run {

// Second order without the limiter (it would clip smooth extrema and lower the order), run to a
// 10-order residual drop so the discretisation error, not the iteration error, is measured.
inline SolverSettings unlimited_second_order() {
  SolverSettings s;
  s.order = 2;
  s.limiter = false;
  s.max_iterations = 200;
  s.residual_drop = 1e-10;
  s.cfl_start = 10.0;
  return s;
}

// L2 norm of the density error, weighted by the dual-cell areas.
inline double density_l2_error(const FlowSolver& solver, const std::vector<State>& exact) {
  const auto w = solver.primitive();
  const auto node_area = solver.node_area();
  double sum = 0.0, area = 0.0;
  for (std::size_t k = 0; k < w.size(); ++k) {
    sum += node_area[k] * (w[k][0] - exact[k][0]) * (w[k][0] - exact[k][0]);
    area += node_area[k];
  }
  return std::sqrt(sum / area);
}

}  // namespace tfmb::flow::exact_solution_run
