// Weighted least-squares gradients on the edge neighbourhood of each node
// (Blazek 2015, sec. 5.3.4, eqs. 5.54-5.61, inverse-distance weights).
#pragma once

#include <vector>

#include "gas.hpp"
#include "mesh_dual.hpp"

namespace tfmb::flow {

// Per node-edge incidence (same order as DualMesh::node_edges) the vector c such that
// grad_i = sum over neighbours of c * (q_neighbour - q_i).
struct LsqGradient {
  std::vector<Vec2> coefficient;
};

LsqGradient build_lsq_gradient(const DualMesh& dual);

// Gradients of the 4 components of q (node-major): grad[node][2*k] = dq_k/dx, [2*k+1] = dq_k/dy.
void lsq_gradients(const DualMesh& dual, const LsqGradient& lsq, const std::vector<State>& q,
                   std::vector<std::array<double, 8>>& grad);

}  // namespace tfmb::flow
