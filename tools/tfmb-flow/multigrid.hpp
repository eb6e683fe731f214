// Aggregation multigrid preconditioner for the block (4x4 to 6x6) implicit operator: coarse
// levels by double pairwise aggregation along the strongest blocks (Notay 2010, "An aggregation-
// based algebraic multigrid method", Electron. Trans. Numer. Anal. 37:123-146, sec. 3: two
// passes of pairwise matching per level), the Galerkin coarse operator of piecewise-constant
// prolongation (the blocks of each pair of aggregates summed), block ILU smoothing on every
// level (after the coarse correction ILU or block Jacobi, Options::post_smoother) and one
// V(1,1)-cycle per application, its coarse corrections scaled to minimise the residual (see
// cycle()); flexible GMRES (linear_solver.hpp) takes it as preconditioner.
#pragma once

#include <vector>

#include "linear_solver.hpp"

namespace tfmb::flow {

// Pairwise matching of the nodes of a block matrix (Notay 2010, alg. 4.1, with the Frobenius
// norm of a block as its strength): in row order, an unmatched node pairs with its strongest
// unmatched neighbour if that coupling is at least `strong_fraction` of the row's strongest;
// otherwise it stays alone. Nodes whose rows impose a condition (a component with no coupling
// to any neighbour: fixed states, strong wall conditions) pair only with nodes that impose the
// same components, so that no coarse equation mixes an imposed row with a flux balance.
// Returns the aggregate of each node (numbered in order of first node) and sets `count`.
std::vector<int> pairwise_aggregates(const BlockSparseMatrix& a, double strong_fraction,
                                     int& count);

// Galerkin coarse operator of piecewise-constant prolongation: A_c(I, J) = sum of A(i, j) over
// i in aggregate I and j in aggregate J.
BlockSparseMatrix galerkin_coarse_matrix(const BlockSparseMatrix& a,
                                         const std::vector<int>& aggregate, int count);

class AggregationMultigrid final : public Preconditioner {
 public:
  // The smoothing step after each coarse correction (every level above the coarsest).
  enum class PostSmoother {
    // one more block ILU step, x += M^-1 r: the stronger smoother where that step contracts
    // (the inviscid NPARC nozzle)
    ilu,
    // one block-Jacobi step, x += D^-1 r (D the level's diagonal blocks): a contraction where
    // the ILU step is not (nasa-2dcd NPR 8.91 with SA: from CFL about 300 an ILU(1) step
    // multiplies the residual by 1.1-2.7 and the V(1,1)-cycle stalls GMRES;
    // tools/tfmb-flow/README.md)
    jacobi,
  };
  struct Options {
    int max_levels = 4;        // including the fine one
    int coarsest_nodes = 500;  // stop coarsening at or below this many nodes
    double strong_fraction = 0.25;
    // ILU(0) Richardson sweeps on the coarsest level: NPARC 0.75 (240 x 60 and 480 x 120, two
    // levels) took about as many GMRES iterations with 1 as with 4, in less time
    int coarsest_sweeps = 1;
    PostSmoother post_smoother = PostSmoother::ilu;
  };
  // Builds the levels for `a` (kept by reference: it must outlive the preconditioner's use)
  // and factorises the smoothers: ILU(fill_level) on the fine level, ILU(0) below, each cut into
  // `partitions` row ranges (see BlockIlu0). The aggregates are found again at every setup; where
  // they are the last setup's (a matrix of the same pattern), the coarse patterns and their
  // storage are kept and only the coarse blocks summed again.
  void setup(const BlockSparseMatrix& a, int partitions, int fill_level, const Options& options);
  void apply(const std::vector<double>& b, std::vector<double>& x) const override;
  bool flexible() const override { return true; }  // the coarse corrections' scaling
  int levels() const { return static_cast<int>(levels_.size()); }
  int level_nodes(int level) const;

 private:
  // The first of a level's two pairwise matchings and the matrix of its pairs, which the second
  // reads (its pattern and block map kept while the pairs stay the same)
  struct Pairing {
    std::vector<int> aggregate;  // the pair of each node
    BlockSparseMatrix matrix;
    std::vector<int> member_ptr, members, coarse_block;
  };
  struct Level {
    BlockSparseMatrix matrix;  // empty on the fine level (fine_ is used)
    BlockIlu0 smoother;
    SinglePrecisionMatrix product;         // the level's matrix, for the cycle's products
    std::vector<float> diagonal_inverse;   // PostSmoother::jacobi: D^-1 by node, row-major blocks
    std::vector<int> aggregate;            // of each node, on the next coarser level
    std::vector<int> member_ptr, members;  // the nodes of each aggregate of the next level
    std::vector<int> coarse_block;  // of each block of this level's matrix, in the next one's
    Pairing pairing;
    mutable std::vector<double> b, x, r, e, q;
  };
  const BlockSparseMatrix& matrix(int level) const;
  bool coarsen(int level);
  void sum_coarse_blocks(int level);
  void cycle(int level, const std::vector<double>& b, std::vector<double>& x) const;
  const BlockSparseMatrix* fine_ = nullptr;
  std::vector<Level> levels_;
  // the fine pattern the coarse levels were built for (setup() rebuilds them for another one)
  int fine_block_size_ = 0;
  std::vector<int> fine_row_ptr_, fine_col_;
  Options options_;
};

}  // namespace tfmb::flow
