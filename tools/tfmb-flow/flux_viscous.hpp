// Laminar viscous fluxes of the Navier-Stokes equations on the dual faces, with the edge-normal
// gradient correction of the averaged node gradients (Blazek 2015, eq. 5.73; Haselbacher and
// Blazek 2000, AIAA J. 38:2094) and Sutherland's viscosity law (White 2006, eq. 1-36).
#pragma once

#include <array>
#include <cmath>

#include "gas.hpp"
#include "mesh.hpp"

namespace tfmb::flow {

struct ViscousModel {
  double prandtl = 0.72;
  double prandtl_turbulent = 0.9;
  double mu_ref = 1.716e-5;       // [Pa s] at t_ref
  double t_ref = 273.15;          // [K]
  double sutherland_s = 110.4;    // [K]
  // Constant viscosity [Pa s] when > 0 (verification cases); Sutherland otherwise.
  double constant_mu = 0.0;

  double viscosity(double t) const {
    if (constant_mu > 0.0) return constant_mu;
    // (t/t_ref)^1.5 as r sqrt(r): pow was 14 % of a second-order SA run (perf, issue 17)
    const double r = t / t_ref;
    return mu_ref * r * std::sqrt(r) * (t_ref + sutherland_s) / (t + sutherland_s);
  }
};

// Viscous flux through a face with normal n between nodes i and j (positions xi, xj, primitive
// states wi, wj, primitive gradients gi, gj as produced by lsq_gradients). Returns the flux of
// (0, momentum, energy) leaving node i. r_face > 0 selects the axisymmetric stresses (y = r,
// velocity divergence with the hoop term v/r; n is then the r-weighted normal). When
// jac_scale is non-null it receives the coefficient c = mu |n| / L of the thin-shear
// approximation used in the implicit operator. eddy_viscosity mu_t [Pa s] at the face adds to
// mu in the stresses (Boussinesq) and mu_t cp / Pr_t to the conductivity (Blazek 2015, eq. 7.9).
State viscous_flux(const PerfectGas& gas, const ViscousModel& model, Vec2 xi, Vec2 xj, const State& wi,
                   const State& wj, const std::array<double, 8>& gi, const std::array<double, 8>& gj,
                   Vec2 n, double r_face, double* jac_scale, double eddy_viscosity = 0.0);

// Hoop stress tau_theta_theta = mu (2 v/r - 2/3 div V) at a node of an axisymmetric flow
// (White 2006, eq. 2-29 in cylindrical coordinates); on the axis v/r -> dv/dr.
double hoop_stress(const PerfectGas& gas, const ViscousModel& model, const State& w,
                   const std::array<double, 8>& g, double r, double eddy_viscosity = 0.0);

// d Phi / dU for the thin-shear implicit operator F_v ~ c (Phi(U_j) - Phi(U_i)), with
// Phi = (0, u, v, k/mu_eff T + u_f u + v_f v) and (u_f, v_f) the face velocity;
// eddy_fraction = mu_t / (mu + mu_t) sets k / mu_eff = cp ((1 - f)/Pr + f/Pr_t).
Block viscous_phi_jacobian(const PerfectGas& gas, const ViscousModel& model, const State& w, double u_face,
                           double v_face, double eddy_fraction = 0.0);

}  // namespace tfmb::flow
