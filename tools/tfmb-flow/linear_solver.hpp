// Block-sparse (BSR) matrix of the implicit operator with 4x4 (mean flow), 5x5 (mean flow and
// one turbulence equation) or 6x6 blocks, its block ILU(0) factorisation and a
// right-preconditioned restarted GMRES (Saad 2003, Iterative Methods for Sparse Linear Systems,
// alg. 6.10 and 10.4). Reductions use a fixed chunking, so results do not depend on the number
// of threads.
#pragma once

#include <functional>
#include <vector>

#include "gas.hpp"

namespace tfmb::flow {

struct BlockSparseMatrix {
  int num_rows = 0;
  int block_size = 4;         // unknowns per node: 4, 5 or 6
  std::vector<int> row_ptr;   // size num_rows + 1
  std::vector<int> col;       // block column ids, sorted within a row
  std::vector<int> diag_pos;  // position of the diagonal block of each row
  std::vector<double> val;    // block_size^2 per block, row-major

  int block_entries() const { return block_size * block_size; }
  double* block(int pos) { return val.data() + block_entries() * static_cast<std::size_t>(pos); }
  const double* block(int pos) const {
    return val.data() + block_entries() * static_cast<std::size_t>(pos);
  }
  int find(int row, int column) const;  // position or -1
  void set_zero();
  void multiply(const std::vector<double>& x, std::vector<double>& y) const;  // y = A x
  // y_i = (A x)_i for the listed rows only (y sized by the caller; other rows untouched)
  void multiply_rows(const std::vector<double>& x, std::vector<double>& y,
                     const std::vector<int>& rows) const;
};

// A block matrix's values in single precision on its pattern (kept by reference), for the
// products inside a preconditioner: their rounding (6e-8 relative) is far below the
// preconditioner's own error, and they read half the bytes (NPARC 480 x 120's matrix is 37 MB
// in double precision; the products there are bound by memory, not arithmetic).
struct SinglePrecisionMatrix {
  const BlockSparseMatrix* pattern = nullptr;
  std::vector<float> val;
  void assign(const BlockSparseMatrix& a);  // a must outlive the copy's use
  void multiply(const std::vector<double>& x, std::vector<double>& y) const;  // y = A x
};

// Every deterministic reduction (GMRES's dot products and norms, the matrix-free product's norm)
// cuts its range [0, n) into these fixed chunks, [chunk_begin(n, c), chunk_begin(n, c + 1)), and
// adds the chunks' results in chunk order: the same bits whatever the number of threads.
inline constexpr int kReductionChunks = 64;
inline std::size_t chunk_begin(std::size_t n, int chunk) {
  return n * chunk / kReductionChunks;
}

// Pattern of a node graph given by its edges: diagonal plus both off-diagonals per edge.
BlockSparseMatrix make_pattern(int num_nodes, const std::vector<std::array<int, 2>>& edges,
                               int block_size = 4);

// x = M^-1 b of a preconditioner. A fixed linear M (flexible() false) lets GMRES keep only the
// Krylov basis; one that depends on b (flexible() true) makes it keep the preconditioned basis
// too (flexible GMRES, Saad 1993, SIAM J. Sci. Comput. 14:461).
class Preconditioner {
 public:
  virtual ~Preconditioner() = default;
  virtual void apply(const std::vector<double>& b, std::vector<double>& x) const = 0;
  virtual bool flexible() const { return false; }
};

// Block ILU(k) (Saad 2003, Iterative Methods for Sparse Linear Systems, 2nd ed., sec. 10.3.3:
// level of fill). k = 0 keeps the pattern of the matrix; k >= 1 also keeps the fill-in entries
// whose level, lev(i,j) = min over k of lev(i,k) + lev(k,j) + 1, is at most k.
class BlockIlu0 final : public Preconditioner {
 public:
  // Factorises a copy of the matrix in the pattern of level `fill_level` (in double precision);
  // diagonal blocks are stored inverted. The factors used by apply() are kept in single
  // precision: the triangular solves are memory bound, and a preconditioner needs no more
  // digits. With partitions > 1, the rows are cut into that many contiguous ranges and
  // couplings between ranges are dropped (block-Jacobi of ILU blocks): the ranges are
  // factorised and solved in parallel, and the result does not depend on the thread count.
  // The fill pattern is computed once per matrix pattern and kept.
  void factorize(const BlockSparseMatrix& a, int partitions = 1, int fill_level = 0);
  void apply(const std::vector<double>& b, std::vector<double>& x) const override;  // (LU)^-1 b
  std::size_t factor_blocks() const { return lu_.col.size(); }  // blocks stored in L and U

 private:
  void build_fill_pattern(const BlockSparseMatrix& a);
  BlockSparseMatrix lu_;
  std::vector<float> factors_;  // lu_.val in single precision
  std::vector<int> pos_of_col_;
  int partitions_ = 1;
  int fill_level_ = 0;
  // the pattern lu_ was built for, and where each block of that matrix goes in lu_
  std::vector<int> pattern_row_ptr_, pattern_col_;
  std::vector<int> scatter_;
};

struct GmresResult {
  int iterations = 0;
  double relative_residual = 0.0;
};

// Krylov basis storage, kept between calls so that no solve allocates. A solve to a relative
// tolerance of at least kSinglePrecisionBasisTolerance keeps its basis (and a flexible
// preconditioner's preconditioned basis) in single precision, v_single and z_single; a tighter
// one in double precision, v and z.
struct GmresWorkspace {
  std::vector<std::vector<double>> v, z;
  std::vector<std::vector<float>> v_single, z_single;
  std::vector<double> h, cs, sn, g, w, r, y;
  std::vector<double> current, preconditioned;  // v_j as stored, and M^-1 v_j
  std::vector<double> column;  // one column of the Hessenberg matrix, as orthogonalised
};

// The tightest relative tolerance whose solves keep a single-precision basis (tighter ones keep
// a double-precision basis). A single-precision basis (Aliaga et al. 2023, "Compressed basis
// GMRES on high-performance graphics processing units", Int. J. High Perform. Comput. Appl.
// 37:82) rounds each vector to 6e-8 relative, which perturbs the Arnoldi relation, and so the
// residual GMRES estimates, by about that much; the arithmetic stays in double precision and
// every restart recomputes the true residual. The nonlinear steps solve to 0.02-0.4
// (matrix-free forcing down to 1e-3), where the basis's orthogonalisation is bound by memory:
// half the bytes.
inline constexpr double kSinglePrecisionBasisTolerance = 1e-4;

// Solves A x = b to ||b - A x|| <= rel_tol ||b|| or max_iterations, starting from x = 0.
GmresResult gmres(const BlockSparseMatrix& a, const Preconditioner& precond,
                  const std::vector<double>& b, std::vector<double>& x, double rel_tol, int restart,
                  int max_iterations, GmresWorkspace& workspace);
GmresResult gmres(const BlockSparseMatrix& a, const Preconditioner& precond,
                  const std::vector<double>& b, std::vector<double>& x, double rel_tol, int restart,
                  int max_iterations);

// The same with the operator given as y = A x (e.g. matrix-free, by differences of residuals).
using LinearOperator = std::function<void(const std::vector<double>& x, std::vector<double>& y)>;
GmresResult gmres(const LinearOperator& a, const Preconditioner& precond,
                  const std::vector<double>& b, std::vector<double>& x, double rel_tol, int restart,
                  int max_iterations, GmresWorkspace& workspace);

// Deterministic dot product (fixed chunk partition, ordered sum of chunk sums).
double dot_product(const std::vector<double>& a, const std::vector<double>& b);

// Inverse of a size x size block (size 4, 5 or 6) by Gauss-Jordan with partial pivoting.
// Returns false if singular.
bool invert_block(const double* a, double* inverse, int size = 4);

}  // namespace tfmb::flow
