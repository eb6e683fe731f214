#include "bc.hpp"

namespace tfmb::flow {

// Outflow: supersonic (face-normal Mach >= 1) takes every variable from the interior; subsonic
// imposes the static pressure and corrects density and normal velocity along the outgoing
// characteristics (Blazek 2015, eq. 8.10).
State outflow_state(const PerfectGas& gas, double p_exit, const State& w, Vec2 n) {
  const double c = gas.sound_speed(w);
  const double vn = w[1] * n.x + w[2] * n.y;
  if (vn >= c) return w;
  const double dp = w[3] - p_exit;
  const double rho_c = w[0] * c;
  return {w[0] - dp / (c * c), w[1] + n.x * dp / rho_c, w[2] + n.y * dp / rho_c, p_exit};
}

}  // namespace tfmb::flow
