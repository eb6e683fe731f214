#pragma once
// In-memory solid mesh of the flap walls for planar (per unit depth) conduction.
// Node numbering inside an element follows gmsh / VTK / meshio:
//   tri3  : corners 0,1,2 counter-clockwise
//   quad4 : corners 0,1,2,3 counter-clockwise
//   tri6  : corners, then mid-edge nodes of edges 0-1, 1-2, 2-0
//   quad8 : corners, then mid-edge nodes of edges 0-1, 1-2, 2-3, 3-0
//   quad9 : as quad8, then the centre node
#include <Eigen/Dense>

#include <cstddef>
#include <cstdint>
#include <map>
#include <span>
#include <string>
#include <vector>

namespace tfmb::heat {

enum class ElementType { tri3, quad4, tri6, quad8, quad9 };

int nodes_per_element(ElementType type);
bool is_triangle(ElementType type);
bool is_quadratic(ElementType type);
const char* element_name(ElementType type);

/// Elements of one type; connectivity is row-major, nodes_per_element(type) 0-based node ids each.
struct ElementBlock {
  ElementType type = ElementType::tri3;
  std::vector<std::int64_t> nodes;

  std::size_t size() const { return nodes.size() / static_cast<std::size_t>(nodes_per_element(type)); }
  std::span<const std::int64_t> element(std::size_t e) const {
    const auto n = static_cast<std::size_t>(nodes_per_element(type));
    return {nodes.data() + e * n, n};
  }
};

/// A tagged boundary curve: edges ordered along the curve, each listing its two end nodes in
/// the direction of travel and then, for quadratic meshes, its mid node (gmsh line3 order).
struct BoundaryCurve {
  int nodes_per_edge = 2;  // 2 (linear) or 3 (quadratic)
  std::vector<std::int64_t> nodes;

  std::size_t size() const { return nodes.size() / static_cast<std::size_t>(nodes_per_edge); }
  std::span<const std::int64_t> edge(std::size_t e) const {
    const auto n = static_cast<std::size_t>(nodes_per_edge);
    return {nodes.data() + e * n, n};
  }
};

struct SolidMesh {
  Eigen::Matrix<double, Eigen::Dynamic, 2, Eigen::RowMajor> points;  // [m]
  std::vector<ElementBlock> blocks;  // global cell id = cells of earlier blocks + row
  std::vector<int> cell_material;    // per global cell: index into the material list
  std::map<std::string, BoundaryCurve> boundaries;

  std::size_t node_count() const { return static_cast<std::size_t>(points.rows()); }
  std::size_t cell_count() const;
};

/// Checks connectivity ranges, material ids, edge node counts and that every element has a
/// positive Jacobian at its nodes (counter-clockwise, not folded). Throws std::invalid_argument.
void validate_mesh(const SolidMesh& mesh, std::size_t material_count);

}  // namespace tfmb::heat
