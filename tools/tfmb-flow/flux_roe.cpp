#include "flux_roe.hpp"

#include <algorithm>

namespace tfmb::flow {

namespace {

struct RoeAverage {
  double rho, u, v, h, c, vn, q2;
  double nx, ny;                 // unit normal
  double abs_l1, abs_l2, abs_l3; // |V-c|, |V|, |V+c| after the entropy fix
};

// Harten's smoothing of |lambda| near zero (Blazek 2015, eq. 4.93).
inline double harten(double lambda, double delta) {
  const double a = std::abs(lambda);
  return a >= delta ? a : 0.5 * (lambda * lambda + delta * delta) / delta;
}

// |A_Roe| times a jump given as primitive increments (Blazek 2015, eqs. 4.90-4.92). Scaled by the
// face length outside.
inline State dissipation(const RoeAverage& r, double drho, double du, double dv, double dp) {
  const double dvn = r.nx * du + r.ny * dv;
  const double c2 = r.c * r.c;
  const double a1 = r.abs_l1 * (dp - r.rho * r.c * dvn) / (2.0 * c2);
  const double a3 = r.abs_l3 * (dp + r.rho * r.c * dvn) / (2.0 * c2);
  const double a2 = r.abs_l2 * (drho - dp / c2);
  const double a2r = r.abs_l2 * r.rho;
  return {a1 + a2 + a3,
          a1 * (r.u - r.c * r.nx) + a2 * r.u + a2r * (du - r.nx * dvn) + a3 * (r.u + r.c * r.nx),
          a1 * (r.v - r.c * r.ny) + a2 * r.v + a2r * (dv - r.ny * dvn) + a3 * (r.v + r.c * r.ny),
          a1 * (r.h - r.c * r.vn) + a2 * 0.5 * r.q2 + a2r * (r.u * du + r.v * dv - r.vn * dvn) +
              a3 * (r.h + r.c * r.vn)};
}

}  // namespace

State roe_flux(const PerfectGas& gas, const State& wl, const State& wr, double nx, double ny,
               double entropy_fix, RoeFluxJacobians* jac) {
  const double s = std::sqrt(nx * nx + ny * ny);
  RoeAverage r;
  r.nx = nx / s;
  r.ny = ny / s;
  // Roe averages (Blazek 2015, eq. 4.89)
  const double sl = std::sqrt(wl[0]);
  const double sr = std::sqrt(wr[0]);
  const double wgt = 1.0 / (sl + sr);
  const double hl = gas.total_enthalpy(wl);
  const double hr = gas.total_enthalpy(wr);
  r.rho = sl * sr;
  r.u = (sl * wl[1] + sr * wr[1]) * wgt;
  r.v = (sl * wl[2] + sr * wr[2]) * wgt;
  r.h = (sl * hl + sr * hr) * wgt;
  r.q2 = r.u * r.u + r.v * r.v;
  r.c = std::sqrt(std::max((gas.gamma - 1.0) * (r.h - 0.5 * r.q2), 1e-12 * r.h));
  r.vn = r.u * r.nx + r.v * r.ny;
  const double delta = entropy_fix * r.c;
  r.abs_l1 = harten(r.vn - r.c, delta);
  r.abs_l2 = harten(r.vn, delta);
  r.abs_l3 = harten(r.vn + r.c, delta);

  const State fl = euler_flux(gas, wl, nx, ny);
  const State fr = euler_flux(gas, wr, nx, ny);
  const State d = dissipation(r, wr[0] - wl[0], wr[1] - wl[1], wr[2] - wl[2], wr[3] - wl[3]);
  State f;
  for (int k = 0; k < 4; ++k) f[k] = 0.5 * (fl[k] + fr[k] - s * d[k]);

  if (jac) {
    // Columns of |A_Roe|: the jump e_k in conservative variables, linearised at the Roe state.
    Block abs_a;
    const double g1 = gas.gamma - 1.0;
    for (int k = 0; k < 4; ++k) {
      const double du0 = k == 0 ? 1.0 : 0.0;
      const double du1 = k == 1 ? 1.0 : 0.0;
      const double du2 = k == 2 ? 1.0 : 0.0;
      const double du3 = k == 3 ? 1.0 : 0.0;
      const double drho = du0;
      const double du = (du1 - r.u * du0) / r.rho;
      const double dv = (du2 - r.v * du0) / r.rho;
      const double dp = g1 * (du3 - r.u * du1 - r.v * du2 + 0.5 * r.q2 * du0);
      const State col = dissipation(r, drho, du, dv, dp);
      for (int row = 0; row < 4; ++row) abs_a[row * 4 + k] = s * col[row];
    }
    const Block al = euler_flux_jacobian(gas, wl, nx, ny);
    const Block ar = euler_flux_jacobian(gas, wr, nx, ny);
    for (int k = 0; k < 16; ++k) {
      jac->d_left[k] = 0.5 * (al[k] + abs_a[k]);
      jac->d_right[k] = 0.5 * (ar[k] - abs_a[k]);
    }
  }
  return f;
}

}  // namespace tfmb::flow
