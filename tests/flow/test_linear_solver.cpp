#include <gtest/gtest.h>

#include <random>

#include "linear_solver.hpp"

using namespace tfmb::flow;

TEST(LinearSolver, GmresWithBlockIluSolvesAConvectionLikeSystem) {
  // 1D chain of 200 nodes with a nonsymmetric, diagonally dominant 4x4 block structure
  const int n = 200;
  std::vector<std::array<int, 2>> edges;
  for (int i = 0; i + 1 < n; ++i) edges.push_back({i, i + 1});
  for (int i = 0; i + 7 < n; i += 3) edges.push_back({i, i + 7});
  BlockSparseMatrix a = make_pattern(n, edges);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int i = 0; i < n; ++i) {
    for (int p = a.row_ptr[i]; p < a.row_ptr[i + 1]; ++p) {
      double* b = a.block(p);
      for (int k = 0; k < 16; ++k) b[k] = 0.3 * u(rng);
      if (a.col[p] == i) {
        for (int k = 0; k < 4; ++k) b[5 * k] += 4.0;
      }
    }
  }
  std::vector<double> x_true(4 * n), b;
  for (auto& v : x_true) v = u(rng);
  a.multiply(x_true, b);
  BlockIlu0 ilu;
  ilu.factorize(a);
  std::vector<double> x;
  const GmresResult r = gmres(a, ilu, b, x, 1e-12, 30, 200);
  EXPECT_LE(r.relative_residual, 1e-12);
  EXPECT_LT(r.iterations, 40);
  for (int k = 0; k < 4 * n; ++k) EXPECT_NEAR(x[k], x_true[k], 1e-10);
}

TEST(LinearSolver, BlockInverse) {
  const double a[16] = {0, 2, 1, 0, 3, 0, 0, 1, 1, 1, 4, 0, 0, 0, 1, 5};
  double inv[16];
  ASSERT_TRUE(invert_block(a, inv));
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) {
      double s = 0.0;
      for (int k = 0; k < 4; ++k) s += a[4 * i + k] * inv[4 * k + j];
      EXPECT_NEAR(s, i == j ? 1.0 : 0.0, 1e-14);
    }
  }
}
