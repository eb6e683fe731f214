// Distance from every node to the nearest no-slip wall, the d of the Spalart-Allmaras model.
#pragma once

#include <array>
#include <vector>

#include "mesh.hpp"

namespace tfmb::flow {

// Exact distance from each point to the nearest of the wall segments (straight edges between
// wall nodes); infinity when there is no wall. Points on a wall get 0.
std::vector<double> wall_distance(const std::vector<Vec2>& points,
                                  const std::vector<std::array<Vec2, 2>>& walls);

// The nearest point on the walls and the index of its segment (-1 and infinite distance when
// there is no wall).
struct NearestWall {
  double distance;
  Vec2 foot;
  int segment;
};
std::vector<NearestWall> nearest_wall(const std::vector<Vec2>& points,
                                      const std::vector<std::array<Vec2, 2>>& walls);

}  // namespace tfmb::flow
