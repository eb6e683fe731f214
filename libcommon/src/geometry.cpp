#include "tfmb/common/geometry.hpp"

#include <algorithm>
#include <cmath>

#include "tfmb/common/assert.hpp"

namespace tfmb::geometry {

std::vector<double> cumulative_length(const Polyline& line) {
  std::vector<double> s(line.size(), 0.0);
  for (std::size_t i = 1; i < line.size(); ++i)
    s[i] = s[i - 1] + (line[i] - line[i - 1]).norm();
  return s;
}

double interpolate(const std::vector<double>& x, const std::vector<double>& y, double at) {
  // x and y are the two columns of one table that the caller built together.
  TFMB_ASSERT(x.size() == y.size(), x.size() << " abscissae but " << y.size() << " values");
  if (x.empty())
    return 0.0;
  if (at <= x.front())
    return y.front();
  if (at >= x.back())
    return y.back();
  const auto upper = std::upper_bound(x.begin(), x.end(), at);
  const std::size_t i = static_cast<std::size_t>(upper - x.begin());
  const double w = (at - x[i - 1]) / (x[i] - x[i - 1]);
  return (1.0 - w) * y[i - 1] + w * y[i];
}

Point point_at_length(const Polyline& line, double s) {
  if (line.empty())
    return Point::Zero();
  double walked = 0.0;
  for (std::size_t i = 1; i < line.size(); ++i) {
    const double length = (line[i] - line[i - 1]).norm();
    if (walked + length >= s && length > 0.0) {
      const double t = std::clamp((s - walked) / length, 0.0, 1.0);
      return line[i - 1] + t * (line[i] - line[i - 1]);
    }
    walked += length;
  }
  return s <= 0.0 ? line.front() : line.back();
}

double distance_to_segment(const Point& p, const Point& a, const Point& b, double* t) {
  const Point ab = b - a;
  const double length2 = ab.squaredNorm();
  double u = length2 > 0.0 ? (p - a).dot(ab) / length2 : 0.0;
  u = std::clamp(u, 0.0, 1.0);
  if (t)
    *t = u;
  return (p - (a + u * ab)).norm();
}

std::optional<Point> segment_intersection(const Point& a0, const Point& a1, const Point& b0,
                                          const Point& b1) {
  const Point r = a1 - a0;
  const Point s = b1 - b0;
  const double denominator = r.x() * s.y() - r.y() * s.x();
  const Point q = b0 - a0;
  const double scale = std::max({r.norm(), s.norm(), 1e-300});
  if (std::abs(denominator) <= 1e-14 * scale * scale)
    return std::nullopt;  // parallel
  const double t = (q.x() * s.y() - q.y() * s.x()) / denominator;
  const double u = (q.x() * r.y() - q.y() * r.x()) / denominator;
  if (t < 0.0 || t > 1.0 || u < 0.0 || u > 1.0)
    return std::nullopt;
  return a0 + t * r;
}

double signed_area(const Polyline& polygon) {
  double twice_area = 0.0;
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const Point& p = polygon[i];
    const Point& q = polygon[(i + 1) % polygon.size()];
    twice_area += p.x() * q.y() - q.x() * p.y();
  }
  return 0.5 * twice_area;
}

Point left_normal(const Point& a, const Point& b) {
  const Point d = (b - a).normalized();
  return Point(-d.y(), d.x());
}

}  // namespace tfmb::geometry
