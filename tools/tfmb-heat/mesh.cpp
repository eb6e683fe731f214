#include "tfmb-heat/mesh.hpp"

#include "tfmb-heat/shape_functions.hpp"

#include <stdexcept>
#include <string>

namespace tfmb::heat {

int nodes_per_element(ElementType type) {
  switch (type) {
    case ElementType::tri3: return 3;
    case ElementType::quad4: return 4;
    case ElementType::tri6: return 6;
    case ElementType::quad8: return 8;
    case ElementType::quad9: return 9;
  }
  return 0;
}

bool is_triangle(ElementType type) {
  return type == ElementType::tri3 || type == ElementType::tri6;
}

bool is_quadratic(ElementType type) {
  return type == ElementType::tri6 || type == ElementType::quad8 || type == ElementType::quad9;
}

const char* element_name(ElementType type) {
  switch (type) {
    case ElementType::tri3: return "triangle";
    case ElementType::quad4: return "quad";
    case ElementType::tri6: return "triangle6";
    case ElementType::quad8: return "quad8";
    case ElementType::quad9: return "quad9";
  }
  return "unknown";
}

std::size_t SolidMesh::cell_count() const {
  std::size_t count = 0;
  for (const auto& block : blocks) count += block.size();
  return count;
}

void validate_mesh(const SolidMesh& mesh, std::size_t material_count) {
  const auto n_nodes = static_cast<std::int64_t>(mesh.node_count());
  if (n_nodes == 0) throw std::invalid_argument("solid mesh: no points");
  if (!mesh.points.allFinite()) throw std::invalid_argument("solid mesh: non-finite point coordinates");
  if (mesh.cell_material.size() != mesh.cell_count()) {
    throw std::invalid_argument("solid mesh: " + std::to_string(mesh.cell_material.size()) +
                                " cell material ids for " + std::to_string(mesh.cell_count()) +
                                " cells");
  }
  for (std::size_t c = 0; c < mesh.cell_material.size(); ++c) {
    const int m = mesh.cell_material[c];
    if (m < 0 || static_cast<std::size_t>(m) >= material_count) {
      throw std::invalid_argument("solid mesh: cell " + std::to_string(c) + " has material id " +
                                  std::to_string(m) + " but " + std::to_string(material_count) +
                                  " materials are defined");
    }
  }
  std::size_t cell = 0;
  for (const auto& block : mesh.blocks) {
    const int npe = nodes_per_element(block.type);
    if (block.nodes.size() % static_cast<std::size_t>(npe) != 0) {
      throw std::invalid_argument(std::string("solid mesh: ") + element_name(block.type) +
                                  " connectivity length is not a multiple of " +
                                  std::to_string(npe));
    }
    const auto ref = reference_node_coordinates(block.type);
    std::vector<double> n(static_cast<std::size_t>(npe)), dxi(n.size()), deta(n.size());
    for (std::size_t e = 0; e < block.size(); ++e, ++cell) {
      const auto nodes = block.element(e);
      for (auto id : nodes) {
        if (id < 0 || id >= n_nodes) {
          throw std::invalid_argument("solid mesh: cell " + std::to_string(cell) +
                                      " refers to node " + std::to_string(id) + " of " +
                                      std::to_string(n_nodes));
        }
      }
      // A folded or clockwise element has a non-positive Jacobian at some node.
      for (const auto& [xi, eta] : ref) {
        shape_functions(block.type, xi, eta, n.data(), dxi.data(), deta.data());
        double j11 = 0, j12 = 0, j21 = 0, j22 = 0;
        for (int a = 0; a < npe; ++a) {
          const double x = mesh.points(nodes[a], 0), y = mesh.points(nodes[a], 1);
          j11 += dxi[a] * x;
          j12 += dxi[a] * y;
          j21 += deta[a] * x;
          j22 += deta[a] * y;
        }
        if (!(j11 * j22 - j12 * j21 > 0.0)) {
          throw std::invalid_argument("solid mesh: cell " + std::to_string(cell) + " (" +
                                      element_name(block.type) +
                                      ") is clockwise or distorted (Jacobian <= 0 at a node)");
        }
      }
    }
  }
  for (const auto& [name, curve] : mesh.boundaries) {
    if (curve.nodes_per_edge != 2 && curve.nodes_per_edge != 3) {
      throw std::invalid_argument("solid mesh: boundary '" + name + "' has " +
                                  std::to_string(curve.nodes_per_edge) +
                                  " nodes per edge (expected 2 or 3)");
    }
    if (curve.nodes.size() % static_cast<std::size_t>(curve.nodes_per_edge) != 0) {
      throw std::invalid_argument("solid mesh: boundary '" + name +
                                  "' edge list length is not a multiple of nodes per edge");
    }
    for (auto id : curve.nodes) {
      if (id < 0 || id >= n_nodes) {
        throw std::invalid_argument("solid mesh: boundary '" + name + "' refers to node " +
                                    std::to_string(id) + " of " + std::to_string(n_nodes));
      }
    }
  }
}

}  // namespace tfmb::heat
