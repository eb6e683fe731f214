// Menter's k-omega shear-stress-transport (SST) two-equation model, in the two forms the NASA
// Turbulence Modeling Resource defines (https://turbmodels.larc.nasa.gov/sst.html):
//   - SST-2003 (Menter, Kuntz and Langtry 2003, Turbulence, Heat and Mass Transfer 4:625-632):
//     eddy viscosity limited with the strain rate magnitude S, the exact production
//     P = tau_ij du_i/dx_j = mu_t (S^2 - 2/3 div(u)^2) - 2/3 rho k div(u), limited to
//     10 beta* rho omega k in both equations, gamma1 = 5/9, gamma2 = 0.44, CD_komega floored at
//     1e-10;
//   - SST-V (Menter 1994, AIAA J. 32(8):1598-1605, with the vorticity source of TMR's "SST-V"):
//     eddy viscosity limited with the vorticity magnitude Omega, production mu_t Omega^2 -
//     2/3 rho k div(u), limited to 20 beta* rho omega k in the k equation only (Menter 1993,
//     AIAA 93-2906, as TMR recommends), gamma from beta/beta* - sigma_w kappa^2 / sqrt(beta*),
//     CD_komega floored at 1e-20.
// Both as TMR's "e" forms: the 2/3 rho k of the Boussinesq stress is left out of the mean-flow
// momentum and energy equations, the production term is kept as defined. TMR's flat-plate reference
// results of CFL3D and
//     FUN3D are for this form (refdata/flow/tmr_flatplate_sst_cf_cd_convergence.csv).
//
// The transport equations (TMR, conservation form)
//   d(rho k)/dt + div(rho u k) = P - beta* rho omega k + div((mu + sigma_k mu_t) grad k)
//   d(rho w)/dt + div(rho u w) = gamma/nu_t P - beta rho w^2 + div((mu + sigma_w mu_t) grad w)
//                                + 2 (1 - F1) rho sigma_w2 / w grad k . grad w
// are solved per unit mass (divided by rho, continuity subtracted), as the solver does with
// Spalart-Allmaras' nu_tilde. The sources here are per unit mass: [m^2/s^3] and [1/s^2].
#pragma once

namespace tfmb::flow::sst {

enum class Variant { sst2003, sst_v };

inline constexpr double beta_star = 0.09;
inline constexpr double kappa = 0.41;
inline constexpr double a1 = 0.31;
// inner (k-omega, 1) and outer (transformed k-epsilon, 2) constants
inline constexpr double sigma_k1 = 0.85, sigma_k2 = 1.0;
inline constexpr double sigma_w1 = 0.5, sigma_w2 = 0.856;
inline constexpr double beta1 = 0.075, beta2 = 0.0828;

struct Constants {
  double gamma1, gamma2;
  double production_limit;      // P <= production_limit * beta* rho omega k (in the k equation)
  bool limit_omega_production;  // SST-2003: the limited P in the omega equation too
  double cross_diffusion_floor;
  bool vorticity;  // SST-V: Omega in mu_t and P; SST-2003: S
};
Constants constants(Variant variant);

// The blending functions (Menter 1994, eqs. 11-14 and 16-18), F1 and F2 both in [0, 1].
// k [m^2/s^2], omega [1/s], nu = mu/rho [m^2/s], d the wall distance [m],
// cross = grad k . grad omega [1/s^3].
struct Blending {
  double f1 = 0.0;
  double f2 = 0.0;
};
Blending blending(const Constants& c, double k, double omega, double nu, double d, double cross);

// phi = F1 phi1 + (1 - F1) phi2
inline double blend(double f1, double inner, double outer) {
  return f1 * inner + (1.0 - f1) * outer;
}

// Eddy viscosity [Pa s]: rho a1 k / max(a1 omega, shear F2), shear = S or Omega by variant;
// zero for k <= 0.
double eddy_viscosity(double rho, double k, double omega, double shear, double f2);

// The velocity gradient's invariants the model needs (planar; `hoop` = v/r adds the
// axisymmetric azimuthal strain, 0 when planar).
struct Shear {
  double strain = 0.0;      // S = sqrt(2 S_ij S_ij) [1/s]
  double vorticity = 0.0;   // Omega = sqrt(2 W_ij W_ij) [1/s]
  double divergence = 0.0;  // div u [1/s]
};
Shear shear(double dudx, double dudy, double dvdx, double dvdy, double hoop = 0.0);

// Sources per unit mass and their implicit parts at one node. `ratio` = rho k / mu_t =
// max(a1 omega, shear F2) / a1 [1/s], so that gamma P / (rho nu_t) stays finite as k -> 0.
struct Source {
  double k = 0.0;      // (P~ - beta* rho omega k) / rho [m^2/s^3]
  double omega = 0.0;  // (gamma P~ / nu_t - beta rho omega^2 + cross-diffusion) / rho [1/s^2]
  // d(source)/d(variable) kept for the implicit operator: only the stabilising (negative)
  // parts, so the scalar systems stay diagonally dominant
  double k_slope = 0.0;
  double omega_slope = 0.0;
  bool limited = false;  // the production limiter was active
};
Source source(const Constants& c, double k, double omega, const Shear& s, double f1, double f2,
              double cross);

// Boundary values (TMR, "Farfield boundary conditions" and "Wall boundary conditions" of the
// SST page): k_inf = 9e-9 a^2, omega_inf = 1e-6 rho a^2 / mu (so mu_t/mu = 0.009 in the free
// stream, independent of the velocity, which a jet into air at rest needs); on a no-slip wall
// k = 0 and omega = 60 nu / (beta1 d1^2), d1 the distance of the first node off the wall.
double freestream_k(double sound_speed);
double freestream_omega(double rho, double sound_speed, double mu);
double wall_omega(double nu, double first_node_distance);

}  // namespace tfmb::flow::sst
