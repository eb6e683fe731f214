#include "wall_distance.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "tfmb/common/geometry.hpp"

namespace tfmb::flow {

std::vector<NearestWall> nearest_wall(const std::vector<Vec2>& points,
                                      const std::vector<std::array<Vec2, 2>>& walls) {
  const int n = static_cast<int>(points.size());
  std::vector<NearestWall> nearest(
      n, NearestWall{std::numeric_limits<double>::infinity(), Vec2{}, -1});
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
    NearestWall best = nearest[i];
    for (std::size_t k = 0; k < walls.size(); ++k) {
      const Box& b = boxes[k];
      const double dx = std::max({b.x0 - p.x, 0.0, p.x - b.x1});
      const double dy = std::max({b.y0 - p.y, 0.0, p.y - b.y1});
      if (dx * dx + dy * dy >= best.distance * best.distance)
        continue;
      const auto& [start, end] = walls[k];
      double t = 0.0;
      const double d = geometry::distance_to_segment(geometry::Point(p.x, p.y),
                                                     geometry::Point(start.x, start.y),
                                                     geometry::Point(end.x, end.y), &t);
      if (d < best.distance)
        best = {d, start + t * (end - start), static_cast<int>(k)};
    }
    nearest[i] = best;
  }
  return nearest;
}

std::vector<double> wall_distance(const std::vector<Vec2>& points,
                                  const std::vector<std::array<Vec2, 2>>& walls) {
  const auto nearest = nearest_wall(points, walls);
  std::vector<double> d(nearest.size());
  for (std::size_t i = 0; i < d.size(); ++i)
    d[i] = nearest[i].distance;
  return d;
}

}  // namespace tfmb::flow
