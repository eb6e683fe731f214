#include <algorithm>
#include <cmath>

#include "bc.hpp"

namespace tfmb::flow {

// Subsonic inflow from stagnation conditions: the Riemann invariant leaving the domain,
// R = V.n + 2c/(gamma-1) (n outward), is taken from the interior; the total enthalpy, the
// entropy (through p0, T0) and the flow direction are imposed (Blazek 2015, sec. 8.4.1; the
// quadratic follows from c^2/(gamma-1) + q^2/2 = H0 with c = (gamma-1)(R - q cos a)/2).
State stagnation_inflow_state(const PerfectGas& gas, const BoundaryCondition& bc, const State& w, Vec2 n) {
  const double g = gas.gamma;
  const double g1 = g - 1.0;
  const double c_in = gas.sound_speed(w);
  const double riemann = w[1] * n.x + w[2] * n.y + 2.0 * c_in / g1;
  const double h0 = gas.cp() * bc.total_temperature;
  const double dx = std::cos(bc.flow_angle);
  const double dy = std::sin(bc.flow_angle);
  const double cos_a = dx * n.x + dy * n.y;  // negative for flow entering
  const double qa = 1.0 + 0.5 * g1 * cos_a * cos_a;
  const double qb = -g1 * riemann * cos_a;
  const double qc = 0.5 * g1 * riemann * riemann - 2.0 * h0;
  const double disc = std::max(qb * qb - 4.0 * qa * qc, 0.0);
  double q = (-qb + std::sqrt(disc)) / (2.0 * qa);
  // Keep the state subsonic and physical if the interior is far from converged.
  const double q_max = std::sqrt(2.0 * h0 * g1 / (g + 1.0));  // speed at M = 1
  q = std::clamp(q, 0.0, q_max);
  const double t = bc.total_temperature - 0.5 * q * q / gas.cp();
  const double p = bc.total_pressure * std::pow(t / bc.total_temperature, g / g1);
  return {p / (gas.R * t), q * dx, q * dy, p};
}

}  // namespace tfmb::flow
