#include "tfmb-heat/strip_mesh.hpp"

#include <stdexcept>

namespace tfmb::heat {

SolidMesh make_strip_mesh(const StripMeshOptions& o) {
  if (o.cells_along < 1 || o.cells_through < 1 || !(o.length > 0.0) || !(o.thickness > 0.0)) {
    throw std::invalid_argument("strip mesh: sizes must be positive");
  }
  const bool quadratic = is_quadratic(o.type);
  const bool centre_nodes = o.type == ElementType::quad9 || o.type == ElementType::tri6;
  // Quadratic meshes use a lattice at half spacing; quad8 skips the cell-centre nodes.
  const int sub = quadratic ? 2 : 1;
  const int nx = o.cells_along * sub + 1, ny = o.cells_through * sub + 1;
  SolidMesh mesh;
  std::vector<std::int64_t> id(static_cast<std::size_t>(nx * ny), -1);
  std::vector<std::array<double, 2>> points;
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const bool cell_centre = quadratic && i % 2 == 1 && j % 2 == 1;
      // Centre nodes are needed by quad9 and by the diagonal mid nodes of split triangles.
      if (cell_centre && !centre_nodes) {
        const double xc = o.length * i / (nx - 1);
        if (!(xc < o.triangles_below_x)) continue;
      }
      id[static_cast<std::size_t>(j * nx + i)] = static_cast<std::int64_t>(points.size());
      double x = o.length * i / (nx - 1), y = o.thickness * j / (ny - 1);
      if (o.map) o.map(x, y);
      points.push_back({x, y});
    }
  }
  mesh.points.resize(static_cast<Eigen::Index>(points.size()), 2);
  for (std::size_t k = 0; k < points.size(); ++k) {
    mesh.points(static_cast<Eigen::Index>(k), 0) = points[k][0];
    mesh.points(static_cast<Eigen::Index>(k), 1) = points[k][1];
  }
  auto node = [&](int i, int j) { return id[static_cast<std::size_t>(j * nx + i)]; };

  const bool all_triangles = is_triangle(o.type);
  ElementBlock triangles{quadratic ? ElementType::tri6 : ElementType::tri3, {}};
  ElementBlock quads{o.type, {}};
  for (int cj = 0; cj < o.cells_through; ++cj) {
    for (int ci = 0; ci < o.cells_along; ++ci) {
      const int i0 = ci * sub, j0 = cj * sub, i1 = i0 + sub, j1 = j0 + sub;
      const double xc = o.length * (ci + 0.5) / o.cells_along;
      if (all_triangles || xc < o.triangles_below_x) {
        // Split along the diagonal (i0, j0) - (i1, j1).
        if (!quadratic) {
          triangles.nodes.insert(triangles.nodes.end(), {node(i0, j0), node(i1, j0), node(i1, j1)});
          triangles.nodes.insert(triangles.nodes.end(), {node(i0, j0), node(i1, j1), node(i0, j1)});
        } else {
          const int im = i0 + 1, jm = j0 + 1;
          triangles.nodes.insert(triangles.nodes.end(), {node(i0, j0), node(i1, j0), node(i1, j1),
                                                         node(im, j0), node(i1, jm), node(im, jm)});
          triangles.nodes.insert(triangles.nodes.end(), {node(i0, j0), node(i1, j1), node(i0, j1),
                                                         node(im, jm), node(im, j1), node(i0, jm)});
        }
      } else if (!quadratic) {
        quads.nodes.insert(quads.nodes.end(), {node(i0, j0), node(i1, j0), node(i1, j1), node(i0, j1)});
      } else {
        const int im = i0 + 1, jm = j0 + 1;
        quads.nodes.insert(quads.nodes.end(), {node(i0, j0), node(i1, j0), node(i1, j1), node(i0, j1),
                                               node(im, j0), node(i1, jm), node(im, j1), node(i0, jm)});
        if (o.type == ElementType::quad9) quads.nodes.push_back(node(im, jm));
      }
    }
  }
  if (!triangles.nodes.empty()) mesh.blocks.push_back(triangles);
  if (!quads.nodes.empty()) mesh.blocks.push_back(quads);
  mesh.cell_material.assign(mesh.cell_count(), 0);

  auto line = [&](bool along, int fixed) {
    BoundaryCurve curve;
    curve.nodes_per_edge = quadratic ? 3 : 2;
    const int cells = along ? o.cells_along : o.cells_through;
    for (int c = 0; c < cells; ++c) {
      const int k0 = c * sub, k1 = k0 + sub;
      auto at = [&](int k) { return along ? node(k, fixed) : node(fixed, k); };
      curve.nodes.push_back(at(k0));
      curve.nodes.push_back(at(k1));
      if (quadratic) curve.nodes.push_back(at(k0 + 1));
    }
    return curve;
  };
  mesh.boundaries["bottom"] = line(true, 0);
  mesh.boundaries["top"] = line(true, ny - 1);
  mesh.boundaries["left"] = line(false, 0);
  mesh.boundaries["right"] = line(false, nx - 1);
  return mesh;
}

}  // namespace tfmb::heat
