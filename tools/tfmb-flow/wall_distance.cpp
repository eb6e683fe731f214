#include "wall_distance.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace tfmb::flow {

namespace {

double segment_distance(Vec2 p, Vec2 a, Vec2 b) {
  const Vec2 ab = b - a;
  const double len2 = dot(ab, ab);
  double t = len2 > 0.0 ? dot(p - a, ab) / len2 : 0.0;
  t = std::clamp(t, 0.0, 1.0);
  const Vec2 q{a.x + t * ab.x, a.y + t * ab.y};
  return norm(p - q);
}

}  // namespace

std::vector<double> wall_distance(const std::vector<Vec2>& points, const std::vector<std::array<Vec2, 2>>& walls) {
  const int n = static_cast<int>(points.size());
  std::vector<double> d(n, std::numeric_limits<double>::infinity());
  // Brute force over the wall segments, bounded first by the segment's bounding-box distance:
  // O(nodes x wall edges) but a few tenths of a second on the 50k-node nozzle meshes.
  struct Box {
    double x0, x1, y0, y1;
  };
  std::vector<Box> boxes(walls.size());
  for (std::size_t k = 0; k < walls.size(); ++k) {
    const auto& s = walls[k];
    boxes[k] = {std::min(s[0].x, s[1].x), std::max(s[0].x, s[1].x), std::min(s[0].y, s[1].y),
                std::max(s[0].y, s[1].y)};
  }
#pragma omp parallel for schedule(dynamic, 256)
  for (int i = 0; i < n; ++i) {
    const Vec2 p = points[i];
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < walls.size(); ++k) {
      const Box& b = boxes[k];
      const double dx = std::max({b.x0 - p.x, 0.0, p.x - b.x1});
      const double dy = std::max({b.y0 - p.y, 0.0, p.y - b.y1});
      if (dx * dx + dy * dy >= best * best) continue;
      best = std::min(best, segment_distance(p, walls[k][0], walls[k][1]));
    }
    d[i] = best;
  }
  return d;
}

}  // namespace tfmb::flow
