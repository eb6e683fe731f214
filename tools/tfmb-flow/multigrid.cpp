#include "multigrid.hpp"

#include <algorithm>
#include <cmath>

#include "tfmb/common/assert.hpp"

namespace tfmb::flow {

namespace {

// node loops below this many nodes run on one thread (a fork-join costs more than they do)
constexpr int kThreadedNodes = 2000;
constexpr int kMaxBlockEntries = 36;  // 6x6 blocks (k-omega SST)

double frobenius_norm(const double* block, int entries) {
  double s = 0.0;
  for (int k = 0; k < entries; ++k)
    s += block[k] * block[k];
  return std::sqrt(s);
}

// Bit r set: row r of node i's equations has no coupling to any neighbour (an imposed value).
std::vector<unsigned> imposed_components(const BlockSparseMatrix& a) {
  const int nb = a.block_size;
  std::vector<unsigned> mask(a.num_rows, 0);
  for (int i = 0; i < a.num_rows; ++i) {
    unsigned coupled = 0;
    for (int p = a.row_ptr[i]; p < a.row_ptr[i + 1]; ++p) {
      if (a.col[p] == i)
        continue;
      const double* blk = a.block(p);
      for (int r = 0; r < nb; ++r) {
        for (int c = 0; c < nb; ++c) {
          if (blk[nb * r + c] != 0.0) {
            coupled |= 1u << r;
            break;
          }
        }
      }
    }
    mask[i] = ~coupled & ((1u << nb) - 1u);
  }
  return mask;
}

// r = b - A x
void residual(const SinglePrecisionMatrix& a, const std::vector<double>& b,
              const std::vector<double>& x, std::vector<double>& r) {
  r.resize(b.size());
  a.multiply(x, r);
  const long n = static_cast<long>(b.size());
  const int nb = a.pattern->block_size;
#pragma omp parallel for schedule(static) if (n > kThreadedNodes * nb)
  for (long k = 0; k < n; ++k)
    r[k] = b[k] - r[k];
}

// The nodes of each aggregate, in node order (a counting sort by aggregate).
void aggregate_members(const std::vector<int>& aggregate, int count, std::vector<int>& member_ptr,
                       std::vector<int>& members) {
  const int n = static_cast<int>(aggregate.size());
  member_ptr.assign(count + 1, 0);
  members.resize(n);
  for (int i = 0; i < n; ++i)
    ++member_ptr[aggregate[i] + 1];
  for (int c = 0; c < count; ++c)
    member_ptr[c + 1] += member_ptr[c];
  std::vector<int> next(member_ptr.begin(), member_ptr.end() - 1);
  for (int i = 0; i < n; ++i)
    members[next[aggregate[i]]++] = i;
}

// The coarse block of each fine block (the fine matrix's aggregates into the coarse pattern).
void coarse_block_map(const BlockSparseMatrix& fine, const std::vector<int>& aggregate,
                      const BlockSparseMatrix& coarse, std::vector<int>& coarse_block) {
  coarse_block.resize(fine.col.size());
  for (int i = 0; i < fine.num_rows; ++i) {
    for (int p = fine.row_ptr[i]; p < fine.row_ptr[i + 1]; ++p)
      coarse_block[p] = coarse.find(aggregate[i], aggregate[fine.col[p]]);
  }
}

// The coarse matrix's blocks summed again from the fine ones (the Galerkin product of
// piecewise-constant prolongation) into its kept pattern, `coarse_block` the coarse block of each
// fine one: a coarse row at a time from its aggregate's members in node order, the order
// galerkin_coarse_matrix sums them in, so the same bits as that and whatever the number of
// threads.
void sum_aggregated_blocks(const BlockSparseMatrix& fine, const std::vector<int>& member_ptr,
                           const std::vector<int>& members, const std::vector<int>& coarse_block,
                           BlockSparseMatrix& coarse) {
  const int be = fine.block_entries();
#pragma omp parallel for schedule(static) if (coarse.num_rows > kThreadedNodes)
  for (int c = 0; c < coarse.num_rows; ++c) {
    std::fill(coarse.block(coarse.row_ptr[c]), coarse.block(coarse.row_ptr[c + 1]), 0.0);
    for (int m = member_ptr[c]; m < member_ptr[c + 1]; ++m) {
      const int i = members[m];
      for (int p = fine.row_ptr[i]; p < fine.row_ptr[i + 1]; ++p) {
        const double* from = fine.block(p);
        double* to = coarse.block(coarse_block[p]);
        for (int k = 0; k < be; ++k)
          to[k] += from[k];
      }
    }
  }
}

// The inverses of a's diagonal blocks, in single precision (a smoother's own error is far
// larger than their rounding). A singular block falls back to the identity, as the block ILU's
// pivots do (only a broken operator has one).
void invert_diagonal_blocks(const BlockSparseMatrix& a, std::vector<float>& inverse) {
  const int n = a.num_rows;
  const int nb = a.block_size;
  const int entries = a.block_entries();
  inverse.resize(static_cast<std::size_t>(entries) * n);
#pragma omp parallel for schedule(static) if (n > kThreadedNodes)
  for (int i = 0; i < n; ++i) {
    double block[kMaxBlockEntries];
    if (!invert_block(a.block(a.diag_pos[i]), block, nb)) {
      for (int k = 0; k < entries; ++k)
        block[k] = k % (nb + 1) == 0 ? 1.0 : 0.0;
    }
    float* to = inverse.data() + static_cast<std::size_t>(entries) * i;
    for (int k = 0; k < entries; ++k)
      to[k] = static_cast<float>(block[k]);
  }
}

// x += D^-1 r, node by node (one block-Jacobi step)
void jacobi_step(const std::vector<float>& diagonal_inverse, int nb, const std::vector<double>& r,
                 std::vector<double>& x) {
  const int n = static_cast<int>(x.size()) / nb;
#pragma omp parallel for schedule(static) if (n > kThreadedNodes)
  for (int i = 0; i < n; ++i) {
    const float* d = diagonal_inverse.data() + static_cast<std::size_t>(nb) * nb * i;
    const double* ri = r.data() + static_cast<std::size_t>(nb) * i;
    double* xi = x.data() + static_cast<std::size_t>(nb) * i;
    for (int u = 0; u < nb; ++u) {
      double s = 0.0;
      for (int v = 0; v < nb; ++v)
        s += static_cast<double>(d[u * nb + v]) * ri[v];
      xi[u] += s;
    }
  }
}

}  // namespace

std::vector<int> pairwise_aggregates(const BlockSparseMatrix& a, double strong_fraction,
                                     int& count) {
  const int n = a.num_rows;
  const int be = a.block_entries();
  const std::vector<unsigned> imposed = imposed_components(a);
  // each block's strength once (the matching below reads it up to twice), on all threads: the
  // matching itself is sequential
  std::vector<double> strength(a.col.size());
  const long blocks = static_cast<long>(a.col.size());
#pragma omp parallel for schedule(static) if (n > kThreadedNodes)
  for (long p = 0; p < blocks; ++p)
    strength[p] = frobenius_norm(a.block(static_cast<int>(p)), be);
  std::vector<int> aggregate(n, -1);
  count = 0;
  for (int i = 0; i < n; ++i) {
    if (aggregate[i] >= 0)
      continue;
    double strongest = 0.0;
    for (int p = a.row_ptr[i]; p < a.row_ptr[i + 1]; ++p) {
      if (a.col[p] != i)
        strongest = std::max(strongest, strength[p]);
    }
    int partner = -1;
    double best = strong_fraction * strongest;
    for (int p = a.row_ptr[i]; p < a.row_ptr[i + 1]; ++p) {
      const int j = a.col[p];
      if (j == i || aggregate[j] >= 0 || imposed[j] != imposed[i])
        continue;
      const double s = strength[p];
      if (s > 0.0 && s >= best) {
        best = s;
        partner = j;
      }
    }
    aggregate[i] = count;
    if (partner >= 0)
      aggregate[partner] = count;
    ++count;
  }
  return aggregate;
}

BlockSparseMatrix galerkin_coarse_matrix(const BlockSparseMatrix& a,
                                         const std::vector<int>& aggregate, int count) {
  const int be = a.block_entries();
  std::vector<int> member_ptr, members;
  aggregate_members(aggregate, count, member_ptr, members);

  BlockSparseMatrix coarse;
  coarse.num_rows = count;
  coarse.block_size = a.block_size;
  coarse.row_ptr.assign(count + 1, 0);
  coarse.diag_pos.assign(count, -1);
  coarse.col.reserve(a.col.size() / 2);
  coarse.val.reserve(a.val.size() / 2);
  std::vector<int> position(count, -1);  // of coarse column J in the current row, -1 if absent
  std::vector<int> row_cols;
  for (int c = 0; c < count; ++c) {
    row_cols.clear();
    for (int m = member_ptr[c]; m < member_ptr[c + 1]; ++m) {
      const int i = members[m];
      for (int p = a.row_ptr[i]; p < a.row_ptr[i + 1]; ++p) {
        const int cj = aggregate[a.col[p]];
        if (position[cj] < 0) {
          position[cj] = 0;
          row_cols.push_back(cj);
        }
      }
    }
    std::sort(row_cols.begin(), row_cols.end());
    const int first = static_cast<int>(coarse.col.size());
    for (std::size_t k = 0; k < row_cols.size(); ++k) {
      position[row_cols[k]] = first + static_cast<int>(k);
      coarse.col.push_back(row_cols[k]);
      if (row_cols[k] == c)
        coarse.diag_pos[c] = first + static_cast<int>(k);
    }
    coarse.val.resize(static_cast<std::size_t>(be) * coarse.col.size(), 0.0);
    for (int m = member_ptr[c]; m < member_ptr[c + 1]; ++m) {
      const int i = members[m];
      for (int p = a.row_ptr[i]; p < a.row_ptr[i + 1]; ++p) {
        const double* from = a.block(p);
        double* to = coarse.block(position[aggregate[a.col[p]]]);
        for (int k = 0; k < be; ++k)
          to[k] += from[k];
      }
    }
    for (int cj : row_cols)
      position[cj] = -1;
    coarse.row_ptr[c + 1] = static_cast<int>(coarse.col.size());
    TFMB_ASSERT(coarse.diag_pos[c] >= 0, "coarse row " << c << " has no diagonal block");
  }
  return coarse;
}

const BlockSparseMatrix& AggregationMultigrid::matrix(int level) const {
  return level == 0 ? *fine_ : levels_[level].matrix;
}

int AggregationMultigrid::level_nodes(int level) const {
  return matrix(level).num_rows;
}

void AggregationMultigrid::setup(const BlockSparseMatrix& a, int partitions, int fill_level,
                                 const Options& options) {
  // the levels below are kept only for the same fine pattern and coarsening options
  if (levels_.empty() || options.max_levels != options_.max_levels ||
      options.coarsest_nodes != options_.coarsest_nodes ||
      options.strong_fraction != options_.strong_fraction || a.block_size != fine_block_size_ ||
      a.row_ptr != fine_row_ptr_ || a.col != fine_col_) {
    levels_.clear();
    levels_.emplace_back();
    fine_block_size_ = a.block_size;
    fine_row_ptr_ = a.row_ptr;
    fine_col_ = a.col;
  }
  options_ = options;
  fine_ = &a;
  levels_[0].smoother.factorize(a, partitions, fill_level);
  for (int l = 0; l + 1 < options_.max_levels; ++l) {
    if (!coarsen(l)) {
      levels_.resize(l + 1);
      break;
    }
    sum_coarse_blocks(l);
    levels_[l + 1].smoother.factorize(levels_[l + 1].matrix, partitions, 0);
  }
  // after the last push_back: a copy keeps its matrix by reference
  for (int l = 0; l < levels(); ++l) {
    levels_[l].product.assign(matrix(l));
    // the coarsest level has no coarse correction to smooth after
    if (options_.post_smoother == PostSmoother::jacobi && l + 1 < levels())
      invert_diagonal_blocks(matrix(l), levels_[l].diagonal_inverse);
  }
}

// Level l's aggregates (two passes of pairwise matching: about four nodes each) and, where they
// differ from the last setup's, level l + 1's pattern and the map of level l's blocks into it
// (every level below rebuilt too); false where coarsening stops. A setup whose aggregates are
// the last ones (the common case once the flow has settled) keeps the coarse patterns and their
// storage, and only sums the coarse blocks again.
bool AggregationMultigrid::coarsen(int l) {
  const BlockSparseMatrix& fine = matrix(l);
  if (fine.num_rows <= options_.coarsest_nodes)
    return false;
  int pairs = 0;
  std::vector<int> first = pairwise_aggregates(fine, options_.strong_fraction, pairs);
  // the matrix of the first matching's pairs, which the second matching reads: where the pairs
  // are the last setup's, its pattern is kept and its blocks only summed again
  Pairing& pairing = levels_[l].pairing;
  if (pairing.matrix.num_rows != pairs || pairing.aggregate != first) {
    pairing.matrix = galerkin_coarse_matrix(fine, first, pairs);
    pairing.aggregate = std::move(first);
    aggregate_members(pairing.aggregate, pairs, pairing.member_ptr, pairing.members);
    coarse_block_map(fine, pairing.aggregate, pairing.matrix, pairing.coarse_block);
  } else {
    sum_aggregated_blocks(fine, pairing.member_ptr, pairing.members, pairing.coarse_block,
                          pairing.matrix);
  }
  const BlockSparseMatrix& paired = pairing.matrix;
  const std::vector<int>& first_pairs = pairing.aggregate;
  int count = 0;
  const std::vector<int> second = pairwise_aggregates(paired, options_.strong_fraction, count);
  if (count * 3 > fine.num_rows * 2)  // coarsening stalled (under 1.5 nodes per aggregate)
    return false;
  std::vector<int> aggregate(fine.num_rows);
  for (int i = 0; i < fine.num_rows; ++i)
    aggregate[i] = second[first_pairs[i]];
  if (l + 1 < levels() && levels_[l + 1].matrix.num_rows == count &&
      levels_[l].aggregate == aggregate)
    return true;
  Level coarse;
  coarse.matrix = galerkin_coarse_matrix(paired, second, count);  // its values summed again
  Level& level = levels_[l];
  level.aggregate = std::move(aggregate);
  aggregate_members(level.aggregate, count, level.member_ptr, level.members);
  coarse_block_map(fine, level.aggregate, coarse.matrix, level.coarse_block);
  levels_.resize(l + 1);
  levels_.push_back(std::move(coarse));
  return true;
}

// Level l + 1's matrix from level l's: each coarse block the sum of its fine blocks (the Galerkin
// product of piecewise-constant prolongation), a coarse row at a time from its aggregate's
// members in node order: the same sums whatever the number of threads.
void AggregationMultigrid::sum_coarse_blocks(int l) {
  const Level& level = levels_[l];
  sum_aggregated_blocks(matrix(l), level.member_ptr, level.members, level.coarse_block,
                        levels_[l + 1].matrix);
}

void AggregationMultigrid::apply(const std::vector<double>& b, std::vector<double>& x) const {
  x.resize(b.size());
  cycle(0, b, x);
}

// One V(1,1)-cycle from x = 0: ILU smoothing, the residual restricted (summed over each
// aggregate), the coarse correction prolongated (copied to each member) and scaled by the
// factor that minimises the residual it leaves, and a post-smoothing step (Options::post_smoother:
// ILU again, or block Jacobi).
// The scaling: an aggregate's summed blocks can nearly cancel (a pair across a shock, at high
// CFL numbers where the time term is small), and the unscaled correction then threw GMRES off
// (NPARC 0.75, 240 x 60: 80 iterations leaving 0.53 at CFL 1,400, and the run diverged). With
// the minimal-residual factor the coarse correction never increases the residual (Notay and
// Vassilevski 2008, Numer. Linear Algebra Appl. 15:123, whose K-cycle does the same with a
// Krylov step on the coarse level); the cycle then depends on b, so GMRES is flexible.
void AggregationMultigrid::cycle(int l, const std::vector<double>& b,
                                 std::vector<double>& x) const {
  const Level& level = levels_[l];
  const BlockSparseMatrix& a = matrix(l);
  const int nb = a.block_size;
  const int n = a.num_rows;
  const long size = static_cast<long>(x.size());
  level.smoother.apply(b, x);
  if (l + 1 == levels()) {
    for (int sweep = 1; sweep < options_.coarsest_sweeps; ++sweep) {
      residual(level.product, b, x, level.r);
      level.smoother.apply(level.r, level.e);
#pragma omp parallel for schedule(static) if (n > kThreadedNodes)
      for (long k = 0; k < size; ++k)
        x[k] += level.e[k];
    }
    return;
  }
  residual(level.product, b, x, level.r);
  const Level& coarse = levels_[l + 1];
  const int count = coarse.matrix.num_rows;
  coarse.b.resize(static_cast<std::size_t>(nb) * count);
  coarse.x.resize(coarse.b.size());
#pragma omp parallel for schedule(static) if (count > kThreadedNodes)
  for (int c = 0; c < count; ++c) {
    double* to = coarse.b.data() + static_cast<std::size_t>(nb) * c;
    for (int v = 0; v < nb; ++v)
      to[v] = 0.0;
    for (int m = level.member_ptr[c]; m < level.member_ptr[c + 1]; ++m) {
      const double* from = level.r.data() + static_cast<std::size_t>(nb) * level.members[m];
      for (int v = 0; v < nb; ++v)
        to[v] += from[v];
    }
  }
  cycle(l + 1, coarse.b, coarse.x);
  level.e.resize(x.size());
  level.q.resize(x.size());
#pragma omp parallel for schedule(static) if (n > kThreadedNodes)
  for (int i = 0; i < n; ++i) {
    const double* from = coarse.x.data() + static_cast<std::size_t>(nb) * level.aggregate[i];
    double* to = level.e.data() + static_cast<std::size_t>(nb) * i;
    for (int v = 0; v < nb; ++v)
      to[v] = from[v];
  }
  level.product.multiply(level.e, level.q);
  const double qq = dot_product(level.q, level.q);
  const double alpha = qq > 0.0 ? dot_product(level.r, level.q) / qq : 0.0;
#pragma omp parallel for schedule(static) if (n > kThreadedNodes)
  for (long k = 0; k < size; ++k) {
    x[k] += alpha * level.e[k];
    level.r[k] -= alpha * level.q[k];
  }
  if (options_.post_smoother == PostSmoother::jacobi) {
    jacobi_step(level.diagonal_inverse, nb, level.r, x);
    return;
  }
  level.smoother.apply(level.r, level.e);
#pragma omp parallel for schedule(static) if (n > kThreadedNodes)
  for (long k = 0; k < size; ++k)
    x[k] += level.e[k];
}

}  // namespace tfmb::flow
