// Solid mesh of the flap walls for conduction: per flap a structured strip of quads, the
// along-flap lines at the beam element boundaries (so every cell lies in one beam element),
// the through-thickness lines from the inner to the outer wall (nodes exactly on both walls).
#include <algorithm>
#include <cmath>

#include "mesh_tools.hpp"
#include "tfmb/common/errors.hpp"
#include "tfmb/common/polyline.hpp"

namespace tfmb::mesh {
namespace {

// The point at arc length s on `line` and the same segment parameter on `a` and `b`, which have
// the same number of points (walls offset from the reference line vertex by vertex).
void sample(const Polyline& line, const Polyline& a, const Polyline& b,
            const std::vector<double>& cumulative, double s, Eigen::Vector2d& on_a,
            Eigen::Vector2d& on_b) {
  std::size_t k = static_cast<std::size_t>(std::upper_bound(cumulative.begin(), cumulative.end(), s) - cumulative.begin());
  k = std::clamp<std::size_t>(k, 1, line.size() - 1) - 1;
  const double seg = cumulative[k + 1] - cumulative[k];
  const double f = seg > 0 ? std::clamp((s - cumulative[k]) / seg, 0.0, 1.0) : 0.0;
  on_a = (1 - f) * a[k] + f * a[k + 1];
  on_b = (1 - f) * b[k] + f * b[k + 1];
}

formats::Boundary chain(std::string kind, std::string flap, std::string side, const std::vector<std::int64_t>& nodes) {
  formats::Boundary b;
  b.kind = std::move(kind);
  b.flap = std::move(flap);
  b.side = std::move(side);
  b.edges.resize(static_cast<Eigen::Index>(nodes.size() - 1), 2);
  for (std::size_t i = 0; i + 1 < nodes.size(); ++i) b.edges.row(static_cast<Eigen::Index>(i)) << nodes[i], nodes[i + 1];
  return b;
}

}  // namespace

Mesh build_solid_mesh(const Model& model, SolidLink& link) {
  if (model.flaps.empty()) throw BadInput("the model has no flaps: no solid mesh");
  Mesh mesh;
  std::vector<Eigen::Vector2d> points;
  std::vector<std::array<std::int64_t, 4>> quads;
  const int per_element = model.mesh.solid_cells_per_element;
  const int layers = model.mesh.solid_layers;
  for (std::size_t f = 0; f < model.flaps.size(); ++f) {
    const auto& flap = model.flaps[f];
    link.flap_names.push_back(flap.name);
    const auto cumulative = geometry::cumulative_length(flap.reference_geometry);
    const int along = flap.elements * per_element;
    const std::int64_t base = static_cast<std::int64_t>(points.size());
    auto id = [&](int i, int j) { return base + static_cast<std::int64_t>(i) * (layers + 1) + j; };
    for (int i = 0; i <= along; ++i) {
      const double s = cumulative.back() * i / along;
      Eigen::Vector2d inner, outer;
      sample(flap.reference_geometry, flap.inner_wall, flap.outer_wall, cumulative, s, inner, outer);
      for (int j = 0; j <= layers; ++j) {
        const double zeta = static_cast<double>(j) / layers;  // 0 inner, 1 outer
        points.push_back((1 - zeta) * inner + zeta * outer);
        link.point_thickness_coordinate.push_back((zeta - 0.5) * flap.thickness);
      }
    }
    std::vector<std::int64_t> cells;
    for (int i = 0; i < along; ++i) {
      for (int j = 0; j < layers; ++j) {
        cells.push_back(static_cast<std::int64_t>(quads.size()));
        quads.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
        link.cell_flap.push_back(static_cast<std::int64_t>(f));
        link.cell_element.push_back(std::min(i / per_element, flap.elements - 1));
      }
    }
    mesh.regions[flap.name] = cells;
    std::vector<std::int64_t> inner, outer, start, end;
    for (int i = 0; i <= along; ++i) {
      inner.push_back(id(i, 0));
      outer.push_back(id(i, layers));
    }
    for (int j = 0; j <= layers; ++j) {
      start.push_back(id(0, j));
      end.push_back(id(along, j));
    }
    mesh.boundaries[flap.name + "_inner"] = chain("solid_inner", flap.name, "inner", inner);
    mesh.boundaries[flap.name + "_outer"] = chain("solid_outer", flap.name, "outer", outer);
    mesh.boundaries[flap.name + "_start"] = chain("solid_end", flap.name, "end", start);
    mesh.boundaries[flap.name + "_end"] = chain("solid_end", flap.name, "end", end);
  }
  mesh.points.resize(static_cast<Eigen::Index>(points.size()), 2);
  for (std::size_t i = 0; i < points.size(); ++i) mesh.points.row(static_cast<Eigen::Index>(i)) = points[i].transpose();
  mesh.triangles.resize(0, 3);
  mesh.quads.resize(static_cast<Eigen::Index>(quads.size()), 4);
  for (std::size_t i = 0; i < quads.size(); ++i) {
    for (int k = 0; k < 4; ++k) mesh.quads(static_cast<Eigen::Index>(i), k) = quads[i][static_cast<std::size_t>(k)];
  }
  orient_counter_clockwise(mesh);
  const Quality q = mesh_quality(mesh);
  if (q.invalid_cells > 0) {
    throw BadInput("solid mesh: " + std::to_string(q.invalid_cells) + " cells fold (flap too thick for its curvature)");
  }
  return mesh;
}

}  // namespace tfmb::mesh
