#include "gradient_lsq.hpp"

#include <stdexcept>

namespace tfmb::flow {

LsqGradient build_lsq_gradient(const DualMesh& dual) {
  const auto& ne = dual.node_edges;
  LsqGradient lsq;
  lsq.coefficient.resize(ne.edge.size());
  for (int i = 0; i < dual.num_nodes; ++i) {
    double a11 = 0.0, a12 = 0.0, a22 = 0.0;
    for (int k = ne.offsets[i]; k < ne.offsets[i + 1]; ++k) {
      const Vec2 d = dual.coords[ne.neighbour[k]] - dual.coords[i];
      const double w2 = 1.0 / dot(d, d);  // weight 1/|d|, squared
      a11 += w2 * d.x * d.x;
      a12 += w2 * d.x * d.y;
      a22 += w2 * d.y * d.y;
    }
    const double det = a11 * a22 - a12 * a12;
    if (!(det > 1e-12 * (a11 + a22) * (a11 + a22))) {
      throw std::invalid_argument("mesh: node " + std::to_string(i) +
                                  " has collinear neighbours; least-squares gradient undefined");
    }
    for (int k = ne.offsets[i]; k < ne.offsets[i + 1]; ++k) {
      const Vec2 d = dual.coords[ne.neighbour[k]] - dual.coords[i];
      const double w2 = 1.0 / dot(d, d);
      lsq.coefficient[k] = {w2 * (a22 * d.x - a12 * d.y) / det, w2 * (a11 * d.y - a12 * d.x) / det};
    }
  }
  return lsq;
}

void lsq_gradients(const DualMesh& dual, const LsqGradient& lsq, const std::vector<State>& q,
                   std::vector<std::array<double, 8>>& grad) {
  const auto& ne = dual.node_edges;
  grad.resize(dual.num_nodes);
#pragma omp parallel for schedule(static)
  for (int i = 0; i < dual.num_nodes; ++i) {
    std::array<double, 8> g{};
    const State& qi = q[i];
    for (int k = ne.offsets[i]; k < ne.offsets[i + 1]; ++k) {
      const State& qj = q[ne.neighbour[k]];
      const Vec2 c = lsq.coefficient[k];
      for (int v = 0; v < 4; ++v) {
        const double dq = qj[v] - qi[v];
        g[2 * v] += c.x * dq;
        g[2 * v + 1] += c.y * dq;
      }
    }
    grad[i] = g;
  }
}

}  // namespace tfmb::flow
