#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <stdexcept>

#include "tfmb-flow/linear_solver.hpp"

using namespace tfmb::flow;

class LinearSolverBlocks : public ::testing::TestWithParam<int> {};

TEST_P(LinearSolverBlocks, GmresWithBlockIluSolvesAConvectionLikeSystem) {
  // 1D chain of 200 nodes with a nonsymmetric, diagonally dominant block structure of the
  // mean flow (4), mean flow + SA (5) or mean flow + a two-equation model (6)
  const int nb = GetParam();
  const int n = 200;
  std::vector<std::array<int, 2>> edges;
  for (int i = 0; i + 1 < n; ++i) edges.push_back({i, i + 1});
  for (int i = 0; i + 7 < n; i += 3) edges.push_back({i, i + 7});
  BlockSparseMatrix a = make_pattern(n, edges, nb);
  ASSERT_EQ(a.block_size, nb);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int i = 0; i < n; ++i) {
    for (int p = a.row_ptr[i]; p < a.row_ptr[i + 1]; ++p) {
      double* b = a.block(p);
      for (int k = 0; k < nb * nb; ++k)
        b[k] = 0.3 * u(rng);
      if (a.col[p] == i) {
        for (int k = 0; k < nb; ++k)
          b[(nb + 1) * k] += 4.0;
      }
    }
  }
  std::vector<double> x_true(nb * n), b;
  for (auto& v : x_true) v = u(rng);
  a.multiply(x_true, b);
  ASSERT_EQ(b.size(), x_true.size());
  // the product against a dense row sum
  for (int i : {0, 57, 199}) {
    for (int r = 0; r < nb; ++r) {
      double s = 0.0;
      for (int p = a.row_ptr[i]; p < a.row_ptr[i + 1]; ++p) {
        for (int c = 0; c < nb; ++c)
          s += a.block(p)[nb * r + c] * x_true[nb * a.col[p] + c];
      }
      EXPECT_NEAR(b[nb * i + r], s, 1e-13);
    }
  }
  // the product restricted to some rows (the assembled rows of the matrix-free operator)
  std::vector<double> y_rows(b.size(), -7.0);
  a.multiply_rows(x_true, y_rows, {3, 100, 199});
  for (int i = 0; i < n; ++i) {
    const bool listed = i == 3 || i == 100 || i == 199;
    for (int r = 0; r < nb; ++r) {
      if (listed)
        EXPECT_NEAR(y_rows[nb * i + r], b[nb * i + r], 1e-13);
      else
        EXPECT_EQ(y_rows[nb * i + r], -7.0);
    }
  }
  for (int partitions : {1, 2}) {
    BlockIlu0 ilu;
    ilu.factorize(a, partitions);
    std::vector<double> x;
    const GmresResult r = gmres(a, ilu, b, x, 1e-12, 30, 200);
    EXPECT_LE(r.relative_residual, 1e-12);
    EXPECT_LT(r.iterations, 40);
    for (int k = 0; k < nb * n; ++k)
      EXPECT_NEAR(x[k], x_true[k], 1e-10);
  }
}

INSTANTIATE_TEST_SUITE_P(BlockSizes, LinearSolverBlocks, ::testing::Values(4, 5, 6));

// Level-of-fill ILU(k) on a 2D grid graph (5-point, 30 x 30 nodes, 4x4 blocks): with k large
// enough to keep every fill-in the factorisation is the exact LU, so one application solves the
// system (single-precision factors: to 1e-5); each level takes more blocks than the one before
// and the GMRES iterations do not grow with k.
TEST(LinearSolver, IluWithLevelOfFill) {
  const int m = 30, n = m * m, nb = 4;
  std::vector<std::array<int, 2>> edges;
  for (int j = 0; j < m; ++j) {
    for (int i = 0; i < m; ++i) {
      if (i + 1 < m)
        edges.push_back({j * m + i, j * m + i + 1});
      if (j + 1 < m)
        edges.push_back({j * m + i, (j + 1) * m + i});
    }
  }
  BlockSparseMatrix a = make_pattern(n, edges, nb);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int i = 0; i < n; ++i) {
    for (int p = a.row_ptr[i]; p < a.row_ptr[i + 1]; ++p) {
      double* b = a.block(p);
      for (int k = 0; k < nb * nb; ++k)
        b[k] = 0.2 * u(rng);
      // a convection-diffusion-like M-matrix part: -1 off the diagonal, 4.4 on it
      for (int k = 0; k < nb; ++k)
        b[(nb + 1) * k] += a.col[p] == i ? 4.4 : -1.0;
    }
  }
  std::vector<double> x_true(nb * n), b;
  for (auto& v : x_true)
    v = u(rng);
  a.multiply(x_true, b);
  std::size_t previous_blocks = 0;
  int previous_iterations = 1000;
  for (int level : {0, 1, 2, 3}) {
    BlockIlu0 ilu;
    ilu.factorize(a, 1, level);
    EXPECT_GT(ilu.factor_blocks(), previous_blocks);
    previous_blocks = ilu.factor_blocks();
    std::vector<double> x;
    const GmresResult r = gmres(a, ilu, b, x, 1e-10, 50, 200);
    EXPECT_LE(r.relative_residual, 1e-10) << "level " << level;
    EXPECT_LE(r.iterations, previous_iterations) << "level " << level;
    previous_iterations = r.iterations;
    std::printf("ILU(%d): %zu blocks, %d GMRES iterations\n", level, ilu.factor_blocks(),
                r.iterations);
  }
  BlockIlu0 exact;
  exact.factorize(a, 1, 2 * m);  // fills the whole band: the exact LU
  std::vector<double> x;
  exact.apply(b, x);
  double err = 0.0;
  for (int k = 0; k < nb * n; ++k)
    err = std::max(err, std::abs(x[k] - x_true[k]));
  EXPECT_LT(err, 1e-4);
  // the same object refactorised at another level and with partitions
  exact.factorize(a, 2, 1);
  const GmresResult r = gmres(a, exact, b, x, 1e-10, 50, 200);
  EXPECT_LE(r.relative_residual, 1e-10);
}

TEST(LinearSolver, UnsupportedBlockSizeIsRefused) {
  EXPECT_THROW(make_pattern(3, {{0, 1}, {1, 2}}, 3), std::invalid_argument);
}

TEST(LinearSolver, BlockInverse5) {
  double a[25];
  for (int k = 0; k < 25; ++k)
    a[k] = std::sin(1.0 + 3.0 * k);
  for (int k = 0; k < 5; ++k)
    a[6 * k] += 3.0;
  double inv[25];
  ASSERT_TRUE(invert_block(a, inv, 5));
  for (int i = 0; i < 5; ++i) {
    for (int j = 0; j < 5; ++j) {
      double s = 0.0;
      for (int k = 0; k < 5; ++k)
        s += a[5 * i + k] * inv[5 * k + j];
      EXPECT_NEAR(s, i == j ? 1.0 : 0.0, 1e-13);
    }
  }
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
