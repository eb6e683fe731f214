// Free thermal strain from a mean expansion coefficient (MIL-HDBK-5 convention, refdata
// README): alpha_mean(T) is the mean coefficient from T_ref to T, so the free strain from T_ref
// is alpha_mean(T) (T - T_ref). Relative to a stress-free temperature T_0:
//   eps_th(T) = alpha_mean(T) (T - T_ref) - alpha_mean(T_0) (T_0 - T_ref)
// (MIL-HDBK-5J sec. 1.4.5 on mean coefficients), which is alpha_mean(T) (T - T_ref) when
// T_0 = T_ref.
//
// Through the thickness the temperature is linear (thermal.md: mean T_m, outer minus inner
// difference dT), so the surfaces are at T_m -+ dT/2 and the thermal curvature (per unit
// distance towards the outer surface) is the secant
//   kappa_th = (eps_th(T_m + dT/2) - eps_th(T_m - dT/2)) / t,
// which is alpha dT / t for a constant alpha (Boley & Weiner, Theory of Thermal Stresses,
// 1960, sec. 9.2). The axial thermal strain of the section is the thickness mean of
// eps_th(T(z)); with alpha_mean linear in T between table points eps_th is quadratic in z, so
// Simpson's rule on the surfaces and the middle is exact:
//   eps_section = (eps_inner + 4 eps_mean + eps_outer) / 6
// and the secant curvature above is exactly the first moment 12/t^3 int eps_th z dz (the
// quadratic part is symmetric). What the linear profile eps_section + kappa_th z leaves out at
// a surface is the self-equilibrated thermal strain a beam cannot carry (Boley & Weiner sec. 9.3).
#pragma once

namespace tfmb::matmap {

// Free thermal strain for alpha_mean(T) and alpha_mean(T0) looked up by the caller.
inline double thermal_strain(double alpha_at_t, double t, double alpha_at_t0, double t0, double t_ref) {
  return alpha_at_t * (t - t_ref) - alpha_at_t0 * (t0 - t_ref);
}

inline double section_thermal_strain(double strain_inner, double strain_mean, double strain_outer) {
  return (strain_inner + 4.0 * strain_mean + strain_outer) / 6.0;
}

inline double thermal_curvature(double strain_outer, double strain_inner, double thickness) {
  return (strain_outer - strain_inner) / thickness;
}

}  // namespace tfmb::matmap
