#include "linear_solver.hpp"

#include <algorithm>
#include <cmath>

namespace tfmb::flow {

namespace {

// c -= a * b for 4x4 blocks
inline void block_mul_sub(const double* a, const double* b, double* c) {
  for (int i = 0; i < 4; ++i) {
    for (int k = 0; k < 4; ++k) {
      const double aik = a[4 * i + k];
      for (int j = 0; j < 4; ++j)
        c[4 * i + j] -= aik * b[4 * k + j];
    }
  }
}
inline void block_mul(const double* a, const double* b, double* c) {
  for (int i = 0; i < 16; ++i)
    c[i] = 0.0;
  for (int i = 0; i < 4; ++i) {
    for (int k = 0; k < 4; ++k) {
      const double aik = a[4 * i + k];
      for (int j = 0; j < 4; ++j)
        c[4 * i + j] += aik * b[4 * k + j];
    }
  }
}
// y -= A x (4-vectors)
inline void block_vec_sub(const double* a, const double* x, double* y) {
  for (int i = 0; i < 4; ++i) {
    y[i] -= a[4 * i] * x[0] + a[4 * i + 1] * x[1] + a[4 * i + 2] * x[2] + a[4 * i + 3] * x[3];
  }
}

constexpr int kChunks = 64;

}  // namespace

bool invert_block(const double* a, double* inv) {
  double m[4][8];
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) {
      m[i][j] = a[4 * i + j];
      m[i][4 + j] = i == j ? 1.0 : 0.0;
    }
  }
  for (int c = 0; c < 4; ++c) {
    int p = c;
    for (int r = c + 1; r < 4; ++r) {
      if (std::abs(m[r][c]) > std::abs(m[p][c]))
        p = r;
    }
    if (m[p][c] == 0.0 || !std::isfinite(m[p][c]))
      return false;
    if (p != c)
      std::swap(m[p], m[c]);
    const double d = 1.0 / m[c][c];
    for (int j = 0; j < 8; ++j)
      m[c][j] *= d;
    for (int r = 0; r < 4; ++r) {
      if (r == c)
        continue;
      const double f = m[r][c];
      if (f == 0.0)
        continue;
      for (int j = 0; j < 8; ++j)
        m[r][j] -= f * m[c][j];
    }
  }
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j)
      inv[4 * i + j] = m[i][4 + j];
  }
  return true;
}

int BlockSparseMatrix::find(int row, int column) const {
  const auto first = col.begin() + row_ptr[row];
  const auto last = col.begin() + row_ptr[row + 1];
  const auto it = std::lower_bound(first, last, column);
  return (it != last && *it == column) ? static_cast<int>(it - col.begin()) : -1;
}

void BlockSparseMatrix::set_zero() {
  std::fill(val.begin(), val.end(), 0.0);
}

void BlockSparseMatrix::multiply(const std::vector<double>& x, std::vector<double>& y) const {
  y.resize(4 * static_cast<std::size_t>(num_rows));
#pragma omp parallel for schedule(static) if (num_rows > 1000)
  for (int i = 0; i < num_rows; ++i) {
    double acc[4] = {0.0, 0.0, 0.0, 0.0};
    for (int p = row_ptr[i]; p < row_ptr[i + 1]; ++p) {
      const double* a = block(p);
      const double* xc = x.data() + 4 * static_cast<std::size_t>(col[p]);
      for (int r = 0; r < 4; ++r)
        acc[r] +=
            a[4 * r] * xc[0] + a[4 * r + 1] * xc[1] + a[4 * r + 2] * xc[2] + a[4 * r + 3] * xc[3];
    }
    for (int r = 0; r < 4; ++r)
      y[4 * static_cast<std::size_t>(i) + r] = acc[r];
  }
}

BlockSparseMatrix make_pattern(int n, const std::vector<std::array<int, 2>>& edges) {
  std::vector<std::vector<int>> rows(n);
  for (int i = 0; i < n; ++i)
    rows[i].push_back(i);
  for (const auto& e : edges) {
    rows[e[0]].push_back(e[1]);
    rows[e[1]].push_back(e[0]);
  }
  BlockSparseMatrix m;
  m.num_rows = n;
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
  m.val.assign(16 * m.col.size(), 0.0);
  return m;
}

void BlockIlu0::factorize(const BlockSparseMatrix& a, int partitions) {
  lu_ = a;
  const int n = lu_.num_rows;
  partitions_ = std::max(1, std::min(partitions, n));
  pos_of_col_.assign(n, -1);
  // Each partition only reads and writes rows and columns of its own range, so the partitions
  // are independent (and pos_of_col_ can be shared).
#pragma omp parallel for schedule(static, 1)
  for (int part = 0; part < partitions_; ++part) {
    const int lo = static_cast<int>(static_cast<long>(n) * part / partitions_);
    const int hi = static_cast<int>(static_cast<long>(n) * (part + 1) / partitions_);
    auto& pos_of_col = pos_of_col_;
    double tmp[16];
    for (int i = lo; i < hi; ++i) {
      for (int p = lu_.row_ptr[i]; p < lu_.row_ptr[i + 1]; ++p) {
        const int c = lu_.col[p];
        if (c >= lo && c < hi)
          pos_of_col[c] = p;
      }
      for (int p = lu_.row_ptr[i]; p < lu_.diag_pos[i]; ++p) {
        const int k = lu_.col[p];
        if (k < lo)
          continue;
        // L_ik = A_ik * inv(U_kk)
        block_mul(lu_.block(p), lu_.block(lu_.diag_pos[k]), tmp);
        std::copy(tmp, tmp + 16, lu_.block(p));
        for (int q = lu_.diag_pos[k] + 1; q < lu_.row_ptr[k + 1]; ++q) {
          const int c = lu_.col[q];
          if (c >= hi)
            continue;
          const int target = pos_of_col[c];
          if (target >= 0)
            block_mul_sub(lu_.block(p), lu_.block(q), lu_.block(target));
        }
      }
      double* d = lu_.block(lu_.diag_pos[i]);
      if (!invert_block(d, tmp)) {
        // A singular pivot only happens for a broken operator; fall back to the identity.
        for (int k = 0; k < 16; ++k)
          tmp[k] = (k % 5 == 0) ? 1.0 : 0.0;
      }
      std::copy(tmp, tmp + 16, d);
      for (int p = lu_.row_ptr[i]; p < lu_.row_ptr[i + 1]; ++p) {
        const int c = lu_.col[p];
        if (c >= lo && c < hi)
          pos_of_col[c] = -1;
      }
    }
  }
  factors_.resize(lu_.val.size());
  for (std::size_t k = 0; k < factors_.size(); ++k)
    factors_[k] = static_cast<float>(lu_.val[k]);
}

void BlockIlu0::apply(const std::vector<double>& b, std::vector<double>& x) const {
  const int n = lu_.num_rows;
  x.resize(b.size());
  const float* f = factors_.data();
  auto sub = [](const float* a, const double* v, double* y) {  // y -= A v
    for (int r = 0; r < 4; ++r) {
      y[r] -= static_cast<double>(a[4 * r]) * v[0] + static_cast<double>(a[4 * r + 1]) * v[1] +
              static_cast<double>(a[4 * r + 2]) * v[2] + static_cast<double>(a[4 * r + 3]) * v[3];
    }
  };
#pragma omp parallel for schedule(static, 1)
  for (int part = 0; part < partitions_; ++part) {
    const int lo = static_cast<int>(static_cast<long>(n) * part / partitions_);
    const int hi = static_cast<int>(static_cast<long>(n) * (part + 1) / partitions_);
    std::copy(b.begin() + 4 * static_cast<std::size_t>(lo),
              b.begin() + 4 * static_cast<std::size_t>(hi),
              x.begin() + 4 * static_cast<std::size_t>(lo));
    for (int i = lo; i < hi; ++i) {
      double* xi = x.data() + 4 * static_cast<std::size_t>(i);
      for (int p = lu_.row_ptr[i]; p < lu_.diag_pos[i]; ++p) {
        const int c = lu_.col[p];
        if (c >= lo)
          sub(f + 16 * static_cast<std::size_t>(p), x.data() + 4 * static_cast<std::size_t>(c), xi);
      }
    }
    for (int i = hi - 1; i >= lo; --i) {
      double* xi = x.data() + 4 * static_cast<std::size_t>(i);
      for (int p = lu_.diag_pos[i] + 1; p < lu_.row_ptr[i + 1]; ++p) {
        const int c = lu_.col[p];
        if (c < hi)
          sub(f + 16 * static_cast<std::size_t>(p), x.data() + 4 * static_cast<std::size_t>(c), xi);
      }
      const float* d = f + 16 * static_cast<std::size_t>(lu_.diag_pos[i]);
      const double r[4] = {xi[0], xi[1], xi[2], xi[3]};
      for (int k = 0; k < 4; ++k) {
        xi[k] = static_cast<double>(d[4 * k]) * r[0] + static_cast<double>(d[4 * k + 1]) * r[1] +
                static_cast<double>(d[4 * k + 2]) * r[2] + static_cast<double>(d[4 * k + 3]) * r[3];
      }
    }
  }
}

double dot_product(const std::vector<double>& a, const std::vector<double>& b) {
  const std::size_t n = a.size();
  double partial[kChunks];
#pragma omp parallel for schedule(static) if (n > 8000)
  for (int c = 0; c < kChunks; ++c) {
    const std::size_t first = n * c / kChunks;
    const std::size_t last = n * (c + 1) / kChunks;
    double s = 0.0;
    for (std::size_t i = first; i < last; ++i)
      s += a[i] * b[i];
    partial[c] = s;
  }
  double s = 0.0;
  for (double p : partial)
    s += p;
  return s;
}

GmresResult gmres(const BlockSparseMatrix& a, const BlockIlu0& m, const std::vector<double>& b,
                  std::vector<double>& x, double rel_tol, int restart, int max_iterations) {
  GmresWorkspace workspace;
  return gmres(a, m, b, x, rel_tol, restart, max_iterations, workspace);
}

GmresResult gmres(const BlockSparseMatrix& a, const BlockIlu0& m, const std::vector<double>& b,
                  std::vector<double>& x, double rel_tol, int restart, int max_iterations,
                  GmresWorkspace& ws) {
  const LinearOperator multiply = [&a](const std::vector<double>& in, std::vector<double>& out) {
    a.multiply(in, out);
  };
  return gmres(multiply, m, b, x, rel_tol, restart, max_iterations, ws);
}

GmresResult gmres(const LinearOperator& a, const BlockIlu0& m, const std::vector<double>& b,
                  std::vector<double>& x, double rel_tol, int restart, int max_iterations,
                  GmresWorkspace& ws) {
  const std::size_t n = b.size();
  x.assign(n, 0.0);
  GmresResult result;
  const double b_norm = std::sqrt(dot_product(b, b));
  if (b_norm == 0.0)
    return result;
  ws.v.resize(restart + 1);
  for (auto& vec : ws.v)
    vec.resize(n);
  ws.z.resize(1);
  ws.z[0].resize(n);
  ws.h.assign((restart + 1) * restart, 0.0);
  ws.cs.assign(restart, 0.0);
  ws.sn.assign(restart, 0.0);
  ws.g.assign(restart + 1, 0.0);
  ws.w.resize(n);
  auto& v = ws.v;
  auto& z = ws.z[0];
  auto& cs = ws.cs;
  auto& sn = ws.sn;
  auto& g = ws.g;
  auto& w = ws.w;
  auto H = [&](int i, int j) -> double& { return ws.h[i * restart + j]; };
  std::vector<double>& r = ws.r;
  r = b;  // x = 0
  double beta = b_norm;
  while (true) {
    for (std::size_t k = 0; k < n; ++k)
      v[0][k] = r[k] / beta;
    std::fill(g.begin(), g.end(), 0.0);
    g[0] = beta;
    int j = 0;
    for (; j < restart && result.iterations < max_iterations; ++j) {
      ++result.iterations;
      m.apply(v[j], z);
      a(z, w);
      for (int i = 0; i <= j; ++i) {  // modified Gram-Schmidt
        H(i, j) = dot_product(w, v[i]);
        const double hij = H(i, j);
        for (std::size_t k = 0; k < n; ++k)
          w[k] -= hij * v[i][k];
      }
      const double wn = std::sqrt(dot_product(w, w));
      H(j + 1, j) = wn;
      if (wn > 0.0) {
        for (std::size_t k = 0; k < n; ++k)
          v[j + 1][k] = w[k] / wn;
      }
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
    // of storing the preconditioned basis (right preconditioning, fixed M).
    std::vector<double>& y = ws.y;
    y.assign(j, 0.0);
    for (int i = j - 1; i >= 0; --i) {
      double s = g[i];
      for (int k = i + 1; k < j; ++k)
        s -= H(i, k) * y[k];
      y[i] = s / H(i, i);
    }
    std::fill(w.begin(), w.end(), 0.0);
    for (int i = 0; i < j; ++i) {
      for (std::size_t k = 0; k < n; ++k)
        w[k] += y[i] * v[i][k];
    }
    m.apply(w, z);
    for (std::size_t k = 0; k < n; ++k)
      x[k] += z[k];
    if (result.relative_residual <= rel_tol || result.iterations >= max_iterations)
      break;
    a(x, w);
    for (std::size_t k = 0; k < n; ++k)
      r[k] = b[k] - w[k];
    beta = std::sqrt(dot_product(r, r));
    result.relative_residual = beta / b_norm;
    if (result.relative_residual <= rel_tol)
      break;
  }
  return result;
}

}  // namespace tfmb::flow
