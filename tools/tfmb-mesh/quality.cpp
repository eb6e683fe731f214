#include <algorithm>
#include <cmath>

#include "mesh_tools.hpp"

namespace tfmb::mesh {
namespace {

Eigen::Vector2d point(const h5::MatrixXdR& p, std::int64_t i) { return {p(i, 0), p(i, 1)}; }

double twice_area(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  return (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
}

std::vector<std::int64_t> cell_nodes(const Mesh& mesh, std::int64_t cell) {
  if (cell < mesh.triangles.rows()) {
    return {mesh.triangles(cell, 0), mesh.triangles(cell, 1), mesh.triangles(cell, 2)};
  }
  const auto q = cell - mesh.triangles.rows();
  return {mesh.quads(q, 0), mesh.quads(q, 1), mesh.quads(q, 2), mesh.quads(q, 3)};
}

}  // namespace

double cell_min_corner_area(const h5::MatrixXdR& points, const Mesh& mesh, std::int64_t cell) {
  const auto nodes = cell_nodes(mesh, cell);
  const std::size_t n = nodes.size();
  double smallest = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < (n == 3 ? 1 : n); ++k) {
    const auto a = point(points, nodes[(k + n - 1) % n]);
    const auto b = point(points, nodes[k]);
    const auto c = point(points, nodes[(k + 1) % n]);
    smallest = std::min(smallest, 0.5 * twice_area(a, b, c));
  }
  return smallest;
}

Quality mesh_quality(const Mesh& mesh) {
  Quality q;
  q.min_area = std::numeric_limits<double>::infinity();
  const auto cells = static_cast<std::int64_t>(mesh.cell_count());
  for (std::int64_t c = 0; c < cells; ++c) {
    const auto nodes = cell_nodes(mesh, c);
    const std::size_t n = nodes.size();
    double shortest = std::numeric_limits<double>::infinity(), longest = 0.0;
    for (std::size_t k = 0; k < n; ++k) {
      const auto a = point(mesh.points, nodes[(k + n - 1) % n]);
      const auto b = point(mesh.points, nodes[k]);
      const auto c2 = point(mesh.points, nodes[(k + 1) % n]);
      const Eigen::Vector2d u = a - b, v = c2 - b;
      const double cosine = std::clamp(u.dot(v) / (u.norm() * v.norm()), -1.0, 1.0);
      q.min_angle = std::min(q.min_angle, std::acos(cosine) * 180.0 / M_PI);
      shortest = std::min(shortest, v.norm());
      longest = std::max(longest, v.norm());
    }
    q.max_aspect_ratio = std::max(q.max_aspect_ratio, longest / shortest);
    const double area = cell_min_corner_area(mesh.points, mesh, c);
    if (area < q.min_area) {
      q.min_area = area;
      q.worst_cell = c;
    }
    if (area <= 0.0) ++q.invalid_cells;
  }
  return q;
}

void orient_counter_clockwise(Mesh& mesh) {
  for (Eigen::Index c = 0; c < mesh.triangles.rows(); ++c) {
    const auto a = point(mesh.points, mesh.triangles(c, 0));
    const auto b = point(mesh.points, mesh.triangles(c, 1));
    const auto d = point(mesh.points, mesh.triangles(c, 2));
    if (twice_area(a, b, d) < 0.0) std::swap(mesh.triangles(c, 1), mesh.triangles(c, 2));
  }
  for (Eigen::Index c = 0; c < mesh.quads.rows(); ++c) {
    double twice = 0.0;
    for (int k = 0; k < 4; ++k) {
      const auto p = point(mesh.points, mesh.quads(c, k));
      const auto r = point(mesh.points, mesh.quads(c, (k + 1) % 4));
      twice += p.x() * r.y() - r.x() * p.y();
    }
    if (twice < 0.0) std::swap(mesh.quads(c, 1), mesh.quads(c, 3));
  }
}

}  // namespace tfmb::mesh
