#include "flux_viscous.hpp"

#include <cmath>

namespace tfmb::flow {

State viscous_flux(const PerfectGas& gas, const ViscousModel& model, Vec2 xi, Vec2 xj, const State& wi,
                   const State& wj, const std::array<double, 8>& gi, const std::array<double, 8>& gj,
                   Vec2 n, double r_face, double* jac_scale, double eddy_viscosity) {
  const Vec2 d = xj - xi;
  const double length = norm(d);
  const Vec2 t{d.x / length, d.y / length};
  const double ti = gas.temperature(wi);
  const double tj = gas.temperature(wj);
  // node temperature gradients from those of rho and p: T = p / (rho R)
  auto grad_t = [&](const State& w, const std::array<double, 8>& g, double temp, int c) {
    return (g[6 + c] - temp * gas.R * g[c]) / (w[0] * gas.R);
  };
  // averaged gradient, corrected along the edge: g - (g.t - dq/L) t  (Blazek 2015, eq. 5.73)
  auto corrected = [&](double gx_avg, double gy_avg, double dq) {
    const double along = gx_avg * t.x + gy_avg * t.y - dq / length;
    return Vec2{gx_avg - along * t.x, gy_avg - along * t.y};
  };
  const Vec2 gu = corrected(0.5 * (gi[2] + gj[2]), 0.5 * (gi[3] + gj[3]), wj[1] - wi[1]);
  const Vec2 gv = corrected(0.5 * (gi[4] + gj[4]), 0.5 * (gi[5] + gj[5]), wj[2] - wi[2]);
  const Vec2 gt = corrected(0.5 * (grad_t(wi, gi, ti, 0) + grad_t(wj, gj, tj, 0)),
                            0.5 * (grad_t(wi, gi, ti, 1) + grad_t(wj, gj, tj, 1)), tj - ti);
  const double tf = 0.5 * (ti + tj);
  const double mu_laminar = model.viscosity(tf);
  const double mu = mu_laminar + eddy_viscosity;
  const double k = gas.cp() * (mu_laminar / model.prandtl + eddy_viscosity / model.prandtl_turbulent);
  const double uf = 0.5 * (wi[1] + wj[1]);
  const double vf = 0.5 * (wi[2] + wj[2]);
  // Stokes' hypothesis (Blazek 2015, eq. 2.15)
  const double div = gu.x + gv.y + (r_face > 0.0 ? vf / r_face : 0.0);
  const double txx = mu * (2.0 * gu.x - 2.0 / 3.0 * div);
  const double tyy = mu * (2.0 * gv.y - 2.0 / 3.0 * div);
  const double txy = mu * (gu.y + gv.x);
  const double fx = txx * n.x + txy * n.y;
  const double fy = txy * n.x + tyy * n.y;
  if (jac_scale) *jac_scale = mu * norm(n) / length;
  return {0.0, fx, fy, uf * fx + vf * fy + k * (gt.x * n.x + gt.y * n.y)};
}

double hoop_stress(const PerfectGas& gas, const ViscousModel& model, const State& w,
                   const std::array<double, 8>& g, double r, double eddy_viscosity) {
  const double mu = model.viscosity(gas.temperature(w)) + eddy_viscosity;
  // v/r, with its limit dv/dr on the axis (v = 0 there by symmetry)
  const double v_over_r = r > 1e-12 ? w[2] / r : g[5];
  const double div = g[2] + g[5] + v_over_r;
  return mu * (2.0 * v_over_r - 2.0 / 3.0 * div);
}

Block viscous_phi_jacobian(const PerfectGas& gas, const ViscousModel& model, const State& w, double uf,
                           double vf, double eddy_fraction) {
  const double rho = w[0], u = w[1], v = w[2];
  const double cv = gas.cv();
  const double e_tot = gas.conservative(w)[3] / rho;
  const double kt = gas.cp() * ((1.0 - eddy_fraction) / model.prandtl + eddy_fraction / model.prandtl_turbulent);
  // derivatives of u, v, T with respect to (rho, rho u, rho v, rho E)
  const double du[4] = {-u / rho, 1.0 / rho, 0.0, 0.0};
  const double dv[4] = {-v / rho, 0.0, 1.0 / rho, 0.0};
  const double dt[4] = {(-e_tot + u * u + v * v) / (rho * cv), -u / (rho * cv), -v / (rho * cv), 1.0 / (rho * cv)};
  Block m{};
  for (int c = 0; c < 4; ++c) {
    m[4 + c] = du[c];
    m[8 + c] = dv[c];
    m[12 + c] = kt * dt[c] + uf * du[c] + vf * dv[c];
  }
  return m;
}

}  // namespace tfmb::flow
