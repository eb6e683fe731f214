#include "linear_solver.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "tfmb/common/assert.hpp"

namespace tfmb::flow {

namespace {

// The kernels are templates on the block size B so that the compiler unrolls them; the
// matrix carries B at run time and dispatch() picks the instance.

// c -= a * b for BxB blocks
template <int B>
inline void block_mul_sub(const double* a, const double* b, double* c) {
  for (int i = 0; i < B; ++i) {
    for (int k = 0; k < B; ++k) {
      const double aik = a[B * i + k];
      for (int j = 0; j < B; ++j)
        c[B * i + j] -= aik * b[B * k + j];
    }
  }
}
template <int B>
inline void block_mul(const double* a, const double* b, double* c) {
  for (int i = 0; i < B * B; ++i)
    c[i] = 0.0;
  for (int i = 0; i < B; ++i) {
    for (int k = 0; k < B; ++k) {
      const double aik = a[B * i + k];
      for (int j = 0; j < B; ++j)
        c[B * i + j] += aik * b[B * k + j];
    }
  }
}

template <int B>
bool invert_block_fixed(const double* a, double* inv) {
  double m[B][2 * B];
  for (int i = 0; i < B; ++i) {
    for (int j = 0; j < B; ++j) {
      m[i][j] = a[B * i + j];
      m[i][B + j] = i == j ? 1.0 : 0.0;
    }
  }
  for (int c = 0; c < B; ++c) {
    int p = c;
    for (int r = c + 1; r < B; ++r) {
      if (std::abs(m[r][c]) > std::abs(m[p][c]))
        p = r;
    }
    if (m[p][c] == 0.0 || !std::isfinite(m[p][c]))
      return false;
    if (p != c)
      std::swap(m[p], m[c]);
    const double d = 1.0 / m[c][c];
    for (int j = 0; j < 2 * B; ++j)
      m[c][j] *= d;
    for (int r = 0; r < B; ++r) {
      if (r == c)
        continue;
      const double f = m[r][c];
      if (f == 0.0)
        continue;
      for (int j = 0; j < 2 * B; ++j)
        m[r][j] -= f * m[c][j];
    }
  }
  for (int i = 0; i < B; ++i) {
    for (int j = 0; j < B; ++j)
      inv[B * i + j] = m[i][B + j];
  }
  return true;
}

// Calls f(std::integral_constant<int, B>) for the run-time block size.
template <typename F>
decltype(auto) dispatch(int block_size, F&& f) {
  switch (block_size) {
    case 4:
      return f(std::integral_constant<int, 4>{});
    case 5:
      return f(std::integral_constant<int, 5>{});
    case 6:
      return f(std::integral_constant<int, 6>{});
    default:
      throw std::invalid_argument("flow: block size " + std::to_string(block_size) +
                                  " (expected 4, 5 or 6)");
  }
}

// y_i = (A x)_i for block row i, the blocks' values from `values`: the matrix's own (row-major
// blocks), or a single-precision copy (SinglePrecisionMatrix, column-major blocks)
template <int B, typename Value>
inline void multiply_row(const BlockSparseMatrix& m, const Value* values,
                         const std::vector<double>& x, std::vector<double>& y, int i) {
  double acc[B] = {};
  for (int p = m.row_ptr[i]; p < m.row_ptr[i + 1]; ++p) {
    const Value* a = values + B * B * static_cast<std::size_t>(p);
    const double* xc = x.data() + B * static_cast<std::size_t>(m.col[p]);
    if constexpr (std::is_same_v<Value, double>) {
      for (int r = 0; r < B; ++r) {
        double s = 0.0;
        for (int c = 0; c < B; ++c)
          s += a[B * r + c] * xc[c];
        acc[r] += s;
      }
    } else {
      // column by column: each column's B floats are contiguous, so they widen as a vector;
      // row by row the compiler gathered single floats across rows (NPARC 240 x 60: the float
      // product took 1.45 times the double one's samples)
      for (int c = 0; c < B; ++c)
        for (int r = 0; r < B; ++r)
          acc[r] += static_cast<double>(a[B * c + r]) * xc[c];
    }
  }
  for (int r = 0; r < B; ++r)
    y[B * static_cast<std::size_t>(i) + r] = acc[r];
}

// y = A x on m's pattern with the values `values`
template <int B, typename Value>
void multiply_fixed(const BlockSparseMatrix& m, const Value* values, const std::vector<double>& x,
                    std::vector<double>& y) {
  const int n = m.num_rows;
#pragma omp parallel for schedule(static) if (n > 1000)
  for (int i = 0; i < n; ++i)
    multiply_row<B>(m, values, x, y, i);
}

template <int B>
void multiply_rows_fixed(const BlockSparseMatrix& m, const std::vector<double>& x,
                         std::vector<double>& y, const std::vector<int>& rows) {
  // threaded: on nasa-2dcd's case mesh (51k nodes) the serial loop was 1 % of a two-thread run,
  // and its fewer than 1000 rows (the walls' and the imposed ones) are dense enough to pay
  const int count = static_cast<int>(rows.size());
#pragma omp parallel for schedule(static) if (count > 100)
  for (int k = 0; k < count; ++k)
    multiply_row<B>(m, m.val.data(), x, y, rows[k]);
}

template <int B>
void factorize_fixed(BlockSparseMatrix& lu, std::vector<int>& pos_of_col, int partitions) {
  const int n = lu.num_rows;
  // Each partition only reads and writes rows and columns of its own range, so the partitions
  // are independent (and pos_of_col can be shared).
#pragma omp parallel for schedule(static, 1)
  for (int part = 0; part < partitions; ++part) {
    const int lo = static_cast<int>(static_cast<long>(n) * part / partitions);
    const int hi = static_cast<int>(static_cast<long>(n) * (part + 1) / partitions);
    double tmp[B * B];
    for (int i = lo; i < hi; ++i) {
      for (int p = lu.row_ptr[i]; p < lu.row_ptr[i + 1]; ++p) {
        const int c = lu.col[p];
        if (c >= lo && c < hi)
          pos_of_col[c] = p;
      }
      for (int p = lu.row_ptr[i]; p < lu.diag_pos[i]; ++p) {
        const int k = lu.col[p];
        if (k < lo)
          continue;
        // L_ik = A_ik * inv(U_kk)
        block_mul<B>(lu.block(p), lu.block(lu.diag_pos[k]), tmp);
        std::copy(tmp, tmp + B * B, lu.block(p));
        for (int q = lu.diag_pos[k] + 1; q < lu.row_ptr[k + 1]; ++q) {
          const int c = lu.col[q];
          if (c >= hi)
            continue;
          const int target = pos_of_col[c];
          if (target >= 0)
            block_mul_sub<B>(lu.block(p), lu.block(q), lu.block(target));
        }
      }
      double* d = lu.block(lu.diag_pos[i]);
      if (!invert_block_fixed<B>(d, tmp)) {
        // A singular pivot only happens for a broken operator; fall back to the identity.
        for (int k = 0; k < B * B; ++k)
          tmp[k] = (k % (B + 1) == 0) ? 1.0 : 0.0;
      }
      std::copy(tmp, tmp + B * B, d);
      for (int p = lu.row_ptr[i]; p < lu.row_ptr[i + 1]; ++p) {
        const int c = lu.col[p];
        if (c >= lo && c < hi)
          pos_of_col[c] = -1;
      }
    }
  }
}

template <int B>
void ilu_apply_fixed(const BlockSparseMatrix& lu, const std::vector<float>& factors, int partitions,
                     const std::vector<double>& b, std::vector<double>& x) {
  const int n = lu.num_rows;
  const float* f = factors.data();
  constexpr std::size_t kEntries = B * B;
  auto sub = [](const float* a, const double* v, double* y) {  // y -= A v
    for (int r = 0; r < B; ++r) {
      double s = 0.0;
      for (int c = 0; c < B; ++c)
        s += static_cast<double>(a[B * r + c]) * v[c];
      y[r] -= s;
    }
  };
#pragma omp parallel for schedule(static, 1)
  for (int part = 0; part < partitions; ++part) {
    const int lo = static_cast<int>(static_cast<long>(n) * part / partitions);
    const int hi = static_cast<int>(static_cast<long>(n) * (part + 1) / partitions);
    std::copy(b.begin() + B * static_cast<std::size_t>(lo),
              b.begin() + B * static_cast<std::size_t>(hi),
              x.begin() + B * static_cast<std::size_t>(lo));
    for (int i = lo; i < hi; ++i) {
      double* xi = x.data() + B * static_cast<std::size_t>(i);
      for (int p = lu.row_ptr[i]; p < lu.diag_pos[i]; ++p) {
        const int c = lu.col[p];
        if (c >= lo)
          sub(f + kEntries * static_cast<std::size_t>(p),
              x.data() + B * static_cast<std::size_t>(c), xi);
      }
    }
    for (int i = hi - 1; i >= lo; --i) {
      double* xi = x.data() + B * static_cast<std::size_t>(i);
      for (int p = lu.diag_pos[i] + 1; p < lu.row_ptr[i + 1]; ++p) {
        const int c = lu.col[p];
        if (c < hi)
          sub(f + kEntries * static_cast<std::size_t>(p),
              x.data() + B * static_cast<std::size_t>(c), xi);
      }
      const float* d = f + kEntries * static_cast<std::size_t>(lu.diag_pos[i]);
      double r[B];
      for (int k = 0; k < B; ++k)
        r[k] = xi[k];
      for (int k = 0; k < B; ++k) {
        double s = 0.0;
        for (int c = 0; c < B; ++c)
          s += static_cast<double>(d[B * k + c]) * r[c];
        xi[k] = s;
      }
    }
  }
}

// Below 8000 entries threads cost more than they save.
constexpr std::size_t kThreadedLength = 8000;

}  // namespace

bool invert_block(const double* a, double* inv, int size) {
  return dispatch(size, [&](auto b) { return invert_block_fixed<decltype(b)::value>(a, inv); });
}

int BlockSparseMatrix::find(int row, int column) const {
  TFMB_ASSERT(row >= 0 && row < num_rows, "row " << row << " of a matrix of " << num_rows);
  const auto first = col.begin() + row_ptr[row];
  const auto last = col.begin() + row_ptr[row + 1];
  const auto it = std::lower_bound(first, last, column);
  return (it != last && *it == column) ? static_cast<int>(it - col.begin()) : -1;
}

void BlockSparseMatrix::set_zero() {
  // threaded: on 58k nodes the values are 52 MB, and a serial fill was 2 % of a two-thread run
  const std::size_t size = val.size();
  double* v = val.data();
#pragma omp parallel for schedule(static) if (size > kThreadedLength)
  for (int c = 0; c < kReductionChunks; ++c)
    std::fill(v + size * c / kReductionChunks, v + size * (c + 1) / kReductionChunks, 0.0);
}

void BlockSparseMatrix::multiply(const std::vector<double>& x, std::vector<double>& y) const {
  y.resize(block_size * static_cast<std::size_t>(num_rows));
  dispatch(block_size,
           [&](auto b) { multiply_fixed<decltype(b)::value>(*this, val.data(), x, y); });
}

void SinglePrecisionMatrix::assign(const BlockSparseMatrix& a) {
  pattern = &a;
  val.resize(a.val.size());
  const long size = static_cast<long>(a.val.size());
  const int b = a.block_size;
  const long blocks = size / (b * b);
#pragma omp parallel for schedule(static) if (size > 16000)
  for (long p = 0; p < blocks; ++p) {
    const double* in = a.val.data() + p * b * b;
    float* out = val.data() + p * b * b;
    for (int r = 0; r < b; ++r)
      for (int c = 0; c < b; ++c)
        out[b * c + r] = static_cast<float>(in[b * r + c]);  // column-major: multiply_row
  }
}

void SinglePrecisionMatrix::multiply(const std::vector<double>& x, std::vector<double>& y) const {
  const BlockSparseMatrix& m = *pattern;
  y.resize(m.block_size * static_cast<std::size_t>(m.num_rows));
  dispatch(m.block_size, [&](auto b) { multiply_fixed<decltype(b)::value>(m, val.data(), x, y); });
}

void BlockSparseMatrix::multiply_rows(const std::vector<double>& x, std::vector<double>& y,
                                      const std::vector<int>& rows) const {
  dispatch(block_size, [&](auto b) { multiply_rows_fixed<decltype(b)::value>(*this, x, y, rows); });
}

BlockSparseMatrix make_pattern(int n, const std::vector<std::array<int, 2>>& edges,
                               int block_size) {
  std::vector<std::vector<int>> rows(n);
  for (int i = 0; i < n; ++i)
    rows[i].push_back(i);
  for (const auto& e : edges) {
    rows[e[0]].push_back(e[1]);
    rows[e[1]].push_back(e[0]);
  }
  BlockSparseMatrix m;
  m.num_rows = n;
  m.block_size = block_size;
  dispatch(block_size, [](auto) {});  // rejects an unsupported size here
  m.row_ptr.assign(n + 1, 0);
  m.diag_pos.resize(n);
  for (int i = 0; i < n; ++i) {
    std::sort(rows[i].begin(), rows[i].end());
    rows[i].erase(std::unique(rows[i].begin(), rows[i].end()), rows[i].end());
    m.row_ptr[i + 1] = m.row_ptr[i] + static_cast<int>(rows[i].size());
    for (int c : rows[i]) {
      if (c == i)
        m.diag_pos[i] = static_cast<int>(m.col.size());
      m.col.push_back(c);
    }
  }
  m.val.assign(static_cast<std::size_t>(m.block_entries()) * m.col.size(), 0.0);
  return m;
}

void BlockIlu0::build_fill_pattern(const BlockSparseMatrix& a) {
  // Symbolic ILU(k) row by row (Saad 2003, algorithm 10.5): the row's entries start at level
  // 0; eliminating with an earlier row k (in increasing column order) adds the entries of U's
  // row k at lev(i,k) + lev(k,j) + 1 where that is at most fill_level_. Fill between two
  // partitions would be dropped by the factorisation, so it is not created.
  const int n = a.num_rows;
  std::vector<std::vector<int>> cols(n), levels(n);
  std::vector<int> level_of(n, -1);  // level of column c in the current row, -1 if absent
  std::vector<int> row_cols;
  for (int part = 0; part < partitions_; ++part) {
    const int lo = static_cast<int>(static_cast<long>(n) * part / partitions_);
    const int hi = static_cast<int>(static_cast<long>(n) * (part + 1) / partitions_);
    for (int i = lo; i < hi; ++i) {
      row_cols.clear();
      for (int p = a.row_ptr[i]; p < a.row_ptr[i + 1]; ++p) {
        level_of[a.col[p]] = 0;
        row_cols.push_back(a.col[p]);
      }
      // eliminate in increasing column order; fill may add columns below i still to visit
      std::sort(row_cols.begin(), row_cols.end());
      for (std::size_t m = 0; m < row_cols.size() && row_cols[m] < i; ++m) {
        const int k = row_cols[m];
        if (k < lo)
          continue;
        const int lik = level_of[k];
        for (std::size_t q = 0; q < cols[k].size(); ++q) {
          const int j = cols[k][q];
          if (j <= k || j >= hi)
            continue;
          const int lev = lik + levels[k][q] + 1;
          if (lev > fill_level_)
            continue;
          if (level_of[j] < 0) {
            level_of[j] = lev;
            // keep row_cols sorted beyond m so that a new column below i is eliminated too
            row_cols.insert(std::upper_bound(row_cols.begin() + m + 1, row_cols.end(), j), j);
          } else {
            level_of[j] = std::min(level_of[j], lev);
          }
        }
      }
      cols[i] = row_cols;
      levels[i].resize(row_cols.size());
      for (std::size_t m = 0; m < row_cols.size(); ++m) {
        levels[i][m] = level_of[row_cols[m]];
        level_of[row_cols[m]] = -1;
      }
    }
  }
  lu_.num_rows = n;
  lu_.block_size = a.block_size;
  lu_.row_ptr.assign(n + 1, 0);
  lu_.col.clear();
  lu_.diag_pos.assign(n, -1);
  for (int i = 0; i < n; ++i) {
    for (int c : cols[i]) {
      if (c == i)
        lu_.diag_pos[i] = static_cast<int>(lu_.col.size());
      lu_.col.push_back(c);
    }
    lu_.row_ptr[i + 1] = static_cast<int>(lu_.col.size());
  }
  scatter_.resize(a.col.size());
  for (int i = 0; i < n; ++i) {
    for (int p = a.row_ptr[i]; p < a.row_ptr[i + 1]; ++p) {
      scatter_[p] = lu_.find(i, a.col[p]);
      // every row starts from all of its matrix entries (level 0), so each one has a place; a
      // missing one would make factorize() copy its block to a negative offset
      TFMB_ASSERT(scatter_[p] >= 0,
                  "ILU fill pattern lacks the matrix block (" << i << ", " << a.col[p] << ")");
    }
  }
  pattern_row_ptr_ = a.row_ptr;
  pattern_col_ = a.col;
}

void BlockIlu0::factorize(const BlockSparseMatrix& a, int partitions, int fill_level) {
  const int n = a.num_rows;
  partitions = std::max(1, std::min(partitions, n));
  if (fill_level <= 0) {
    if (lu_.block_size != a.block_size || lu_.row_ptr != a.row_ptr || lu_.col != a.col) {
      lu_ = a;
    } else {
      // same pattern as the last factorisation: copy the values only, threaded (a serial copy
      // of the 52 MB of a 58k-node matrix was 1.5 % of a two-thread run)
      const std::size_t size = a.val.size();
      const double* from = a.val.data();
      double* to = lu_.val.data();
#pragma omp parallel for schedule(static) if (size > kThreadedLength)
      for (int c = 0; c < kReductionChunks; ++c)
        std::copy(from + size * c / kReductionChunks, from + size * (c + 1) / kReductionChunks,
                  to + size * c / kReductionChunks);
    }
    pattern_col_.clear();
  } else {
    if (fill_level != fill_level_ || partitions != partitions_ || a.block_size != lu_.block_size ||
        a.row_ptr != pattern_row_ptr_ || a.col != pattern_col_) {
      fill_level_ = fill_level;
      partitions_ = partitions;
      build_fill_pattern(a);
    }
    // the fill blocks zeroed and the matrix's blocks scattered into their places, both threaded:
    // serial, the zeroing and the copy were 2.6 % of a two-thread run on nasa-2dcd's case mesh
    // (51k nodes, ILU(1)), with the second thread idle
    const int be = a.block_entries();
    lu_.val.resize(static_cast<std::size_t>(be) * lu_.col.size());
    lu_.set_zero();
    const long blocks = static_cast<long>(scatter_.size());
    const bool threaded = lu_.val.size() > kThreadedLength;
    const double* from = a.val.data();
    double* to = lu_.val.data();
#pragma omp parallel for schedule(static) if (threaded)
    for (long p = 0; p < blocks; ++p)
      std::copy(from + be * p, from + be * (p + 1),
                to + be * static_cast<std::size_t>(scatter_[p]));
  }
  fill_level_ = fill_level;
  partitions_ = partitions;
  pos_of_col_.assign(n, -1);
  dispatch(lu_.block_size,
           [&](auto b) { factorize_fixed<decltype(b)::value>(lu_, pos_of_col_, partitions_); });
  const std::size_t size = lu_.val.size();
  factors_.resize(size);
  const double* from = lu_.val.data();
  float* to = factors_.data();
#pragma omp parallel for schedule(static) if (size > kThreadedLength)
  for (int c = 0; c < kReductionChunks; ++c) {
    for (std::size_t k = size * c / kReductionChunks; k < size * (c + 1) / kReductionChunks; ++k)
      to[k] = static_cast<float>(from[k]);
  }
}

void BlockIlu0::apply(const std::vector<double>& b, std::vector<double>& x) const {
  x.resize(b.size());
  dispatch(lu_.block_size, [&](auto bs) {
    ilu_apply_fixed<decltype(bs)::value>(lu_, factors_, partitions_, b, x);
  });
}

namespace {

// The vector loops of GMRES, threaded over the same kReductionChunks fixed chunks as every
// reduction, so that a sum is added in one order whatever the thread count (deterministic results)
// and the element-wise updates give the same bits as serial loops.

template <class ChunkSum>
double chunked_sum(std::size_t n, ChunkSum chunk_sum) {
  double partial[kReductionChunks];
#pragma omp parallel for schedule(static) if (n > kThreadedLength)
  for (int c = 0; c < kReductionChunks; ++c)
    partial[c] = chunk_sum(chunk_begin(n, c), chunk_begin(n, c + 1));
  double s = 0.0;
  for (double p : partial)
    s += p;
  return s;
}

template <class Element>
void for_each_entry(std::size_t n, Element element) {
#pragma omp parallel for schedule(static) if (n > kThreadedLength)
  for (int c = 0; c < kReductionChunks; ++c) {
    const std::size_t last = chunk_begin(n, c + 1);
    for (std::size_t k = chunk_begin(n, c); k < last; ++k)
      element(k);
  }
}

// Modified Gram-Schmidt of w against v[0..j], its norm and the next basis vector
// v[j + 1] = w / |w| (also written to `current` in double precision, as the basis holds it: the
// next iteration's input), in one parallel region: column[i] = w . v_i (w already reduced by
// v_0..v_{i-1}), column[j + 1] = |w|; returns |w|. Each projection's subtraction is fused with the
// next projection and the last with the norm (one pass over memory each). The chunks and the order
// of their sums are those of chunked_sum(), so the bits are the same whatever the thread count. One
// region with a barrier per projection instead of a fork and a join per projection: with
// OMP_WAIT_POLICY=passive each of them puts the idle thread to sleep and wakes it again.
template <class Basis>
double orthogonalize(std::vector<double>& w, std::vector<std::vector<Basis>>& v, int j,
                     double* column, std::vector<double>& current) {
  const std::size_t n = w.size();
  double* wp = w.data();
  Basis* next = v[j + 1].data();
  double* next_exact = current.data();
  // double-buffered chunk sums: a thread may start projection i + 1 while another still adds
  // up projection i's sums; it cannot reach i + 2 before that one has passed i + 1's barrier
  double partial[2][kReductionChunks];
  double norm = 0.0;
#pragma omp parallel if (n > kThreadedLength)
  {
    double previous = 0.0;  // the last projection, the same in every thread
    for (int i = 0; i <= j + 1; ++i) {
      const Basis* subtract = i > 0 ? v[i - 1].data() : nullptr;
      const Basis* onto = i <= j ? v[i].data() : nullptr;  // nullptr: |w|^2
      double* sums = partial[i % 2];
      const double h = previous;
#pragma omp for schedule(static)
      for (int c = 0; c < kReductionChunks; ++c) {
        const std::size_t first = chunk_begin(n, c);
        const std::size_t last = chunk_begin(n, c + 1);
        double s = 0.0;
        if (subtract && onto) {
          for (std::size_t k = first; k < last; ++k) {
            wp[k] -= h * subtract[k];
            s += wp[k] * onto[k];
          }
        } else if (subtract) {
          for (std::size_t k = first; k < last; ++k) {
            wp[k] -= h * subtract[k];
            s += wp[k] * wp[k];
          }
        } else {  // i = 0: nothing to subtract yet
          for (std::size_t k = first; k < last; ++k)
            s += wp[k] * onto[k];
        }
        sums[c] = s;
      }
      double s = 0.0;
      for (int c = 0; c < kReductionChunks; ++c)
        s += sums[c];
      previous = s;
#pragma omp master
      column[i] = i <= j ? s : std::sqrt(s);
    }
    const double w_norm = std::sqrt(previous);
#pragma omp master
    norm = w_norm;
    if (w_norm > 0.0) {
#pragma omp for schedule(static) nowait
      for (int c = 0; c < kReductionChunks; ++c) {
        const std::size_t last = chunk_begin(n, c + 1);
        for (std::size_t k = chunk_begin(n, c); k < last; ++k) {
          next[k] = static_cast<Basis>(wp[k] / w_norm);
          next_exact[k] = next[k];  // what the basis holds
        }
      }
    }
  }
  return norm;
}

}  // namespace

double dot_product(const std::vector<double>& a, const std::vector<double>& b) {
  const double* ap = a.data();
  const double* bp = b.data();
  return chunked_sum(a.size(), [=](std::size_t first, std::size_t last) {
    double s = 0.0;
    for (std::size_t i = first; i < last; ++i)
      s += ap[i] * bp[i];
    return s;
  });
}

GmresResult gmres(const BlockSparseMatrix& a, const Preconditioner& m, const std::vector<double>& b,
                  std::vector<double>& x, double rel_tol, int restart, int max_iterations) {
  GmresWorkspace workspace;
  return gmres(a, m, b, x, rel_tol, restart, max_iterations, workspace);
}

GmresResult gmres(const BlockSparseMatrix& a, const Preconditioner& m, const std::vector<double>& b,
                  std::vector<double>& x, double rel_tol, int restart, int max_iterations,
                  GmresWorkspace& ws) {
  const LinearOperator multiply = [&a](const std::vector<double>& in, std::vector<double>& out) {
    a.multiply(in, out);
  };
  return gmres(multiply, m, b, x, rel_tol, restart, max_iterations, ws);
}

namespace {

// The workspace's basis and preconditioned basis in the precision Basis.
template <class Basis>
struct BasisStorage {
  std::vector<std::vector<Basis>>& v;
  std::vector<std::vector<Basis>>& z;
};
template <class Basis>
BasisStorage<Basis> basis_storage(GmresWorkspace& ws) {
  if constexpr (std::is_same_v<Basis, float>)
    return {ws.v_single, ws.z_single};
  else
    return {ws.v, ws.z};
}

// Restarted GMRES with its basis stored as Basis (double, or float for the loose solves).
template <class Basis>
GmresResult gmres_with_basis(const LinearOperator& a, const Preconditioner& m,
                             const std::vector<double>& b, std::vector<double>& x, double rel_tol,
                             int restart, int max_iterations, GmresWorkspace& ws) {
  const std::size_t n = b.size();
  x.assign(n, 0.0);
  GmresResult result;
  const double b_norm = std::sqrt(dot_product(b, b));
  if (b_norm == 0.0)
    return result;
  const BasisStorage<Basis> storage = basis_storage<Basis>(ws);
  auto& v = storage.v;
  // the basis only grows: a Newton step's 81 vectors freed for a defect-correction step's 21
  // were allocated again, page fault by page fault, by the next Newton step
  if (v.size() < static_cast<std::size_t>(restart + 1))
    v.resize(restart + 1);
  for (auto& vec : v)
    vec.resize(n);
  const bool flexible = m.flexible();
  auto& z = storage.z;
  if (flexible && z.size() < static_cast<std::size_t>(restart))
    z.resize(restart);
  for (std::size_t i = 0; flexible && i < z.size(); ++i)
    z[i].resize(n);
  ws.h.assign((restart + 1) * restart, 0.0);
  ws.cs.assign(restart, 0.0);
  ws.sn.assign(restart, 0.0);
  ws.g.assign(restart + 1, 0.0);
  ws.w.resize(n);
  ws.current.resize(n);
  ws.preconditioned.resize(n);
  auto& cs = ws.cs;
  auto& sn = ws.sn;
  auto& g = ws.g;
  auto& w = ws.w;
  auto& current = ws.current;                // v_j in double precision, as the basis holds it
  auto& preconditioned = ws.preconditioned;  // M^-1 v_j, or M^-1 (V y)
  auto H = [&](int i, int j) -> double& { return ws.h[i * restart + j]; };
  std::vector<double>& r = ws.r;
  r = b;  // x = 0
  double beta = b_norm;
  while (true) {
    for_each_entry(n, [&](std::size_t k) {
      v[0][k] = static_cast<Basis>(r[k] / beta);
      current[k] = v[0][k];
    });
    std::fill(g.begin(), g.end(), 0.0);
    g[0] = beta;
    int j = 0;
    for (; j < restart && result.iterations < max_iterations; ++j) {
      ++result.iterations;
      m.apply(current, preconditioned);
      a(preconditioned, w);
      if (flexible) {
        Basis* zj = z[j].data();
        for_each_entry(n, [&](std::size_t k) { zj[k] = static_cast<Basis>(preconditioned[k]); });
      }
      // modified Gram-Schmidt: H(i, j) = w . v_i, w -= H(i, j) v_i for i = 0..j, then
      // H(j + 1, j) = |w| and v_{j+1} = w / |w|
      std::vector<double>& column = ws.column;
      column.resize(j + 2);
      const double wn = orthogonalize(w, v, j, column.data(), current);
      for (int i = 0; i <= j + 1; ++i)
        H(i, j) = column[i];
      for (int i = 0; i < j; ++i) {  // apply earlier Givens rotations
        const double t = cs[i] * H(i, j) + sn[i] * H(i + 1, j);
        H(i + 1, j) = -sn[i] * H(i, j) + cs[i] * H(i + 1, j);
        H(i, j) = t;
      }
      const double den = std::hypot(H(j, j), H(j + 1, j));
      cs[j] = den > 0.0 ? H(j, j) / den : 1.0;
      sn[j] = den > 0.0 ? H(j + 1, j) / den : 0.0;
      H(j, j) = den;
      H(j + 1, j) = 0.0;
      g[j + 1] = -sn[j] * g[j];
      g[j] = cs[j] * g[j];
      result.relative_residual = std::abs(g[j + 1]) / b_norm;
      if (result.relative_residual <= rel_tol || wn == 0.0) {
        ++j;
        break;
      }
    }
    // x += M^-1 (V y) with H y = g (upper triangular): one preconditioner application instead
    // of storing the preconditioned basis (right preconditioning, fixed M); a flexible M's
    // basis is stored, x += Z y.
    std::vector<double>& y = ws.y;
    y.assign(j, 0.0);
    for (int i = j - 1; i >= 0; --i) {
      double s = g[i];
      for (int k = i + 1; k < j; ++k)
        s -= H(i, k) * y[k];
      y[i] = s / H(i, i);
    }
    if (flexible) {
      for_each_entry(n, [&](std::size_t k) {
        double s = 0.0;
        for (int i = 0; i < j; ++i)
          s += y[i] * z[i][k];
        x[k] += s;
      });
    } else {
      for_each_entry(n, [&](std::size_t k) {
        double s = 0.0;
        for (int i = 0; i < j; ++i)
          s += y[i] * v[i][k];
        w[k] = s;
      });
      m.apply(w, preconditioned);
      for_each_entry(n, [&](std::size_t k) { x[k] += preconditioned[k]; });
    }
    if (result.relative_residual <= rel_tol || result.iterations >= max_iterations)
      break;
    a(x, w);
    for_each_entry(n, [&](std::size_t k) { r[k] = b[k] - w[k]; });
    beta = std::sqrt(dot_product(r, r));
    result.relative_residual = beta / b_norm;
    if (result.relative_residual <= rel_tol)
      break;
  }
  return result;
}

}  // namespace

GmresResult gmres(const LinearOperator& a, const Preconditioner& m, const std::vector<double>& b,
                  std::vector<double>& x, double rel_tol, int restart, int max_iterations,
                  GmresWorkspace& ws) {
  if (rel_tol >= kSinglePrecisionBasisTolerance)
    return gmres_with_basis<float>(a, m, b, x, rel_tol, restart, max_iterations, ws);
  return gmres_with_basis<double>(a, m, b, x, rel_tol, restart, max_iterations, ws);
}

}  // namespace tfmb::flow
