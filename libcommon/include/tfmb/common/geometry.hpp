// Planar geometry helpers shared by the input, mesh, loads and heat stages. No physics.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <vector>

namespace tfmb::geometry {

using Point = Eigen::Vector2d;
using Polyline = std::vector<Point>;

// Cumulative arc length at each vertex (first entry 0) [m].
std::vector<double> cumulative_length(const Polyline& line);

// Linear interpolation of a tabulated function y(x) with x strictly increasing; outside the
// table the end values are returned (callers that must refuse extrapolation check the range).
double interpolate(const std::vector<double>& x, const std::vector<double>& y, double at);

// The point at arc length s along a polyline (clamped to its ends).
Point point_at_length(const Polyline& line, double s);

// Distance from a point to the segment [a, b] and the segment parameter t in [0, 1].
double distance_to_segment(const Point& p, const Point& a, const Point& b, double* t = nullptr);

// Intersection point of two closed segments, if they cross or touch.
std::optional<Point> segment_intersection(const Point& a0, const Point& a1, const Point& b0,
                                          const Point& b1);

// Signed area of a polygon (positive if counter-clockwise) [m^2].
double signed_area(const Polyline& polygon);

// Unit normal to the left of the direction a -> b.
Point left_normal(const Point& a, const Point& b);

}  // namespace tfmb::geometry
