#include "bc.hpp"

#include "flux_roe.hpp"

namespace tfmb::flow {

std::string to_string(BcKind kind) {
  switch (kind) {
    case BcKind::stagnation_inflow: return "stagnation_inflow";
    case BcKind::farfield: return "farfield";
    case BcKind::pressure_outflow: return "pressure_outflow";
    case BcKind::slip_wall: return "slip_wall";
    case BcKind::symmetry: return "symmetry";
    case BcKind::wall_adiabatic: return "wall_adiabatic";
    case BcKind::wall_isothermal: return "wall_isothermal";
  }
  return "unknown";
}

State boundary_flux(const PerfectGas& gas, const BoundaryCondition& bc, const State& w, Vec2 n, int node,
                    double entropy_fix) {
  const double s = norm(n);
  if (s == 0.0) return {};  // a face on the axis of an axisymmetric mesh carries no flux
  const Vec2 unit{n.x / s, n.y / s};
  switch (bc.kind) {
    case BcKind::stagnation_inflow:
      return euler_flux(gas, stagnation_inflow_state(gas, bc, w, unit), n.x, n.y);
    case BcKind::farfield: {
      const State& inf = bc.node_freestream.empty() ? bc.freestream : bc.node_freestream[node];
      if (!bc.riemann_invariants) return roe_flux(gas, w, inf, n.x, n.y, entropy_fix);
      return roe_flux(gas, w, farfield_state(gas, inf, w, unit), n.x, n.y, entropy_fix);
    }
    case BcKind::pressure_outflow:
      return roe_flux(gas, w, outflow_state(gas, bc.static_pressure, w, unit), n.x, n.y, entropy_fix);
    case BcKind::slip_wall:
      if (!bc.riemann_wall) return {0.0, w[3] * n.x, w[3] * n.y, 0.0};
      [[fallthrough]];
    case BcKind::symmetry: {
      // Riemann problem against the mirror state (normal velocity reversed): no mass or energy
      // crosses, and the wall pressure is the acoustic one, p - rho c V.n (Blazek 2015,
      // sec. 8.1 with the ghost-state variant of sec. 8.9); equals p n once V.n = 0, and stays
      // robust when the flow still impinges on the wall during the transient.
      const double vn = w[1] * unit.x + w[2] * unit.y;
      const State mirror{w[0], w[1] - 2.0 * vn * unit.x, w[2] - 2.0 * vn * unit.y, w[3]};
      State f = roe_flux(gas, w, mirror, n.x, n.y, entropy_fix);
      f[0] = 0.0;  // zero up to round-off by symmetry; make it exact
      f[3] = 0.0;
      return f;
    }
    case BcKind::wall_adiabatic:
    case BcKind::wall_isothermal:
      // No mass or energy crosses a wall; only the pressure acts (Blazek 2015, eq. 8.2). The
      // wall node's velocity is zero (imposed strongly).
      return {0.0, w[3] * n.x, w[3] * n.y, 0.0};
  }
  return {};
}

}  // namespace tfmb::flow
