#include "scalar_ilu.hpp"

#include <algorithm>
#include <numeric>

namespace tfmb::flow {

void ScalarIlu0::factorize(const NodeEdges& pattern, const std::vector<double>& diag,
                           const std::vector<double>& offdiag) {
  const int n = static_cast<int>(diag.size());
  if (pattern_ != &pattern || sorted_slots_.size() != pattern.neighbour.size()) {
    pattern_ = &pattern;
    sorted_slots_.resize(pattern.neighbour.size());
    for (int i = 0; i < n; ++i) {
      auto first = sorted_slots_.begin() + pattern.offsets[i];
      auto last = sorted_slots_.begin() + pattern.offsets[i + 1];
      std::iota(first, last, pattern.offsets[i]);
      std::sort(first, last, [&](int a, int b) { return pattern.neighbour[a] < pattern.neighbour[b]; });
    }
    position_.assign(n, -1);
  }
  diag_ = diag;
  offdiag_ = offdiag;
  const auto& nb = pattern.neighbour;
  for (int i = 0; i < n; ++i) {
    for (int s = pattern.offsets[i]; s < pattern.offsets[i + 1]; ++s) position_[nb[s]] = s;
    for (int q = pattern.offsets[i]; q < pattern.offsets[i + 1]; ++q) {
      const int s = sorted_slots_[q];
      const int k = nb[s];
      if (k >= i) break;
      const double l = offdiag_[s] / diag_[k];
      offdiag_[s] = l;
      for (int t = pattern.offsets[k]; t < pattern.offsets[k + 1]; ++t) {
        const int j = nb[t];
        if (j <= k) continue;
        if (j == i) {
          diag_[i] -= l * offdiag_[t];
        } else if (position_[j] >= 0) {
          offdiag_[position_[j]] -= l * offdiag_[t];
        }
      }
    }
    for (int s = pattern.offsets[i]; s < pattern.offsets[i + 1]; ++s) position_[nb[s]] = -1;
  }
}

void ScalarIlu0::apply(const std::vector<double>& rhs, std::vector<double>& x) const {
  const NodeEdges& p = *pattern_;
  const int n = static_cast<int>(diag_.size());
  x.resize(n);
  for (int i = 0; i < n; ++i) {
    double v = rhs[i];
    for (int s = p.offsets[i]; s < p.offsets[i + 1]; ++s) {
      if (p.neighbour[s] < i) v -= offdiag_[s] * x[p.neighbour[s]];
    }
    x[i] = v;
  }
  for (int i = n - 1; i >= 0; --i) {
    double v = x[i];
    for (int s = p.offsets[i]; s < p.offsets[i + 1]; ++s) {
      if (p.neighbour[s] > i) v -= offdiag_[s] * x[p.neighbour[s]];
    }
    x[i] = v / diag_[i];
  }
}

void solve_scalar(const NodeEdges& pattern, const std::vector<double>& diag, const std::vector<double>& offdiag,
                  const std::vector<double>& b, std::vector<double>& x, int iterations, ScalarIlu0& ilu) {
  const int n = static_cast<int>(diag.size());
  ilu.factorize(pattern, diag, offdiag);
  x.assign(n, 0.0);
  std::vector<double> r = b, z(n);
  for (int it = 0; it < iterations; ++it) {
    ilu.apply(r, z);
    for (int i = 0; i < n; ++i) x[i] += z[i];
    if (it + 1 == iterations) break;
    for (int i = 0; i < n; ++i) {
      double ax = diag[i] * x[i];
      for (int s = pattern.offsets[i]; s < pattern.offsets[i + 1]; ++s) ax += offdiag[s] * x[pattern.neighbour[s]];
      r[i] = b[i] - ax;
    }
  }
}

}  // namespace tfmb::flow
