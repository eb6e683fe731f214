// In-memory mixed triangle/quad mesh of a 2D flow domain, the input of the median-dual
// construction. Kept free of any file format: the executable fills it from flowmesh.h5,
// the tests fill it from the generators in tests/flow/mesh_generate.hpp.
#pragma once

#include <array>
#include <cmath>
#include <string>
#include <string_view>
#include <vector>

namespace tfmb::flow {

struct Vec2 {
  double x = 0.0;
  double y = 0.0;
};
inline Vec2 operator+(Vec2 a, Vec2 b) { return {a.x + b.x, a.y + b.y}; }
inline Vec2 operator-(Vec2 a, Vec2 b) { return {a.x - b.x, a.y - b.y}; }
inline Vec2 operator*(double s, Vec2 a) { return {s * a.x, s * a.y}; }
inline double dot(Vec2 a, Vec2 b) { return a.x * b.x + a.y * b.y; }
inline double norm(Vec2 a) { return std::sqrt(a.x * a.x + a.y * a.y); }

// One tagged boundary curve. Edges are node pairs ordered along the curve (edge k ends where
// edge k+1 starts), so wall traces come out ordered without a search.
struct BoundaryCurve {
  std::string name;
  std::vector<std::array<int, 2>> edges;
};

struct Mesh {
  std::vector<Vec2> points;                 // [m]
  std::vector<std::array<int, 3>> triangles;  // 0-based node ids, either orientation
  std::vector<std::array<int, 4>> quads;      // 0-based node ids, either orientation
  std::vector<BoundaryCurve> boundaries;

  int num_points() const { return static_cast<int>(points.size()); }
  int num_cells() const { return static_cast<int>(triangles.size() + quads.size()); }
  // Index into boundaries, or -1 when no curve has that name.
  int boundary_index(std::string_view name) const;
};

// Checks node ids, degenerate cells, and that the boundary curves cover exactly the edges that
// belong to one cell. Throws std::invalid_argument naming the first problem found.
void check_mesh(const Mesh& mesh);

}  // namespace tfmb::flow

namespace tfmb::flow {

// Reverse Cuthill-McKee ordering of the node graph (Cuthill and McKee 1969; George 1971),
// starting from a pseudo-peripheral node. Returns new_of_old. A banded ordering makes ILU(0)
// a stronger preconditioner and the edge loops cache friendly.
std::vector<int> rcm_ordering(const Mesh& mesh);

// Lines of strongly coupled nodes in stretched cells (Mavriplis 1998, "Multigrid strategies for
// viscous flow solvers on anisotropic unstructured meshes", J. Comput. Phys. 145:141, sec. 4):
// each node's edges are weighted by their inverse length; from the most anisotropic free node
// (largest ratio of its strongest to its weakest edge), a line grows both ways by following the
// strongest edge to a free neighbour while that edge's weight is at least `ratio` times the
// weakest of the current node's edges. In a boundary layer of flat cells the lines are the
// wall-normal columns. Returns the lines of two or more nodes, each in its order along the line.
std::vector<std::vector<int>> strong_coupling_lines(const Mesh& mesh, double ratio = 4.0);

// An ordering (new_of_old) that keeps each line contiguous: the nodes are taken in the order
// `base` (new_of_old, e.g. rcm_ordering) and a node on a line brings its whole line with it,
// starting from the line's end that comes first in `base`. Incomplete factorisations then hold
// the tridiagonal coupling along each line exactly (a line-implicit preconditioner inside the
// ILU).
std::vector<int> line_ordering(const std::vector<int>& base,
                               const std::vector<std::vector<int>>& lines);

// Applies a node permutation (new_of_old) to points, cells and boundary curves.
void renumber_nodes(Mesh& mesh, const std::vector<int>& new_of_old);

}  // namespace tfmb::flow
