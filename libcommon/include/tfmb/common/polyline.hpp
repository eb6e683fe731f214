// Polyline operations the input and mesh stages share: resampling, offsetting, intersections,
// distances. No physics.
#pragma once

#include <optional>
#include <string>

#include "tfmb/common/geometry.hpp"

namespace tfmb::geometry {

double length(const Polyline& line);
Polyline reversed(Polyline line);
// n+1 points at equal arc length from start to end (n >= 1).
Polyline resample(const Polyline& line, int segments);
// Points at the given arc lengths.
Polyline points_at(const Polyline& line, const std::vector<double>& arc_lengths);

// Unit vertex normals to the left of the direction of travel, mitred: at an interior vertex the
// bisector of the two segment normals scaled by 1/cos(half the turn) so that an offset keeps the
// distance to both segments (the scale is capped at `max_miter`).
std::vector<Point> vertex_normals(const Polyline& line, double max_miter = 4.0);
// The polyline moved by `distance` along its mitred left normals (negative: to the right).
Polyline offset(const Polyline& line, double distance);

// Sum of the left normals weighted by segment length (its sign tells which side faces where).
Point mean_left_normal(const Polyline& line);

struct Crossing {
  std::size_t segment_a = 0, segment_b = 0;
  Point point = Point::Zero();
};
// First crossing of two non-adjacent segments of one polyline (closed: the last and first
// segments are adjacent too).
std::optional<Crossing> self_intersection(const Polyline& line, bool closed = false);
// First crossing between two polylines, ignoring crossings within `ignore_radius` of any point in
// `ignore_near`.
std::optional<Crossing> crossing(const Polyline& a, const Polyline& b,
                                 const std::vector<Point>& ignore_near = {},
                                 double ignore_radius = 0.0);
// Distance from a point to a polyline and the arc length of the foot point.
double distance_to(const Polyline& line, const Point& p, double* arc_length = nullptr);

// "(x, y)" with 6 significant digits, for messages.
std::string format_point(const Point& p);

}  // namespace tfmb::geometry
