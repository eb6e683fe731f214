// The block pattern of an m x m grid graph (5-point stencil, nodes numbered along x first), shared
// by the linear-solver and multigrid tests.
#pragma once

#include <array>
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

}  // namespace tfmb::flow::test_grids
