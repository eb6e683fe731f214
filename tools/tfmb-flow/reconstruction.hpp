// Second-order reconstruction of the primitive state from a node to a point of its dual cell
// (an edge midpoint or a boundary face centre), shared by the residual and its Jacobian so that
// both see the same states.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>

#include "gas.hpp"
#include "mesh_dual.hpp"

namespace tfmb::flow {

// Scales a reconstructed state's increment so that density and pressure keep at least half of
// the node's value. Continuous in the state (a switch back to the node value would make the
// residual jump, and the matrix-free Jacobian's differences across such a jump near a
// near-vacuum lip corner stalled GMRES).
inline void keep_positive(const State& node, State& face) {
  double scale = 1.0;
  for (int v : {0, 3}) {
    const double increment = face[v] - node[v];
    if (increment < -0.5 * node[v])
      scale = std::min(scale, -0.5 * node[v] / increment);
  }
  if (scale < 1.0 || !std::isfinite(face[0] + face[3])) {
    for (int v = 0; v < 4; ++v)
      face[v] = std::isfinite(scale) ? node[v] + scale * (face[v] - node[v]) : node[v];
  }
}

// w + phi (grad w . h) per primitive variable (Blazek 2015, eq. 5.57), phi null for no limiter,
// then kept positive.
inline State reconstruct(const State& w, const std::array<double, 8>& grad, const State* phi,
                         Vec2 h) {
  State face = w;
  for (int v = 0; v < 4; ++v)
    face[v] += (phi ? (*phi)[v] : 1.0) * (grad[2 * v] * h.x + grad[2 * v + 1] * h.y);
  keep_positive(w, face);
  return face;
}

}  // namespace tfmb::flow
