#include "mesh.hpp"

#include <cstdint>
#include <stdexcept>
#include <unordered_map>

namespace tfmb::flow {

int Mesh::boundary_index(std::string_view name) const {
  for (std::size_t b = 0; b < boundaries.size(); ++b) {
    if (boundaries[b].name == name) return static_cast<int>(b);
  }
  return -1;
}

namespace {
std::uint64_t edge_key(int a, int b) {
  if (a > b) std::swap(a, b);
  return (static_cast<std::uint64_t>(a) << 32) | static_cast<std::uint32_t>(b);
}
}  // namespace

void check_mesh(const Mesh& mesh) {
  const int n = mesh.num_points();
  std::unordered_map<std::uint64_t, int> edge_cells;
  auto add_cell = [&](const int* ids, int nv, int cell) {
    double twice_area = 0.0;
    for (int k = 0; k < nv; ++k) {
      const int a = ids[k];
      const int b = ids[(k + 1) % nv];
      if (a < 0 || a >= n || b < 0 || b >= n) {
        throw std::invalid_argument("mesh: cell " + std::to_string(cell) + " has node id out of range [0," +
                                    std::to_string(n) + ")");
      }
      const Vec2 pa = mesh.points[a];
      const Vec2 pb = mesh.points[b];
      twice_area += pa.x * pb.y - pb.x * pa.y;
      ++edge_cells[edge_key(a, b)];
    }
    if (!(std::abs(twice_area) > 0.0)) {
      throw std::invalid_argument("mesh: cell " + std::to_string(cell) + " has zero area");
    }
  };
  int cell = 0;
  for (const auto& t : mesh.triangles) add_cell(t.data(), 3, cell++);
  for (const auto& q : mesh.quads) add_cell(q.data(), 4, cell++);

  std::unordered_map<std::uint64_t, int> tagged;
  for (const auto& curve : mesh.boundaries) {
    for (const auto& e : curve.edges) {
      const auto it = edge_cells.find(edge_key(e[0], e[1]));
      if (it == edge_cells.end() || it->second != 1) {
        throw std::invalid_argument("mesh: boundary '" + curve.name + "' edge (" + std::to_string(e[0]) +
                                    "," + std::to_string(e[1]) + ") is not a boundary edge of the cells");
      }
      if (++tagged[it->first] > 1) {
        throw std::invalid_argument("mesh: boundary edge (" + std::to_string(e[0]) + "," +
                                    std::to_string(e[1]) + ") is tagged twice (second time in '" +
                                    curve.name + "')");
      }
    }
  }
  for (const auto& [key, count] : edge_cells) {
    if (count > 2) throw std::invalid_argument("mesh: an edge is shared by more than two cells");
    if (count == 1 && !tagged.count(key)) {
      throw std::invalid_argument("mesh: boundary edge (" + std::to_string(key >> 32) + "," +
                                  std::to_string(key & 0xffffffffu) +
                                  ") belongs to no tagged boundary; tag every boundary curve");
    }
  }
}

}  // namespace tfmb::flow
