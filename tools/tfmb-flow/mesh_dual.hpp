// Median-dual control volumes around the nodes of a mixed mesh, in the edge-based form the
// vertex-centred finite-volume solver loops over (Blazek 2015, sec. 5.2.2 and 5.3.2).
#pragma once

#include <array>
#include <vector>

#include "mesh.hpp"

namespace tfmb::flow {

enum class Geometry { planar, axisymmetric };

// A piece of a dual cell's boundary lying on a boundary curve: half of one boundary edge.
struct BoundaryFace {
  int node;          // the node owning the dual cell
  int curve;         // index into Mesh::boundaries
  int curve_edge;    // index of the edge along that curve
  Vec2 normal;       // outward, length = face measure (see DualMesh::edge_normal)
  Vec2 center;       // midpoint of the half edge [m]
};

// Node-to-edge incidence in CSR form; sign is +1 when the node is the first node of the edge
// (the edge normal points out of its dual cell), -1 otherwise.
struct NodeEdges {
  std::vector<int> offsets;  // size num_nodes + 1
  std::vector<int> edge;
  std::vector<int> neighbour;
  std::vector<double> sign;
};

struct DualMesh {
  Geometry geometry = Geometry::planar;
  int num_nodes = 0;
  std::vector<Vec2> coords;                  // node coordinates [m]
  std::vector<std::array<int, 2>> edges;     // node pairs, first < second
  // Dual-face normal of each edge, oriented from the first to the second node, summed over the
  // cells sharing the edge. Planar: length [m] per unit depth. Axisymmetric: integral of r n ds,
  // [m^2] per radian.
  std::vector<Vec2> edge_normal;
  std::vector<Vec2> edge_normal_planar;      // the planar dual-face normal [m] (both geometries)
  // Dual-cell measure: planar area [m^2]; axisymmetric integral of r dA [m^3] per radian.
  std::vector<double> volume;
  std::vector<double> area;                  // planar area of the dual cell [m^2]
  std::vector<BoundaryFace> boundary_faces;  // two per boundary edge
  NodeEdges node_edges;

  int num_edges() const { return static_cast<int>(edges.size()); }
};

// Builds the dual. Boundary faces are oriented out of the domain by the cell that owns the edge.
DualMesh build_dual(const Mesh& mesh, Geometry geometry);

// Sum over the dual cell's faces of the face normals (interior and boundary), per node. Zero
// for planar duals (closure); (0, planar area) for axisymmetric duals, since the closed
// integral of r n ds over a cell equals its planar area times the unit radial vector.
std::vector<Vec2> dual_closure(const DualMesh& dual);

}  // namespace tfmb::flow
