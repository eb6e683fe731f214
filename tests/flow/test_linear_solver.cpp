#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <stdexcept>

#include "grid_graph.hpp"
#include "tfmb-flow/linear_solver.hpp"

#ifdef _OPENMP
#include <omp.h>
#endif

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

namespace {

// A 2D grid graph (5-point, m x m nodes) with nb x nb blocks: random blocks of size noise plus a
// convection-diffusion-like M-matrix part (-1 off the diagonal, `diagonal` on it), and the
// right-hand side of a random solution.
struct GridSystem {
  BlockSparseMatrix a;
  std::vector<double> x_true, b;
};

GridSystem grid_system(int m, int nb, unsigned seed, double noise, double diagonal) {
  const int n = m * m;
  GridSystem g{test_grids::grid_graph_pattern(m, nb), std::vector<double>(nb * n), {}};
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int i = 0; i < n; ++i) {
    for (int p = g.a.row_ptr[i]; p < g.a.row_ptr[i + 1]; ++p) {
      double* block = g.a.block(p);
      for (int k = 0; k < nb * nb; ++k)
        block[k] = noise * u(rng);
      for (int k = 0; k < nb; ++k)
        block[(nb + 1) * k] += g.a.col[p] == i ? diagonal : -1.0;
    }
  }
  for (auto& v : g.x_true)
    v = u(rng);
  g.a.multiply(g.x_true, g.b);
  return g;
}

}  // namespace

// Level-of-fill ILU(k) on a 2D grid graph (5-point, 30 x 30 nodes, 4x4 blocks): with k large
// enough to keep every fill-in the factorisation is the exact LU, so one application solves the
// system (single-precision factors: to 1e-5); each level takes more blocks than the one before
// and the GMRES iterations do not grow with k.
TEST(LinearSolver, IluWithLevelOfFill) {
  const int m = 30, n = m * m, nb = 4;
  const GridSystem g = grid_system(m, nb, 11, 0.2, 4.4);
  const BlockSparseMatrix& a = g.a;
  const std::vector<double>& x_true = g.x_true;
  const std::vector<double>& b = g.b;
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

// GMRES on a system whose vectors are above the threading threshold (8,000 entries): its vector
// loops and its Gram-Schmidt (one parallel region per iteration) run on the threads over fixed
// chunks whose sums are added in a fixed order, so one and two threads take the same iterations
// to the same bits. Restarted, so that the restart's loops run too.
TEST(LinearSolver, GmresGivesTheSameBitsOnOneAndTwoThreads) {
  const GridSystem g = grid_system(50, 4, 5, 0.3, 4.2);  // 10,000 unknowns
  const BlockSparseMatrix& a = g.a;
  const std::vector<double>& x_true = g.x_true;
  const std::vector<double>& b = g.b;
  auto solve = [&](int threads, std::vector<double>& x) {
#ifdef _OPENMP
    omp_set_num_threads(threads);
#else
    (void)threads;
#endif
    BlockIlu0 ilu;
    ilu.factorize(a, 1, 1);
    return gmres(a, ilu, b, x, 1e-10, 10, 400);
  };
#ifdef _OPENMP
  const int threads_before = omp_get_max_threads();
#endif
  std::vector<double> x1, x2;
  const GmresResult r1 = solve(1, x1);
  const GmresResult r2 = solve(2, x2);
#ifdef _OPENMP
  omp_set_num_threads(threads_before);
#endif
  EXPECT_LE(r1.relative_residual, 1e-10);
  EXPECT_GT(r1.iterations, 10);  // restarted at least once
  EXPECT_EQ(r1.iterations, r2.iterations);
  EXPECT_EQ(r1.relative_residual, r2.relative_residual);
  ASSERT_EQ(x1.size(), x2.size());
  int differing = 0;
  double error = 0.0;
  for (std::size_t k = 0; k < x1.size(); ++k) {
    differing += x1[k] != x2[k];
    error = std::max(error, std::abs(x1[k] - x_true[k]));
  }
  EXPECT_EQ(differing, 0);
  EXPECT_LT(error, 1e-7);
}

// The single-precision copy's product (multigrid's internal products) is the double product to
// single-precision rounding of the values (half a unit in the last place, 2^-24 < 6e-8), for
// every block size.
TEST(LinearSolver, SinglePrecisionProductMatchesTheDoubleOne) {
  for (int nb : {4, 5, 6}) {
    const GridSystem g = grid_system(20, nb, 3, 0.3, 4.2);
    SinglePrecisionMatrix single;
    single.assign(g.a);
    std::vector<double> exact, rounded;
    g.a.multiply(g.x_true, exact);
    single.multiply(g.x_true, rounded);
    ASSERT_EQ(rounded.size(), exact.size());
    // |A x - A_single x| <= eps_single |A| |x| row by row
    std::vector<double> bound(exact.size(), 0.0);
    for (int i = 0; i < g.a.num_rows; ++i) {
      for (int p = g.a.row_ptr[i]; p < g.a.row_ptr[i + 1]; ++p) {
        for (int r = 0; r < nb; ++r) {
          for (int c = 0; c < nb; ++c)
            bound[nb * i + r] += std::abs(g.a.block(p)[nb * r + c] *
                                          g.x_true[nb * static_cast<std::size_t>(g.a.col[p]) + c]);
        }
      }
    }
    double largest_error = 0.0;
    for (std::size_t k = 0; k < exact.size(); ++k) {
      EXPECT_LE(std::abs(rounded[k] - exact[k]), 6e-8 * bound[k] + 1e-300) << nb << ": " << k;
      largest_error = std::max(largest_error, std::abs(rounded[k] - exact[k]) / bound[k]);
    }
    EXPECT_GT(largest_error, 0.0) << "the copy is not in single precision";
  }
}

namespace {
// The block ILU declared flexible, so that GMRES keeps the preconditioned basis too.
class FlexibleIlu final : public Preconditioner {
 public:
  explicit FlexibleIlu(const BlockIlu0& ilu) : ilu_(ilu) {}
  void apply(const std::vector<double>& b, std::vector<double>& x) const override {
    ilu_.apply(b, x);
  }
  bool flexible() const override { return true; }

 private:
  const BlockIlu0& ilu_;
};

}  // namespace

// A solve to a tolerance of kSinglePrecisionBasisTolerance or looser keeps its Krylov basis (and
// a flexible preconditioner's preconditioned basis) in single precision; the residual it reports
// is still the true one to 1e-6, and the solution meets the tolerance, restarted or not. A
// tighter solve in the same workspace keeps a double-precision basis and reaches 1e-8.
TEST(LinearSolver, LooseSolvesKeepASinglePrecisionBasis) {
  const GridSystem g = grid_system(40, 4, 11, 0.3, 4.1);  // 6,400 unknowns
  BlockIlu0 ilu;
  ilu.factorize(g.a, 1, 0);
  const FlexibleIlu flexible_ilu(ilu);
  for (const Preconditioner* m : {static_cast<const Preconditioner*>(&ilu),
                                  static_cast<const Preconditioner*>(&flexible_ilu)}) {
    const bool flexible = m->flexible();
    for (int restart : {3, 40}) {
      GmresWorkspace ws;
      std::vector<double> x;
      const double tolerance = std::max(1e-3, kSinglePrecisionBasisTolerance);
      const GmresResult loose = gmres(g.a, *m, g.b, x, tolerance, restart, 400, ws);
      EXPECT_TRUE(ws.v.empty()) << flexible << " " << restart;
      ASSERT_FALSE(ws.v_single.empty());
      EXPECT_EQ(ws.z_single.empty(), !flexible);
      EXPECT_TRUE(ws.z.empty());
      EXPECT_LE(loose.relative_residual, tolerance);
      EXPECT_GT(loose.iterations, restart == 3 ? 3 : 1) << "not restarted";
      const double loose_true = test_grids::relative_residual(g.a, g.b, x);
      EXPECT_LE(loose_true, tolerance * (1.0 + 1e-3));
      EXPECT_NEAR(loose.relative_residual, loose_true, 1e-6);

      const GmresResult tight = gmres(g.a, *m, g.b, x, 1e-8, 40, 400, ws);
      EXPECT_FALSE(ws.v.empty());
      EXPECT_LE(tight.relative_residual, 1e-8);
      EXPECT_LE(test_grids::relative_residual(g.a, g.b, x), 2e-8);
    }
  }
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
