#include "trace.hpp"
#include "tfmb/common/quadrature.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace tfmb::loads {

const char* side_name(Side side) {
  switch (side) {
    case Side::inner: return "inner";
    case Side::outer: return "outer";
    case Side::end: return "end";
  }
  return "?";
}

Vec2 WallTrace::traction(std::size_t k, double u) const {
  const double p = (1.0 - u) * pressure[k] + u * pressure[k + 1];
  const double tau = (1.0 - u) * wall_shear[k] + u * wall_shear[k + 1];
  return -p * outward_normal(k) + tau * unit_tangent(k);
}

Vec2 WallTrace::smooth_normal(std::size_t k, double u) const {
  auto vertex_normal = [&](std::size_t v) {
    if (v == 0) return outward_normal(0);
    if (v == points.size() - 1) return outward_normal(v - 1);
    return Vec2((outward_normal(v - 1) + outward_normal(v)).normalized());
  };
  return ((1.0 - u) * vertex_normal(k) + u * vertex_normal(k + 1)).normalized();
}

Vec2 WallTrace::smooth_traction(std::size_t k, double u) const {
  const Vec2 n = smooth_normal(k, u);
  // The tangent along increasing index is the normal turned back by 90 degrees.
  const Vec2 e = normal_sign * Vec2(n.y(), -n.x());
  const double p = (1.0 - u) * pressure[k] + u * pressure[k + 1];
  const double tau = (1.0 - u) * wall_shear[k] + u * wall_shear[k + 1];
  return -p * n + tau * e;
}

void check_trace(const WallTrace& trace) {
  const std::size_t n = trace.points.size();
  if (n < 2) throw std::invalid_argument("trace " + trace.name + " has fewer than two points");
  if (trace.pressure.size() != n || trace.wall_shear.size() != n) {
    throw std::invalid_argument("trace " + trace.name + ": pressure/wall_shear sizes differ from the points");
  }
  for (std::size_t k = 0; k + 1 < n; ++k) {
    if (!((trace.points[k + 1] - trace.points[k]).norm() > 0.0)) {
      throw std::invalid_argument("trace " + trace.name + ": points " + std::to_string(k) + " and " +
                                  std::to_string(k + 1) + " coincide");
    }
  }
}

Resultant integrate_traces(const std::vector<const WallTrace*>& traces) {
  Resultant total;
  for (const WallTrace* trace : traces) {
    for (std::size_t k = 0; k < trace->segment_count(); ++k) {
      const double h = (trace->points[k + 1] - trace->points[k]).norm();
      static const auto gauss_2 = quadrature::gauss_legendre_unit(2);  // on [0, 1]
      for (const auto& [u, w] : gauss_2) {
        const Vec2 t = trace->traction(k, u);
        total.force += w * h * t;
        total.moment += w * h * cross(trace->position(k, u), t);
      }
    }
  }
  return total;
}

Vec2 closest_point(const std::vector<Vec2>& polyline, const Vec2& x) {
  Vec2 best = polyline.front();
  double best_distance = (x - best).squaredNorm();
  for (std::size_t k = 0; k + 1 < polyline.size(); ++k) {
    const Vec2 a = polyline[k];
    const Vec2 d = polyline[k + 1] - a;
    const double length2 = d.squaredNorm();
    const double u = length2 > 0.0 ? std::clamp((x - a).dot(d) / length2, 0.0, 1.0) : 0.0;
    const Vec2 p = a + u * d;
    const double distance = (x - p).squaredNorm();
    if (distance < best_distance) {
      best_distance = distance;
      best = p;
    }
  }
  return best;
}

Coverage coverage(const BeamLine& beam, const std::vector<const WallTrace*>& traces) {
  std::vector<std::pair<double, double>> intervals;
  for (const WallTrace* trace : traces) {
    double lo = std::numeric_limits<double>::infinity();
    double hi = -lo;
    for (const Vec2& x : trace->points) {
      const BeamProjection projection = beam.project(x);
      // A point past an end node line covers the end itself.
      lo = std::min(lo, projection.arc_length);
      hi = std::max(hi, projection.arc_length);
    }
    intervals.emplace_back(lo, hi);
  }
  Coverage result;
  if (intervals.empty()) {
    result.gaps.emplace_back(0.0, beam.length());
    return result;
  }
  std::sort(intervals.begin(), intervals.end());
  result.start = intervals.front().first;
  double reach = intervals.front().second;
  if (result.start > 0.0) result.gaps.emplace_back(0.0, result.start);
  for (std::size_t i = 1; i < intervals.size(); ++i) {
    if (intervals[i].first > reach) result.gaps.emplace_back(reach, intervals[i].first);
    reach = std::max(reach, intervals[i].second);
  }
  result.end = reach;
  if (reach < beam.length()) result.gaps.emplace_back(reach, beam.length());
  return result;
}

}  // namespace tfmb::loads
