#include "turbulence_sa.hpp"

#include <algorithm>
#include <cmath>

namespace tfmb::flow::sa {

double fv1(double chi) {
  const double c3 = chi * chi * chi;
  return c3 / (c3 + cv1 * cv1 * cv1);
}

double eddy_viscosity(double rho, double nu_tilde, double nu) {
  if (nu_tilde <= 0.0) return 0.0;
  return rho * nu_tilde * fv1(nu_tilde / nu);
}

double diffusivity(double nu_tilde, double nu) {
  if (nu_tilde >= 0.0) return nu + nu_tilde;
  // SA-neg: fn = (cn1 + chi^3) / (cn1 - chi^3) (Allmaras et al. 2012, eq. 22)
  const double chi = nu_tilde / nu;
  const double c3 = chi * chi * chi;
  return nu + nu_tilde * (cn1 + c3) / (cn1 - c3);
}

namespace {

Source source_terms(double nu_tilde, double nu, double vorticity, double d, bool with_ft2) {
  Source s;
  const double kd2 = kappa * kappa * d * d;
  const double chi = nu_tilde / nu;
  if (nu_tilde < 0.0) {
    // SA-neg (Allmaras et al. 2012, eqs. 20-21): production cb1 (1 - ct3) Omega nu_tilde,
    // destruction -cw1 (nu_tilde/d)^2
    s.production = cb1 * (1.0 - ct3) * vorticity * nu_tilde;
    s.destruction = -cw1 * nu_tilde * nu_tilde / (d * d);
    // d(P - D)/d nu_tilde = cb1 (1 - ct3) Omega + 2 cw1 nu_tilde / d^2; both terms < 0 here
    s.d_source = cb1 * (1.0 - ct3) * vorticity + 2.0 * cw1 * nu_tilde / (d * d);
    s.d_source = std::min(s.d_source, 0.0);
    return s;
  }
  const double f1 = fv1(chi);
  const double fv2 = 1.0 - chi / (1.0 + chi * f1);
  // S-tilde with the clipping of TMR note 1(c) that keeps it positive
  const double s_bar = nu_tilde * fv2 / kd2;
  double s_tilde;
  if (s_bar >= -cv2 * vorticity) {
    s_tilde = vorticity + s_bar;
  } else {
    s_tilde = vorticity + vorticity * (cv2 * cv2 * vorticity + cv3 * s_bar) / ((cv3 - 2.0 * cv2) * vorticity - s_bar);
  }
  const double ft2 = with_ft2 ? ct3 * std::exp(-ct4 * chi * chi) : 0.0;
  s.production = cb1 * (1.0 - ft2) * s_tilde * nu_tilde;
  double r = 10.0;
  if (s_tilde > 0.0) r = std::min(nu_tilde / (s_tilde * kd2), 10.0);
  const double g = r + cw2 * (std::pow(r, 6) - r);
  const double c6 = std::pow(cw3, 6);
  const double fw = g * std::pow((1.0 + c6) / (std::pow(g, 6) + c6), 1.0 / 6.0);
  s.destruction = (cw1 * fw - cb1 / (kappa * kappa) * ft2) * nu_tilde * nu_tilde / (d * d);
  return s;
}

}  // namespace

Source source(double nu_tilde, double nu, double vorticity, double d, bool with_ft2) {
  Source s = source_terms(nu_tilde, nu, vorticity, d, with_ft2);
  if (nu_tilde < 0.0) return s;
  // The whole source is linearised (by a one-sided difference): near the wall the production
  // falls with nu_tilde through fv2 in S-tilde, and leaving that explicit makes the implicit
  // step overshoot into a two-iteration cycle. Only the stabilising (negative) part is kept.
  const double h = 1e-7 * (nu_tilde + nu);
  const Source up = source_terms(nu_tilde + h, nu, vorticity, d, with_ft2);
  const double derivative = ((up.production - up.destruction) - (s.production - s.destruction)) / h;
  s.d_source = std::min(derivative, 0.0);
  return s;
}

}  // namespace tfmb::flow::sa
