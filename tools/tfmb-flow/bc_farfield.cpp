#include <cmath>

#include "bc.hpp"

namespace tfmb::flow {

// Characteristic far field with the locally one-dimensional Riemann invariants
// R+- = V.n +- 2c/(gamma-1) (Blazek 2015, sec. 8.2; Whitfield and Janus 1984). Supersonic
// inflow takes the free stream, supersonic outflow the interior.
State farfield_state(const PerfectGas& gas, const State& w_inf, const State& w, Vec2 n) {
  const double g1 = gas.gamma - 1.0;
  const double c_in = gas.sound_speed(w);
  const double c_inf = gas.sound_speed(w_inf);
  const double vn_in = w[1] * n.x + w[2] * n.y;
  const double vn_inf = w_inf[1] * n.x + w_inf[2] * n.y;
  if (vn_inf <= -c_inf && vn_in <= -c_in) return w_inf;  // supersonic inflow
  if (vn_in >= c_in) return w;                            // supersonic outflow
  const double r_plus = vn_in + 2.0 * c_in / g1;          // leaves the domain
  const double r_minus = vn_inf - 2.0 * c_inf / g1;       // enters the domain
  const double vn = 0.5 * (r_plus + r_minus);
  const double c = 0.25 * g1 * (r_plus - r_minus);
  // entropy and tangential velocity travel with the flow
  const State& up = vn < 0.0 ? w_inf : w;
  const double s = up[3] / std::pow(up[0], gas.gamma);
  const double vn_up = up[1] * n.x + up[2] * n.y;
  const double u = up[1] + (vn - vn_up) * n.x;
  const double v = up[2] + (vn - vn_up) * n.y;
  const double rho = std::pow(c * c / (gas.gamma * s), 1.0 / g1);
  return {rho, u, v, rho * c * c / gas.gamma};
}

}  // namespace tfmb::flow
