#include "limiter.hpp"

#include <algorithm>

namespace tfmb::flow {

std::vector<State> make_venkat_epsilon(const DualMesh& dual, double k_venkat, const State& q_ref) {
  double total_area = 0.0;
  for (double a : dual.area)
    total_area += a;
  const double length = std::sqrt(total_area);
  std::vector<State> eps(dual.num_nodes);
  for (int i = 0; i < dual.num_nodes; ++i) {
    const double kh = k_venkat * std::sqrt(dual.area[i]) / length;
    for (int v = 0; v < 4; ++v)
      eps[i][v] = kh * kh * kh * q_ref[v] * q_ref[v];
  }
  return eps;
}

std::vector<State> make_wang_epsilon(const std::vector<State>& q, double coefficient,
                                     int num_nodes) {
  State lo = q[0], hi = q[0];
  for (int i = 0; i < num_nodes; ++i) {
    for (int v = 0; v < 4; ++v) {
      lo[v] = std::min(lo[v], q[i][v]);
      hi[v] = std::max(hi[v], q[i][v]);
    }
  }
  State e;
  for (int v = 0; v < 4; ++v) {
    const double d = coefficient * (hi[v] - lo[v]);
    e[v] = std::max(d * d, 1e-300);
  }
  return std::vector<State>(num_nodes, e);
}

void venkatakrishnan_limiter(const DualMesh& dual, const std::vector<Vec2>& to_neighbour,
                             const std::vector<State>& q,
                             const std::vector<std::array<double, 8>>& grad,
                             const std::vector<State>& epsilon2, std::vector<State>& phi) {
  const auto& ne = dual.node_edges;
  phi.resize(dual.num_nodes);
#pragma omp parallel for schedule(static)
  for (int i = 0; i < dual.num_nodes; ++i) {
    State qmax = q[i], qmin = q[i];
    for (int k = ne.offsets[i]; k < ne.offsets[i + 1]; ++k) {
      const State& qj = q[ne.neighbour[k]];
      for (int v = 0; v < 4; ++v) {
        qmax[v] = std::max(qmax[v], qj[v]);
        qmin[v] = std::min(qmin[v], qj[v]);
      }
    }
    State p{1.0, 1.0, 1.0, 1.0};
    for (int k = ne.offsets[i]; k < ne.offsets[i + 1]; ++k) {
      const Vec2 r = 0.5 * to_neighbour[k];
      for (int v = 0; v < 4; ++v) {
        const double d2 = grad[i][2 * v] * r.x + grad[i][2 * v + 1] * r.y;
        if (d2 == 0.0)
          continue;
        const double d1 = d2 > 0.0 ? qmax[v] - q[i][v] : qmin[v] - q[i][v];
        const double e2 = epsilon2[i][v];
        // Venkatakrishnan (1995), eq. 6 written without the division by d2
        const double f = (d1 * d1 + e2 + 2.0 * d2 * d1) / (d1 * d1 + 2.0 * d2 * d2 + d1 * d2 + e2);
        p[v] = std::min(p[v], f);
      }
    }
    phi[i] = p;
  }
}

}  // namespace tfmb::flow
