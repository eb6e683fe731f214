#include "gradient_lsq.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "wall_distance.hpp"

namespace tfmb::flow {

StencilGeometry cartesian_stencil(const DualMesh& dual) {
  const auto& ne = dual.node_edges;
  StencilGeometry g;
  g.to_neighbour.resize(ne.edge.size());
  for (int i = 0; i < dual.num_nodes; ++i) {
    for (int k = ne.offsets[i]; k < ne.offsets[i + 1]; ++k) {
      g.to_neighbour[k] = dual.coords[ne.neighbour[k]] - dual.coords[i];
    }
  }
  g.to_face.resize(dual.boundary_faces.size());
  for (std::size_t f = 0; f < g.to_face.size(); ++f) {
    g.to_face[f] = dual.boundary_faces[f].center - dual.coords[dual.boundary_faces[f].node];
  }
  return g;
}

namespace {
// Neighbours whose wall normals differ by more than 45 degrees do not share a wall frame.
constexpr double kMinNormalCosine = 0.7071;
constexpr double kMinCornerCosine = 0.9239;
}  // namespace

StencilGeometry wall_aligned_stencil(const Mesh& mesh, const DualMesh& dual,
                                     const std::vector<char>& wall_curves, double min_aspect_ratio,
                                     int* mapped_nodes) {
  StencilGeometry g = cartesian_stencil(dual);
  if (mapped_nodes)
    *mapped_nodes = 0;
  std::vector<std::array<Vec2, 2>> walls;
  for (std::size_t c = 0; c < mesh.boundaries.size(); ++c) {
    if (!wall_curves[c])
      continue;
    for (const auto& e : mesh.boundaries[c].edges)
      walls.push_back({dual.coords[e[0]], dual.coords[e[1]]});
  }
  if (walls.empty())
    return g;
  const auto nearest = nearest_wall(dual.coords, walls);
  const int n = dual.num_nodes;
  // unit wall normal into the fluid at each node: from the foot point, or on the wall itself
  // against the outward normals of the node's wall faces; has_frame false at sharp corners
  std::vector<Vec2> wall_normal(n);
  std::vector<char> has_frame(n, 1);
  std::vector<Vec2> face_normal_sum(n);
  std::vector<double> face_normal_length(n, 0.0);
  for (const auto& face : dual.boundary_faces) {
    if (!wall_curves[face.curve])
      continue;
    face_normal_sum[face.node] = face_normal_sum[face.node] - face.normal;
    face_normal_length[face.node] += norm(face.normal);
  }
  double scale = 0.0;
  for (const auto& p : dual.coords)
    scale = std::max({scale, std::abs(p.x), std::abs(p.y)});
  for (int i = 0; i < n; ++i) {
    const auto& nw = nearest[i];
    if (nw.distance > 1e-12 * scale) {
      wall_normal[i] = (1.0 / nw.distance) * (dual.coords[i] - nw.foot);
    } else {
      const double length = norm(face_normal_sum[i]);
      wall_normal[i] = length > 0.0 ? (1.0 / length) * face_normal_sum[i] : Vec2{0.0, 0.0};
      // a sharp corner (a lip, a step) has no wall frame: walls turning by more than 45 degrees
      // give a normal sum shorter than cos(22.5 deg) of the face lengths
      if (!(length > kMinCornerCosine * face_normal_length[i]))
        has_frame[i] = 0;
    }
  }
  const auto& ne = dual.node_edges;
  std::vector<char> mapped(n, 0);
  for (int i = 0; i < n; ++i) {
    if (!has_frame[i])
      continue;
    double shortest = std::numeric_limits<double>::infinity(), longest = 0.0;
    for (int k = ne.offsets[i]; k < ne.offsets[i + 1]; ++k) {
      const double l = norm(g.to_neighbour[k]);
      shortest = std::min(shortest, l);
      longest = std::max(longest, l);
    }
    if (longest < min_aspect_ratio * shortest)
      continue;
    mapped[i] = 1;
    if (mapped_nodes)
      ++*mapped_nodes;
    const Vec2 normal = wall_normal[i];
    const Vec2 tangent{-normal.y, normal.x};
    for (int k = ne.offsets[i]; k < ne.offsets[i + 1]; ++k) {
      const int j = ne.neighbour[k];
      // a neighbour facing another wall (across a concave corner) keeps its Cartesian vector
      if (!has_frame[j] || dot(wall_normal[j], normal) < kMinNormalCosine)
        continue;
      const Vec2 d = g.to_neighbour[k];
      const double dn = nearest[j].distance - nearest[i].distance;  // |dn| <= |d|: 1-Lipschitz
      const double ds =
          std::copysign(std::sqrt(std::max(dot(d, d) - dn * dn, 0.0)), dot(d, tangent));
      g.to_neighbour[k] = ds * tangent + dn * normal;
    }
  }
  for (std::size_t f = 0; f < g.to_face.size(); ++f) {
    const auto& face = dual.boundary_faces[f];
    if (!mapped[face.node] || !wall_curves[face.curve])
      continue;
    // the face centre lies on the wall: all of the offset is along it
    const Vec2 normal = wall_normal[face.node];
    const Vec2 tangent{-normal.y, normal.x};
    const Vec2 r = g.to_face[f];
    g.to_face[f] = std::copysign(norm(r), dot(r, tangent)) * tangent;
  }
  return g;
}

LsqGradient build_lsq_gradient(const DualMesh& dual) {
  return build_lsq_gradient(dual, cartesian_stencil(dual).to_neighbour);
}

LsqGradient build_lsq_gradient(const DualMesh& dual, const std::vector<Vec2>& to_neighbour) {
  const auto& ne = dual.node_edges;
  LsqGradient lsq;
  lsq.coefficient.resize(ne.edge.size());
  for (int i = 0; i < dual.num_nodes; ++i) {
    double a11 = 0.0, a12 = 0.0, a22 = 0.0;
    for (int k = ne.offsets[i]; k < ne.offsets[i + 1]; ++k) {
      const Vec2 d = to_neighbour[k];
      const double w2 = 1.0 / dot(d, d);  // weight 1/|d|, squared
      a11 += w2 * d.x * d.x;
      a12 += w2 * d.x * d.y;
      a22 += w2 * d.y * d.y;
    }
    const double det = a11 * a22 - a12 * a12;
    if (!(det > 1e-12 * (a11 + a22) * (a11 + a22))) {
      throw std::invalid_argument("mesh: node " + std::to_string(i) +
                                  " has collinear neighbours; least-squares gradient undefined");
    }
    for (int k = ne.offsets[i]; k < ne.offsets[i + 1]; ++k) {
      const Vec2 d = to_neighbour[k];
      const double w2 = 1.0 / dot(d, d);
      lsq.coefficient[k] = {w2 * (a22 * d.x - a12 * d.y) / det, w2 * (a11 * d.y - a12 * d.x) / det};
    }
  }
  return lsq;
}

void lsq_gradients(const DualMesh& dual, const LsqGradient& lsq, const std::vector<State>& q,
                   std::vector<std::array<double, 8>>& grad) {
  const auto& ne = dual.node_edges;
  grad.resize(dual.num_nodes);
#pragma omp parallel for schedule(static)
  for (int i = 0; i < dual.num_nodes; ++i) {
    std::array<double, 8> g{};
    const State& qi = q[i];
    for (int k = ne.offsets[i]; k < ne.offsets[i + 1]; ++k) {
      const State& qj = q[ne.neighbour[k]];
      const Vec2 c = lsq.coefficient[k];
      for (int v = 0; v < 4; ++v) {
        const double dq = qj[v] - qi[v];
        g[2 * v] += c.x * dq;
        g[2 * v + 1] += c.y * dq;
      }
    }
    grad[i] = g;
  }
}

}  // namespace tfmb::flow
