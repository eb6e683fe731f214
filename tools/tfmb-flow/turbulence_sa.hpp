// Spalart-Allmaras one-equation turbulence model, the "SA" (standard, with the ft2 term) and
// "SA-neg" versions as defined by the NASA Turbulence Modeling Resource (TMR,
// https://turbmodels.larc.nasa.gov/spalart.html; Spalart and Allmaras 1994, Rech. Aerosp. 1:5-21;
// Allmaras, Johnson and Spalart 2012, ICCFD7-1902 for SA-neg and the S-tilde clipping).
//
// The working variable is nu_tilde [m^2/s]; the eddy viscosity is mu_t = rho nu_tilde fv1 for
// nu_tilde >= 0 and 0 otherwise.
#pragma once

namespace tfmb::flow::sa {

inline constexpr double cb1 = 0.1355;
inline constexpr double cb2 = 0.622;
inline constexpr double sigma = 2.0 / 3.0;
inline constexpr double kappa = 0.41;
inline constexpr double cw2 = 0.3;
inline constexpr double cw3 = 2.0;
inline constexpr double cv1 = 7.1;
inline constexpr double ct3 = 1.2;
inline constexpr double ct4 = 0.5;
inline constexpr double cv2 = 0.7;   // S-tilde clipping (TMR, note 1(c))
inline constexpr double cv3 = 0.9;
inline constexpr double cn1 = 16.0;  // SA-neg diffusion
inline constexpr double cw1 = cb1 / (kappa * kappa) + (1.0 + cb2) / sigma;

// fv1 = chi^3 / (chi^3 + cv1^3), chi = nu_tilde / nu (TMR eq. for mu_t).
double fv1(double chi);

// Eddy viscosity [Pa s]: rho nu_tilde fv1 (zero for a negative nu_tilde, SA-neg).
double eddy_viscosity(double rho, double nu_tilde, double nu);

// d mu_t / d nu_tilde at fixed rho and nu: rho (fv1 + chi fv1'(chi)) (0 for nu_tilde <= 0).
double eddy_viscosity_derivative(double rho, double nu_tilde, double nu);

// Source terms per unit volume of the nu_tilde equation written as
//   D nu_tilde / Dt = production - destruction + diffusion,
// with vorticity magnitude `vorticity` [1/s] and wall distance d [m]. d_source is the negative
// part of the exact d(production - destruction)/d nu_tilde, for the implicit operator (a
// positive derivative is left out: it would weaken the diagonal).
struct Source {
  double production = 0.0;
  double destruction = 0.0;
  double d_source = 0.0;
  double d_source_exact = 0.0;  // the whole derivative, both signs (as source_derivative())
};
Source source(double nu_tilde, double nu, double vorticity, double wall_distance, bool with_ft2 = true);

// The exact d(production - destruction)/d nu_tilde, both signs (forward AD; source() keeps only
// its negative part for the implicit operator).
double source_derivative(double nu_tilde, double nu, double vorticity, double wall_distance,
                         bool with_ft2 = true);

// d(production - destruction)/d vorticity (forward AD): the nu_tilde equation's dependence on
// the mean flow through the vorticity, for the cross blocks of the coupled Jacobian.
double source_vorticity_derivative(double nu_tilde, double nu, double vorticity,
                                   double wall_distance, bool with_ft2 = true);

// Diffusion coefficient nu + nu_tilde (SA) or nu + nu_tilde fn (SA-neg for nu_tilde < 0).
double diffusivity(double nu_tilde, double nu);

// d diffusivity / d nu_tilde (1 for nu_tilde >= 0; the SA-neg branch by forward AD).
double diffusivity_derivative(double nu_tilde, double nu);

}  // namespace tfmb::flow::sa
