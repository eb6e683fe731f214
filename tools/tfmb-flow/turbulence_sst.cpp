#include "turbulence_sst.hpp"

#include <algorithm>
#include <cmath>

namespace tfmb::flow::sst {

Constants constants(Variant variant) {
  if (variant == Variant::sst2003) {
    // Menter, Kuntz and Langtry 2003, as TMR's "SST-2003"
    return {5.0 / 9.0, 0.44, 10.0, true, 1e-10, false};
  }
  // Menter 1994: gamma_i = beta_i / beta* - sigma_wi kappa^2 / sqrt(beta*)
  const double root = std::sqrt(beta_star);
  return {beta1 / beta_star - sigma_w1 * kappa * kappa / root,
          beta2 / beta_star - sigma_w2 * kappa * kappa / root,
          20.0,
          false,
          1e-20,
          true};
}

Blending blending(const Constants& c, double k, double omega, double nu, double d, double cross) {
  const double kk = std::max(k, 0.0);
  const double root_k = std::sqrt(kk);
  const double viscous = 500.0 * nu / (d * d * omega);
  // CD_komega per unit mass: 2 sigma_w2 / omega grad k . grad omega, floored (Menter 1994, eq. 14)
  const double cd = std::max(2.0 * sigma_w2 * cross / omega, c.cross_diffusion_floor);
  const double arg1 = std::min(std::max(root_k / (beta_star * omega * d), viscous),
                               4.0 * sigma_w2 * kk / (cd * d * d));
  const double arg2 = std::max(2.0 * root_k / (beta_star * omega * d), viscous);
  return {std::tanh(std::pow(arg1, 4)), std::tanh(arg2 * arg2)};
}

double eddy_viscosity(double rho, double k, double omega, double shear, double f2) {
  if (k <= 0.0)
    return 0.0;
  return rho * a1 * k / std::max(a1 * omega, shear * f2);
}

Shear shear(double dudx, double dudy, double dvdx, double dvdy, double hoop) {
  const double sxy = 0.5 * (dudy + dvdx);
  // 2 S_ij S_ij with the azimuthal normal strain v/r of an axisymmetric flow
  const double s2 = 2.0 * (dudx * dudx + dvdy * dvdy + hoop * hoop + 2.0 * sxy * sxy);
  return {std::sqrt(s2), std::abs(dvdx - dudy), dudx + dvdy + hoop};
}

Source source(const Constants& c, double k, double omega, const Shear& s, double f1, double f2,
              double cross) {
  const double kk = std::max(k, 0.0);
  const double magnitude = c.vorticity ? s.vorticity : s.strain;
  // rho k / mu_t, the eddy viscosity's inverse time scale
  const double ratio = std::max(a1 * omega, magnitude * f2) / a1;
  // P / (rho k): SST-2003 mu_t (S^2 - 2/3 div^2) - 2/3 rho k div; SST-V mu_t Omega^2 - 2/3 rho k
  // div
  const double shear_term = c.vorticity
                                ? magnitude * magnitude
                                : magnitude * magnitude - 2.0 / 3.0 * s.divergence * s.divergence;
  const double p = shear_term / ratio - 2.0 / 3.0 * s.divergence;
  const double cap = c.production_limit * beta_star * omega;
  const double p_limited = std::min(p, cap);
  const double beta = blend(f1, beta1, beta2);
  const double gamma = blend(f1, c.gamma1, c.gamma2);
  const double cross_term = (1.0 - f1) * 2.0 * sigma_w2 * cross / omega;
  Source out;
  out.limited = p > cap;
  out.k = kk * (p_limited - beta_star * omega);
  // gamma P~ / (rho nu_t) = gamma P~ / mu_t = gamma (P~ / (rho k)) (rho k / mu_t)
  out.omega = gamma * (c.limit_omega_production ? p_limited : p) * ratio - beta * omega * omega +
              cross_term;
  out.k_slope = std::min(p_limited, 0.0) - beta_star * omega;
  out.omega_slope = -2.0 * beta * omega - std::max(cross_term, 0.0) / omega;
  return out;
}

double freestream_k(double sound_speed) {
  return 9e-9 * sound_speed * sound_speed;
}

double freestream_omega(double rho, double sound_speed, double mu) {
  return 1e-6 * rho * sound_speed * sound_speed / mu;
}

double wall_omega(double nu, double first_node_distance) {
  return 60.0 * nu / (beta1 * first_node_distance * first_node_distance);
}

}  // namespace tfmb::flow::sst
