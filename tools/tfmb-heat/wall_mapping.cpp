#include "tfmb-heat/wall_mapping.hpp"

#include "tfmb-heat/boundary_geometry.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

namespace tfmb::heat {

CurveProjection project_onto_curve(const SolidMesh& mesh, const BoundaryCurve& curve,
                                   const std::vector<double>& arc_length, double x, double y) {
  CurveProjection best{0.0, std::numeric_limits<double>::infinity()};
  const auto npe = static_cast<std::size_t>(curve.nodes_per_edge);
  const Eigen::Vector2d p(x, y);
  for (std::size_t e = 0; e < curve.size(); ++e) {
    const auto edge = curve.edge(e);
    const Eigen::Vector2d a = mesh.points.row(edge[0]).transpose();
    const Eigen::Vector2d b = mesh.points.row(edge[1]).transpose();
    const Eigen::Vector2d chord = b - a;
    const double t = std::clamp((p - a).dot(chord) / chord.squaredNorm(), 0.0, 1.0);
    const double distance = (a + t * chord - p).norm();
    if (distance < best.distance) {
      best.distance = distance;
      best.s = (1.0 - t) * arc_length[e * npe] + t * arc_length[e * npe + 1];
    }
  }
  return best;
}

Trace map_trace_to_boundary(const SolidMesh& mesh, const BoundaryCurve& curve,
                            const std::vector<double>& x, const std::vector<double>& y,
                            const std::vector<double>& values, const std::string& name,
                            double max_distance) {
  if (x.size() != values.size() || y.size() != values.size() || values.empty()) {
    throw std::invalid_argument(name + ": trace coordinates and values differ in length or are empty");
  }
  const auto arc_length = boundary_arc_length(mesh, curve);
  std::vector<std::pair<double, double>> samples;
  samples.reserve(values.size());
  for (std::size_t i = 0; i < values.size(); ++i) {
    const auto projection = project_onto_curve(mesh, curve, arc_length, x[i], y[i]);
    if (projection.distance > max_distance) {
      throw std::invalid_argument(name + ": trace point " + std::to_string(i) + " at (" +
                                  std::to_string(x[i]) + ", " + std::to_string(y[i]) + ") m is " +
                                  std::to_string(projection.distance) +
                                  " m from the solid wall (more than " +
                                  std::to_string(max_distance) +
                                  " m): the trace does not belong to this wall");
    }
    samples.emplace_back(projection.s, values[i]);
  }
  std::stable_sort(samples.begin(), samples.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<double> s, v;
  for (const auto& [si, vi] : samples) {
    if (!s.empty() && !(si > s.back())) continue;
    s.push_back(si);
    v.push_back(vi);
  }
  return Trace(std::move(s), std::move(v), name);
}

}  // namespace tfmb::heat
