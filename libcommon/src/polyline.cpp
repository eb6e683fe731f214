#include "tfmb/common/polyline.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace tfmb::geometry {

double length(const Polyline& line) {
  double total = 0.0;
  for (std::size_t i = 1; i < line.size(); ++i)
    total += (line[i] - line[i - 1]).norm();
  return total;
}

Polyline reversed(Polyline line) {
  std::reverse(line.begin(), line.end());
  return line;
}

Polyline points_at(const Polyline& line, const std::vector<double>& arc_lengths) {
  Polyline out;
  out.reserve(arc_lengths.size());
  for (double s : arc_lengths)
    out.push_back(point_at_length(line, s));
  return out;
}

Polyline resample(const Polyline& line, int segments) {
  const double total = length(line);
  std::vector<double> s(static_cast<std::size_t>(segments) + 1);
  for (int i = 0; i <= segments; ++i)
    s[static_cast<std::size_t>(i)] = total * i / segments;
  Polyline out = points_at(line, s);
  out.front() = line.front();  // exact ends: joints and supports sit there
  out.back() = line.back();
  return out;
}

std::vector<Point> vertex_normals(const Polyline& line, double max_miter) {
  const std::size_t n = line.size();
  std::vector<Point> segment(n - 1);
  for (std::size_t i = 0; i + 1 < n; ++i)
    segment[i] = left_normal(line[i], line[i + 1]);
  std::vector<Point> normals(n);
  normals[0] = segment[0];
  normals[n - 1] = segment[n - 2];
  for (std::size_t i = 1; i + 1 < n; ++i) {
    Point bisector = segment[i - 1] + segment[i];
    if (bisector.norm() < 1e-12)
      bisector = segment[i];  // a full turn back: no mitre exists
    bisector.normalize();
    const double cos_half = std::max(bisector.dot(segment[i]), 1.0 / max_miter);
    normals[i] = bisector / cos_half;
  }
  return normals;
}

Polyline offset(const Polyline& line, double distance) {
  const auto normals = vertex_normals(line);
  Polyline out(line.size());
  for (std::size_t i = 0; i < line.size(); ++i)
    out[i] = line[i] + distance * normals[i];
  return out;
}

Point mean_left_normal(const Polyline& line) {
  Point sum = Point::Zero();
  for (std::size_t i = 0; i + 1 < line.size(); ++i) {
    sum += left_normal(line[i], line[i + 1]) * (line[i + 1] - line[i]).norm();
  }
  return sum;
}

std::optional<Crossing> self_intersection(const Polyline& line, bool closed) {
  const std::size_t segments = closed ? line.size() : line.size() - 1;
  auto end = [&](std::size_t i) { return line[(i + 1) % line.size()]; };
  for (std::size_t i = 0; i < segments; ++i) {
    for (std::size_t j = i + 2; j < segments; ++j) {
      if (closed && i == 0 && j == segments - 1)
        continue;
      if (auto p = geometry::segment_intersection(line[i], end(i), line[j], end(j))) {
        return Crossing{i, j, *p};
      }
    }
  }
  return std::nullopt;
}

std::optional<Crossing> crossing(const Polyline& a, const Polyline& b,
                                 const std::vector<Point>& ignore_near, double ignore_radius) {
  for (std::size_t i = 0; i + 1 < a.size(); ++i) {
    for (std::size_t j = 0; j + 1 < b.size(); ++j) {
      auto p = geometry::segment_intersection(a[i], a[i + 1], b[j], b[j + 1]);
      if (!p)
        continue;
      bool ignored = false;
      for (const Point& q : ignore_near)
        ignored |= (*p - q).norm() <= ignore_radius;
      if (!ignored)
        return Crossing{i, j, *p};
    }
  }
  return std::nullopt;
}

double distance_to(const Polyline& line, const Point& p, double* arc_length) {
  double best = std::numeric_limits<double>::infinity();
  double s = 0.0, best_s = 0.0;
  for (std::size_t i = 0; i + 1 < line.size(); ++i) {
    double t = 0.0;
    const double d = geometry::distance_to_segment(p, line[i], line[i + 1], &t);
    const double seg = (line[i + 1] - line[i]).norm();
    if (d < best) {
      best = d;
      best_s = s + t * seg;
    }
    s += seg;
  }
  if (arc_length)
    *arc_length = best_s;
  return best;
}

std::string format_point(const Point& p) {
  std::ostringstream out;
  out.precision(6);
  out << "(" << p.x() << ", " << p.y() << ")";
  return out.str();
}

}  // namespace tfmb::geometry
