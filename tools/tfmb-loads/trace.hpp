// Wall traces: the flow solution on one wetted surface of a flap, as a polyline with pressure
// and wall shear at its points (linear between them, the seed's and the flow solver's
// convention for node data on a wall).
//
// Traction on the solid (force per unit wall area, per unit depth):
//   t = -p n + tau e
// n the unit normal pointing out of the solid into the fluid, e the unit tangent in the
// direction of increasing point index, tau the wall shear along e (flow.md: "wall shear stress
// along the wall direction of increasing s"). Newton's third law on the fluid's stress vector
// at a wall (e.g. Anderson, Fundamentals of Aerodynamics, 6th ed., eq. 1.1-1.2).
#pragma once

#include <string>
#include <vector>

#include "beam_line.hpp"

namespace tfmb::loads {

enum class Side { inner, outer, end };
const char* side_name(Side side);

struct WallTrace {
  std::string name;                 // e.g. the flow mesh boundary it came from
  std::string flap;
  Side side = Side::inner;
  std::vector<Vec2> points;         // ordered along the wall [m]
  std::vector<double> pressure;     // [Pa]
  std::vector<double> wall_shear;   // [Pa], along increasing point index
  double normal_sign = 1.0;         // n = normal_sign * (left normal of the segment direction)

  std::size_t segment_count() const { return points.size() - 1; }
  Vec2 unit_tangent(std::size_t k) const { return (points[k + 1] - points[k]).normalized(); }
  Vec2 outward_normal(std::size_t k) const {
    const Vec2 e = unit_tangent(k);
    return normal_sign * Vec2(-e.y(), e.x());
  }
  // Traction at local coordinate u in [0, 1] of segment k [Pa].
  Vec2 traction(std::size_t k, double u) const;
  // The same with the normal interpolated linearly between vertex normals (the mean of the
  // two segments meeting there) and renormalised: on a polygon inscribed in a smooth wall the
  // direction error drops from O(h) to O(h^2). Used where a traction is sampled at a point
  // (the linear method); integrals use the exact piecewise-constant normal.
  Vec2 smooth_traction(std::size_t k, double u) const;
  // The interpolated unit normal used by smooth_traction (out of the solid).
  Vec2 smooth_normal(std::size_t k, double u) const;
  Vec2 position(std::size_t k, double u) const { return points[k] + u * (points[k + 1] - points[k]); }
};

// Sets trace.normal_sign so that n points away from the solid. `interior` returns, for a
// point on the trace, a point inside or on the far side of the solid (e.g. the closest point
// of the opposite wall); the sign is the length-weighted vote over the segments.
// Throws std::invalid_argument if the vote is undecided (zero-thickness flap).
template <typename InteriorPoint>
void orient_trace(WallTrace& trace, InteriorPoint interior) {
  double vote = 0.0;
  trace.normal_sign = 1.0;
  for (std::size_t k = 0; k < trace.segment_count(); ++k) {
    const Vec2 middle = trace.position(k, 0.5);
    const double h = (trace.points[k + 1] - trace.points[k]).norm();
    vote += h * trace.outward_normal(k).dot(middle - interior(middle));
  }
  if (vote == 0.0) throw std::invalid_argument("cannot tell the solid side of trace " + trace.name);
  trace.normal_sign = vote > 0.0 ? 1.0 : -1.0;
}

// Checks sizes, at least two points, no zero-length segment; throws std::invalid_argument.
void check_trace(const WallTrace& trace);

// Resultant force and moment about the origin (z) of the traction of a set of traces, per
// unit depth [N/m, N]. Exact for the piecewise-linear traces: the force integrand is linear
// and the moment integrand x x t quadratic on each segment, and two-point Gauss-Legendre
// quadrature is exact to degree 3 (Abramowitz & Stegun 25.4.29).
struct Resultant {
  Vec2 force = Vec2::Zero();
  double moment = 0.0;
};
Resultant integrate_traces(const std::vector<const WallTrace*>& traces);

// Closest point of a polyline to x.
Vec2 closest_point(const std::vector<Vec2>& polyline, const Vec2& x);

// Beam arc-length interval covered by the traces of one side of a flap: the union of the
// projections of their points. `gaps` lists uncovered stretches [from, to] inside [0, L].
struct Coverage {
  double start = 0.0;  // [m]
  double end = 0.0;    // [m]
  std::vector<std::pair<double, double>> gaps;
};
Coverage coverage(const BeamLine& beam, const std::vector<const WallTrace*>& traces);

}  // namespace tfmb::loads
