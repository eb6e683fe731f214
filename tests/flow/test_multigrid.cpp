#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "grid_graph.hpp"
#include "tfmb-flow/linear_solver.hpp"
#include "tfmb-flow/multigrid.hpp"

using namespace tfmb::flow;

namespace {

// A block system on an m x m grid graph (nodes numbered along x first): each off-diagonal block
// -coupling_x or -coupling_y times the identity (plus noise), each diagonal block the sum of the
// couplings plus `shift` times the identity: an anisotropic diffusion-like operator.
struct Grid {
  BlockSparseMatrix a;
  std::vector<double> b;
};

Grid anisotropic_grid(int m, int nb, double coupling_x, double coupling_y, double shift,
                      double noise, unsigned seed) {
  const int n = m * m;
  Grid g{test_grids::grid_graph_pattern(m, nb),
         std::vector<double>(static_cast<std::size_t>(nb) * n)};
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int row = 0; row < n; ++row) {
    for (int p = g.a.row_ptr[row]; p < g.a.row_ptr[row + 1]; ++p) {
      double* block = g.a.block(p);
      for (int k = 0; k < nb * nb; ++k)
        block[k] = noise * u(rng);
      const int col = g.a.col[p];
      const double coupling = std::abs(col - row) == 1 ? coupling_x : coupling_y;
      for (int k = 0; k < nb; ++k)
        block[(nb + 1) * k] += col == row ? shift : -coupling;
    }
  }
  // the diagonal: the sum of the row's couplings plus the shift
  for (int row = 0; row < n; ++row) {
    double* diag = g.a.block(g.a.diag_pos[row]);
    for (int p = g.a.row_ptr[row]; p < g.a.row_ptr[row + 1]; ++p) {
      if (g.a.col[p] != row) {
        for (int k = 0; k < nb; ++k)
          diag[(nb + 1) * k] -= g.a.block(p)[(nb + 1) * k];
      }
    }
  }
  for (auto& v : g.b)
    v = u(rng);
  return g;
}

}  // namespace

// Pairs follow the strong couplings: with x couplings 100 times the y ones, every pair of a
// matching lies in one grid row, and every node is in a pair or alone.
TEST(Multigrid, PairwiseAggregatesFollowTheStrongDirection) {
  const int m = 12;
  const Grid g = anisotropic_grid(m, 4, 1.0, 0.01, 0.1, 0.0, 1);
  int count = 0;
  const std::vector<int> aggregate = pairwise_aggregates(g.a, 0.25, count);
  std::vector<std::vector<int>> members(count);
  for (int i = 0; i < m * m; ++i) {
    ASSERT_GE(aggregate[i], 0);
    ASSERT_LT(aggregate[i], count);
    members[aggregate[i]].push_back(i);
  }
  for (const auto& nodes : members) {
    ASSERT_GE(nodes.size(), 1u);
    ASSERT_LE(nodes.size(), 2u);
    if (nodes.size() == 2) {
      EXPECT_EQ(nodes[0] / m, nodes[1] / m) << "a pair across the weak direction";
    }
  }
  EXPECT_EQ(count, m * m / 2);  // even rows: all paired along x
  // the same with the strong direction along y: pairs within a grid column
  const Grid h = anisotropic_grid(m, 4, 0.01, 1.0, 0.1, 0.0, 1);
  const std::vector<int> by_column = pairwise_aggregates(h.a, 0.25, count);
  for (int i = 0; i + m < m * m; ++i) {
    for (int j = i + 1; j < m * m; ++j) {
      if (by_column[i] == by_column[j]) {
        EXPECT_EQ(i % m, j % m) << "a pair across the weak direction";
      }
    }
  }
}

// A node whose rows impose values (no coupling to any neighbour in some component, like a fixed
// state or a strong wall condition) is never paired with a node that does not impose the same.
TEST(Multigrid, ImposedRowsPairOnlyWithTheirOwnKind) {
  const int m = 8;
  Grid g = anisotropic_grid(m, 4, 1.0, 1.0, 0.1, 0.0, 2);
  // the first grid row: momentum components (1, 2) imposed, as at a wall
  for (int row = 0; row < m; ++row) {
    for (int p = g.a.row_ptr[row]; p < g.a.row_ptr[row + 1]; ++p) {
      double* block = g.a.block(p);
      for (int r : {1, 2}) {
        for (int c = 0; c < 4; ++c)
          block[4 * r + c] = g.a.col[p] == row && r == c ? 1.0 : 0.0;
      }
    }
  }
  int count = 0;
  const std::vector<int> aggregate = pairwise_aggregates(g.a, 0.25, count);
  for (int i = 0; i < m * m; ++i) {
    for (int j = i + 1; j < m * m; ++j) {
      if (aggregate[i] == aggregate[j]) {
        EXPECT_EQ(i < m, j < m) << "nodes " << i << " and " << j;
      }
    }
  }
  // wall nodes still pair along the wall
  EXPECT_EQ(aggregate[0], aggregate[1]);
}

// The coarse operator is P^T A P for piecewise-constant P: A_c x_c = R (A (P x_c)).
TEST(Multigrid, GalerkinCoarseMatrixIsRestrictedProduct) {
  const int m = 10, nb = 5;
  const Grid g = anisotropic_grid(m, nb, 1.0, 0.3, 0.2, 0.3, 3);
  int pairs = 0;
  const std::vector<int> first = pairwise_aggregates(g.a, 0.25, pairs);
  const BlockSparseMatrix coarse = galerkin_coarse_matrix(g.a, first, pairs);
  ASSERT_EQ(coarse.num_rows, pairs);
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<double> xc(static_cast<std::size_t>(nb) * pairs), yc(xc.size());
  for (auto& v : xc)
    v = u(rng);
  coarse.multiply(xc, yc);
  std::vector<double> x(static_cast<std::size_t>(nb) * m * m), y(x.size());
  for (int i = 0; i < m * m; ++i) {
    for (int v = 0; v < nb; ++v)
      x[nb * i + v] = xc[nb * first[i] + v];
  }
  g.a.multiply(x, y);
  std::vector<double> restricted(xc.size(), 0.0);
  for (int i = 0; i < m * m; ++i) {
    for (int v = 0; v < nb; ++v)
      restricted[nb * first[i] + v] += y[nb * i + v];
  }
  for (std::size_t k = 0; k < xc.size(); ++k)
    EXPECT_NEAR(yc[k], restricted[k], 1e-12 * (1.0 + std::abs(restricted[k])));
}

// GMRES(30) iterations to 1e-8 on grids of 24^2 to 96^2 nodes (16 times as many) of a nearly
// singular diffusion operator (a shift below its smallest eigenvalue), where a one-level
// preconditioner degrades with the mesh: ILU(0)'s count grows about 14-fold, multigrid's about
// 4-fold (a V-cycle of unsmoothed aggregation is not fully mesh-independent on diffusion, Notay
// 2010, sec. 1), and on the largest grid multigrid needs fewer.
TEST(Multigrid, GmresIterationsGrowLessWithTheGridThanWithIlu) {
  std::vector<int> ilu_iterations, multigrid_iterations;
  for (int m : {24, 48, 96}) {
    const Grid g = anisotropic_grid(m, 4, 1.0, 1.0, 1e-4, 0.0, 5);
    BlockIlu0 ilu;
    ilu.factorize(g.a, 1, 0);
    std::vector<double> x;
    const GmresResult with_ilu = gmres(g.a, ilu, g.b, x, 1e-8, 30, 2000);
    AggregationMultigrid multigrid;
    AggregationMultigrid::Options options;
    options.max_levels = 6;
    options.coarsest_nodes = 50;
    multigrid.setup(g.a, 1, 0, options);
    const GmresResult with_multigrid = gmres(g.a, multigrid, g.b, x, 1e-8, 30, 2000);
    // the true residual of the flexible GMRES solution
    EXPECT_LE(test_grids::relative_residual(g.a, g.b, x), 1e-8 * 1.01) << m << " x " << m;
    EXPECT_LE(with_ilu.relative_residual, 1e-8);
    EXPECT_LE(with_multigrid.relative_residual, 1e-8);
    std::printf(
        "%d x %d nodes: ILU(0) %d GMRES iterations; multigrid (%d levels, coarsest %d "
        "nodes) %d\n",
        m, m, with_ilu.iterations, multigrid.levels(),
        multigrid.level_nodes(multigrid.levels() - 1), with_multigrid.iterations);
    ilu_iterations.push_back(with_ilu.iterations);
    multigrid_iterations.push_back(with_multigrid.iterations);
  }
  const double ilu_growth = double(ilu_iterations.back()) / ilu_iterations.front();
  const double multigrid_growth =
      double(multigrid_iterations.back()) / multigrid_iterations.front();
  EXPECT_LT(multigrid_growth, 0.5 * ilu_growth);
  EXPECT_LT(multigrid_iterations.back(), ilu_iterations.back() / 2);
}

// Flexible GMRES: with a preconditioner that changes from one application to the next, the
// flexible variant still converges to the true solution, while treating it as fixed (the
// solution rebuilt with the last preconditioner) does not. This test fails if GMRES ignores
// flexible().
namespace {
class VaryingPreconditioner final : public Preconditioner {
 public:
  VaryingPreconditioner(const BlockIlu0& ilu, bool flexible) : ilu_(ilu), flexible_(flexible) {}
  void apply(const std::vector<double>& b, std::vector<double>& x) const override {
    ilu_.apply(b, x);
    const double scale = 1.0 + 0.5 * (calls_++ % 3);
    for (double& v : x)
      v *= scale;
  }
  bool flexible() const override { return flexible_; }

 private:
  const BlockIlu0& ilu_;
  bool flexible_;
  mutable int calls_ = 0;
};
}  // namespace

TEST(LinearSolver, FlexibleGmresTakesAPreconditionerThatChanges) {
  const Grid g = anisotropic_grid(20, 4, 1.0, 0.5, 0.1, 0.1, 6);
  BlockIlu0 ilu;
  ilu.factorize(g.a, 1, 0);
  auto true_residual = [&](bool flexible) {
    const VaryingPreconditioner m(ilu, flexible);
    std::vector<double> x;
    const GmresResult r = gmres(g.a, m, g.b, x, 1e-10, 40, 200);
    EXPECT_LE(r.relative_residual, 1e-10);
    return test_grids::relative_residual(g.a, g.b, x);
  };
  EXPECT_LT(true_residual(true), 1e-9);
  EXPECT_GT(true_residual(false), 1e-3);  // the fixed-M update is wrong for a varying M
}

// The two-level cycle, rebuilt here from its public pieces: ILU smoothing, the residual summed
// over each aggregate (two passes of pairwise matching), one ILU(0) step on the coarse level,
// the correction copied back and scaled to minimise the residual, then the post-smoothing step:
// the ILU again, or one block-Jacobi step x += D^-1 r. The multigrid's own cycle must give the
// same x (to the single-precision products' rounding) for both; a post-smoothing step skipped,
// applied to the wrong residual or with the ILU in place of Jacobi fails it (the two x differ by
// far more than the tolerance, checked below).
TEST(Multigrid, PostSmoothingStepIsTheIluOrOneBlockJacobiStep) {
  const int nb = 5;
  const Grid g = anisotropic_grid(16, nb, 1.0, 0.3, 0.05, 0.1, 7);
  const int n = g.a.num_rows;
  const std::size_t size = g.b.size();
  BlockIlu0 fine_ilu;
  fine_ilu.factorize(g.a, 1, 0);
  int pairs = 0, count = 0;
  AggregationMultigrid::Options options;
  options.max_levels = 2;
  options.coarsest_nodes = 10;
  const std::vector<int> first = pairwise_aggregates(g.a, options.strong_fraction, pairs);
  const BlockSparseMatrix paired = galerkin_coarse_matrix(g.a, first, pairs);
  const std::vector<int> second = pairwise_aggregates(paired, options.strong_fraction, count);
  const BlockSparseMatrix coarse = galerkin_coarse_matrix(paired, second, count);
  BlockIlu0 coarse_ilu;
  coarse_ilu.factorize(coarse, 1, 0);
  SinglePrecisionMatrix product;
  product.assign(g.a);
  // pre-smoothing, residual, coarse correction and its scaling
  std::vector<double> x, r(size), q(size), e(size), bc(static_cast<std::size_t>(nb) * count, 0.0),
      xc;
  fine_ilu.apply(g.b, x);
  product.multiply(x, r);
  for (std::size_t k = 0; k < size; ++k)
    r[k] = g.b[k] - r[k];
  for (int i = 0; i < n; ++i)
    for (int v = 0; v < nb; ++v)
      bc[static_cast<std::size_t>(nb) * second[first[i]] + v] +=
          r[static_cast<std::size_t>(nb) * i + v];
  coarse_ilu.apply(bc, xc);
  for (int i = 0; i < n; ++i)
    for (int v = 0; v < nb; ++v)
      e[static_cast<std::size_t>(nb) * i + v] =
          xc[static_cast<std::size_t>(nb) * second[first[i]] + v];
  product.multiply(e, q);
  double rq = 0.0, qq = 0.0;
  for (std::size_t k = 0; k < size; ++k) {
    rq += r[k] * q[k];
    qq += q[k] * q[k];
  }
  const double alpha = rq / qq;
  for (std::size_t k = 0; k < size; ++k) {
    x[k] += alpha * e[k];
    r[k] -= alpha * q[k];
  }
  // the two post-smoothing steps
  std::vector<double> with_ilu = x, with_jacobi = x, step;
  fine_ilu.apply(r, step);
  for (std::size_t k = 0; k < size; ++k)
    with_ilu[k] += step[k];
  for (int i = 0; i < n; ++i) {
    double inverse[nb * nb];
    ASSERT_TRUE(invert_block(g.a.block(g.a.diag_pos[i]), inverse, nb));
    for (int u = 0; u < nb; ++u)
      for (int v = 0; v < nb; ++v)
        with_jacobi[static_cast<std::size_t>(nb) * i + u] +=
            inverse[u * nb + v] * r[static_cast<std::size_t>(nb) * i + v];
  }
  auto largest_difference = [](const std::vector<double>& a, const std::vector<double>& b) {
    double diff = 0.0, scale = 0.0;
    for (std::size_t k = 0; k < a.size(); ++k) {
      diff = std::max(diff, std::abs(a[k] - b[k]));
      scale = std::max(scale, std::abs(b[k]));
    }
    return diff / scale;
  };
  // the two variants are far apart, so the check below can tell them apart
  ASSERT_GT(largest_difference(with_ilu, with_jacobi), 1e-2);
  for (auto post :
       {AggregationMultigrid::PostSmoother::ilu, AggregationMultigrid::PostSmoother::jacobi}) {
    options.post_smoother = post;
    AggregationMultigrid multigrid;
    multigrid.setup(g.a, 1, 0, options);
    ASSERT_EQ(multigrid.levels(), 2);
    ASSERT_EQ(multigrid.level_nodes(1), count);
    std::vector<double> cycle;
    multigrid.apply(g.b, cycle);
    const auto& expected = post == AggregationMultigrid::PostSmoother::ilu ? with_ilu : with_jacobi;
    EXPECT_LT(largest_difference(cycle, expected), 1e-5)
        << (post == AggregationMultigrid::PostSmoother::ilu ? "ilu" : "jacobi");
  }
}

// A later setup of a matrix with the same pattern and the same aggregates keeps the coarse
// patterns and sums the coarse blocks again: with the diagonal blocks shifted (the off-diagonal
// strengths, and so the aggregates, unchanged) the cycle is that of a multigrid built afresh
// for the shifted matrix
// (to the single-precision products' rounding), and far from the first matrix's cycle; the
// first matrix's coarse blocks kept would fail it. Another pattern rebuilds the levels.
TEST(Multigrid, LaterSetupOfTheSamePatternSumsTheCoarseBlocksAgain) {
  const int nb = 4;
  const Grid g = anisotropic_grid(16, nb, 1.0, 0.3, 0.05, 0.1, 11);
  Grid shifted = g;
  for (int i = 0; i < shifted.a.num_rows; ++i)
    for (int k = 0; k < nb; ++k)
      shifted.a.block(shifted.a.diag_pos[i])[(nb + 1) * k] += 0.5;
  AggregationMultigrid::Options options;
  options.max_levels = 3;
  options.coarsest_nodes = 10;
  AggregationMultigrid reused, fresh;
  std::vector<double> x_first, x_reused, x_fresh;
  reused.setup(g.a, 1, 0, options);
  reused.apply(g.b, x_first);
  reused.setup(shifted.a, 1, 0, options);
  reused.apply(g.b, x_reused);
  fresh.setup(shifted.a, 1, 0, options);
  fresh.apply(g.b, x_fresh);
  ASSERT_EQ(reused.levels(), fresh.levels());
  ASSERT_EQ(reused.levels(), 3);
  double diff_fresh = 0.0, diff_first = 0.0, scale = 0.0;
  for (std::size_t k = 0; k < x_fresh.size(); ++k) {
    diff_fresh = std::max(diff_fresh, std::abs(x_reused[k] - x_fresh[k]));
    diff_first = std::max(diff_first, std::abs(x_reused[k] - x_first[k]));
    scale = std::max(scale, std::abs(x_fresh[k]));
  }
  EXPECT_LT(diff_fresh / scale, 1e-6);
  EXPECT_GT(diff_first / scale, 1e-2);  // the shift changes the cycle
  // another pattern: the levels of that matrix
  const Grid other = anisotropic_grid(12, nb, 1.0, 0.3, 0.05, 0.1, 12);
  reused.setup(other.a, 1, 0, options);
  AggregationMultigrid other_fresh;
  other_fresh.setup(other.a, 1, 0, options);
  ASSERT_EQ(reused.levels(), other_fresh.levels());
  for (int l = 0; l < reused.levels(); ++l)
    EXPECT_EQ(reused.level_nodes(l), other_fresh.level_nodes(l));
  std::vector<double> y_reused, y_fresh;
  reused.apply(other.b, y_reused);
  other_fresh.apply(other.b, y_fresh);
  EXPECT_EQ(y_reused, y_fresh);
}

// The first matching's pairs kept with their matrix: a later setup whose pairs are the last
// ones sums that matrix's blocks again before the second matching reads them. With the y
// couplings raised from 0.3 to 0.6 of the x ones, the first matching still pairs along x, but
// the second now pairs those pairs along y (two y edges of 0.6 against one x edge of 1 between
// neighbouring pairs): the levels and the cycle must then be those of a multigrid built afresh
// for the new matrix, bit for bit. The pairs' matrix kept from the first setup (its sums left
// out) gives the second matching the old strengths and fails it.
TEST(Multigrid, KeptPairsAreSummedAgainBeforeTheSecondMatching) {
  const int nb = 4;
  const Grid weak_y = anisotropic_grid(16, nb, 1.0, 0.3, 0.05, 0.02, 14);
  const Grid strong_y = anisotropic_grid(16, nb, 1.0, 0.6, 0.05, 0.02, 14);
  int pairs_weak = 0, pairs_strong = 0;
  ASSERT_EQ(pairwise_aggregates(weak_y.a, 0.25, pairs_weak),
            pairwise_aggregates(strong_y.a, 0.25, pairs_strong));
  AggregationMultigrid::Options options;
  options.max_levels = 2;
  options.coarsest_nodes = 10;
  AggregationMultigrid reused, fresh, first;
  reused.setup(weak_y.a, 1, 0, options);
  reused.setup(strong_y.a, 1, 0, options);
  fresh.setup(strong_y.a, 1, 0, options);
  first.setup(weak_y.a, 1, 0, options);
  std::vector<double> x_reused, x_fresh, x_first;
  reused.apply(strong_y.b, x_reused);
  fresh.apply(strong_y.b, x_fresh);
  first.apply(strong_y.b, x_first);
  ASSERT_EQ(reused.levels(), 2);
  EXPECT_EQ(reused.level_nodes(1), fresh.level_nodes(1));
  EXPECT_EQ(x_reused, x_fresh);
  // the two matrices' multigrids differ, so a stale pairs' matrix shows
  EXPECT_NE(x_first, x_fresh);
}
