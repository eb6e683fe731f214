#pragma once
// Arc length along a tagged boundary curve, used to evaluate wall traces.
#include "tfmb-heat/mesh.hpp"

#include <vector>

namespace tfmb::heat {

/// Arc length [m] at every node of every edge of the curve, laid out like curve.nodes. The
/// curve must be one connected chain of edges; edges are taken in the stored order and each
/// edge may be stored in either direction. s starts at 0 at the first node of the chain.
/// Edge lengths are integrated with Gauss quadrature (exact for straight edges; quadratic edges
/// to 1e-6 relative or better). Throws std::invalid_argument for a broken chain.
std::vector<double> boundary_arc_length(const SolidMesh& mesh, const BoundaryCurve& curve);

/// Total length [m] of the curve.
double boundary_length(const SolidMesh& mesh, const BoundaryCurve& curve);

}  // namespace tfmb::heat
