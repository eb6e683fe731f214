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

// The vectors the gradient and the reconstruction measure from a node: to each neighbour (per
// node-edge incidence) and to the centre of each boundary face.
struct StencilGeometry {
  std::vector<Vec2> to_neighbour;
  std::vector<Vec2> to_face;
};

// Cartesian: neighbour minus node, face centre minus node.
StencilGeometry cartesian_stencil(const DualMesh& dual);

// Wall-aligned ("approximate mapping", Diskin and Thomas 2008, NIA report 2008-12, sec. 4;
// Mavriplis 2003, AIAA 2003-3986): at nodes of stretched wall layers the vector to a neighbour
// is measured in the node's wall-normal frame, with the normal component the difference of
// the two wall distances and the tangential component the rest of its length. Along a curved
// or kinked wall the neighbours of a wall-layer node lie Delta s^2 / 2R off its tangent, many
// first-cell heights; measured in Cartesian terms, the large wall-normal gradient times that
// offset swamps the reconstruction to the along-wall faces and the second-order scheme has no
// steady state there. A node is mapped when its nearest boundary is one of `wall_curves` and
// its neighbour distances differ by more than `min_aspect_ratio`; a neighbour whose wall
// normal differs from the node's by more than 45 degrees (across a concave corner) keeps its
// Cartesian vector. On straight walls the mapped vectors equal
// the Cartesian ones. Returns the number of mapped nodes in `mapped_nodes` if not null.
StencilGeometry wall_aligned_stencil(const Mesh& mesh, const DualMesh& dual,
                                     const std::vector<char>& wall_curves, double min_aspect_ratio,
                                     int* mapped_nodes = nullptr);

LsqGradient build_lsq_gradient(const DualMesh& dual);
LsqGradient build_lsq_gradient(const DualMesh& dual, const std::vector<Vec2>& to_neighbour);

// Gradients of the 4 components of q (node-major): grad[node][2*k] = dq_k/dx, [2*k+1] = dq_k/dy.
void lsq_gradients(const DualMesh& dual, const LsqGradient& lsq, const std::vector<State>& q,
                   std::vector<std::array<double, 8>>& grad);

}  // namespace tfmb::flow
