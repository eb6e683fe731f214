#pragma once
// Transfer of a flow wall trace (points x, y with values, ordered along the flow wall) onto a
// solid boundary curve: every trace point is projected onto the curve and takes the curve's
// arc length there, so the trace is expressed in the solid boundary's own s (which may start at
// the other end, or be discretised differently from the flow wall).
#include "tfmb-heat/mesh.hpp"
#include "tfmb-heat/trace.hpp"

#include <string>
#include <vector>

namespace tfmb::heat {

struct CurveProjection {
  double s = 0.0;         // [m] arc length of the closest point on the curve
  double distance = 0.0;  // [m] from the point to the curve
};

/// Closest point on the curve (edges taken as straight chords between their end nodes).
CurveProjection project_onto_curve(const SolidMesh& mesh, const BoundaryCurve& curve,
                                   const std::vector<double>& arc_length, double x, double y);

/// The trace re-parameterised by the solid boundary's arc length. Points projecting onto the
/// same s keep the first. Throws std::invalid_argument naming `name` if a point lies further
/// than max_distance [m] from the curve (the trace belongs to another wall).
Trace map_trace_to_boundary(const SolidMesh& mesh, const BoundaryCurve& curve,
                            const std::vector<double>& x, const std::vector<double>& y,
                            const std::vector<double>& values, const std::string& name,
                            double max_distance);

}  // namespace tfmb::heat
