#pragma once
// Shared helpers for the tfmb-heat tests: meshes, materials and traces sampled from a field.
#include "tfmb-heat/boundary_geometry.hpp"
#include "tfmb-heat/strip_mesh.hpp"
#include "tfmb-heat/trace.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

namespace tfmb::heat::testing {

/// Trace of field(x, y) sampled exactly at the nodes of a boundary (so imposed temperatures
/// equal the field at every boundary node).
inline Trace trace_at_nodes(const SolidMesh& mesh, const std::string& boundary,
                            const std::function<double(double, double)>& field) {
  const auto& curve = mesh.boundaries.at(boundary);
  const auto s = boundary_arc_length(mesh, curve);
  std::vector<std::pair<double, double>> samples;
  for (std::size_t i = 0; i < s.size(); ++i) {
    const auto node = curve.nodes[i];
    samples.emplace_back(s[i], field(mesh.points(node, 0), mesh.points(node, 1)));
  }
  std::sort(samples.begin(), samples.end());
  samples.erase(std::unique(samples.begin(), samples.end(),
                            [](const auto& a, const auto& b) { return std::abs(a.first - b.first) < 1e-14; }),
                samples.end());
  std::vector<double> ss, vs;
  for (const auto& [si, vi] : samples) ss.push_back(si), vs.push_back(vi);
  return Trace(ss, vs, boundary);
}

/// Trace of f(s) sampled at `count` equally spaced points on [0, length].
inline Trace dense_trace(double length, int count, const std::function<double(double)>& f,
                         const std::string& name) {
  std::vector<double> s, v;
  for (int i = 0; i < count; ++i) {
    s.push_back(length * i / (count - 1));
    v.push_back(f(s.back()));
  }
  return Trace(s, v, name);
}

inline Trace constant_trace(double length, double value, const std::string& name) {
  return Trace({0.0, length}, {value, value}, name);
}

/// Smooth distortion of the unit square that keeps its sides straight and in place.
inline void distort_unit_square(double& x, double& y) {
  const double pi = std::numbers::pi;
  const double x0 = x, y0 = y;
  x = x0 + 0.06 * std::sin(2.0 * pi * x0) * std::sin(pi * y0);
  y = y0 + 0.06 * std::sin(pi * x0) * std::sin(2.0 * pi * y0);
}

/// Two meshes side by side as one (separate nodes); boundaries renamed prefix_a + name, ...
inline SolidMesh join_meshes(const SolidMesh& a, const SolidMesh& b, const std::string& prefix_a,
                             const std::string& prefix_b) {
  SolidMesh mesh;
  const auto offset = static_cast<std::int64_t>(a.node_count());
  mesh.points.resize(a.points.rows() + b.points.rows(), 2);
  mesh.points << a.points, b.points;
  // Blocks of the same type are kept separate so the global cell order stays a then b.
  mesh.blocks = a.blocks;
  for (auto block : b.blocks) {
    for (auto& n : block.nodes) n += offset;
    mesh.blocks.push_back(block);
  }
  mesh.cell_material = a.cell_material;
  for (int m : b.cell_material) mesh.cell_material.push_back(m);
  for (const auto& [name, curve] : a.boundaries) mesh.boundaries[prefix_a + name] = curve;
  for (auto [name, curve] : b.boundaries) {
    for (auto& n : curve.nodes) n += offset;
    mesh.boundaries[prefix_b + name] = curve;
  }
  return mesh;
}

}  // namespace tfmb::heat::testing
