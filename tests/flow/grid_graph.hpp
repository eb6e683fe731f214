// The block pattern of an m x m grid graph (5-point stencil, nodes numbered along x first) and the
// true relative residual of a solution, shared by the linear-solver and multigrid tests.
#pragma once

#include <array>
#include <cmath>
#include <vector>

#include "tfmb-flow/linear_solver.hpp"

namespace tfmb::flow::test_grids {

inline BlockSparseMatrix grid_graph_pattern(int m, int nb) {
  std::vector<std::array<int, 2>> edges;
  for (int j = 0; j < m; ++j) {
    for (int i = 0; i < m; ++i) {
      if (i + 1 < m)
        edges.push_back({j * m + i, j * m + i + 1});
      if (j + 1 < m)
        edges.push_back({j * m + i, (j + 1) * m + i});
    }
  }
  return make_pattern(m * m, edges, nb);
}

// |b - A x| / |b|, computed afresh (not GMRES's own estimate)
inline double relative_residual(const BlockSparseMatrix& a, const std::vector<double>& b,
                                const std::vector<double>& x) {
  std::vector<double> ax;
  a.multiply(x, ax);
  double r2 = 0.0, b2 = 0.0;
  for (std::size_t k = 0; k < b.size(); ++k) {
    r2 += (b[k] - ax[k]) * (b[k] - ax[k]);
    b2 += b[k] * b[k];
  }
  return std::sqrt(r2 / b2);
}

}  // namespace tfmb::flow::test_grids
