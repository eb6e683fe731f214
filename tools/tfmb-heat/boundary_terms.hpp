#pragma once
// Boundary conditions turned into quadrature points on the tagged edges (Robin-type terms) and
// nodal values (imposed temperatures).
//   flux out of the body at a point:  q_out(T) = h (T - T_aw) + eps sigma (T^4 - T_env^4) - q_in
//   residual R_a += int N_a q_out ds,  tangent K_ab += int N_a N_b (h + 4 eps sigma T^3) ds
// Radiation linearised by Newton about the iterate (exact tangent of T^4).
#include "tfmb-heat/boundary_conditions.hpp"
#include "tfmb-heat/mesh.hpp"

#include <array>
#include <cstdint>
#include <utility>
#include <vector>

namespace tfmb::heat {

/// Stefan-Boltzmann constant [W/(m^2 K^4)], CODATA 2018 (exact in the 2019 SI).
inline constexpr double kStefanBoltzmann = 5.670374419e-8;

struct BoundaryPoint {
  std::array<std::int64_t, 3> nodes{};  // edge nodes (count of them used)
  std::array<double, 3> n{};            // edge shape functions at the point
  int count = 0;
  double weight = 0.0;      // quadrature weight times ds/dxi [m]
  double h = 0.0;           // [W/(m^2 K)]
  double t_ref = 0.0;       // adiabatic wall temperature [K]
  double eps_sigma = 0.0;   // emissivity times Stefan-Boltzmann [W/(m^2 K^4)]
  double t_env = 0.0;       // [K]
  double q_in = 0.0;        // imposed flux into the body [W/m^2]
  int boundary = -1;        // index of the boundary condition it comes from

  double flux_out(double t) const {
    const double t2 = t * t, e2 = t_env * t_env;
    return h * (t - t_ref) + eps_sigma * (t2 * t2 - e2 * e2) - q_in;
  }
  double flux_out_slope(double t) const { return h + 4.0 * eps_sigma * t * t * t; }
};

/// Quadrature points (3 per linear edge, 5 per quadratic edge) of a flux-type condition
/// (convection, radiation, imposed flux; adiabatic gives none). `arc_length` comes from
/// boundary_arc_length(); traces are evaluated at the interpolated arc length of each point.
/// Throws std::invalid_argument for missing or uncovering traces and out-of-range parameters.
std::vector<BoundaryPoint> boundary_points(const SolidMesh& mesh, const BoundaryCurve& curve,
                                           const std::vector<double>& arc_length,
                                           const BoundaryCondition& condition,
                                           int boundary_index, double trace_tolerance);

/// (node, temperature [K]) for every node of an imposed-temperature curve.
std::vector<std::pair<std::int64_t, double>> imposed_temperatures(
    const BoundaryCurve& curve, const std::vector<double>& arc_length,
    const ImposedTemperature& condition, double trace_tolerance);

}  // namespace tfmb::heat
