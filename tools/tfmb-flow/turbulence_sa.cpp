#include "turbulence_sa.hpp"

#include <algorithm>
#include <cmath>

#include "tfmb/common/dual.hpp"

namespace tfmb::flow::sa {

using tfmb::Dual;

double fv1(double chi) {
  const double c3 = chi * chi * chi;
  return c3 / (c3 + cv1 * cv1 * cv1);
}

double eddy_viscosity(double rho, double nu_tilde, double nu) {
  if (nu_tilde <= 0.0) return 0.0;
  return rho * nu_tilde * fv1(nu_tilde / nu);
}

double eddy_viscosity_derivative(double rho, double nu_tilde, double nu) {
  if (nu_tilde <= 0.0)
    return 0.0;
  const double chi = nu_tilde / nu;
  const double c3 = chi * chi * chi;
  const double v3 = cv1 * cv1 * cv1;
  // fv1' = 3 chi^2 cv1^3 / (chi^3 + cv1^3)^2
  return rho * (fv1(chi) + 3.0 * c3 * v3 / ((c3 + v3) * (c3 + v3)));
}

double diffusivity(double nu_tilde, double nu) {
  if (nu_tilde >= 0.0) return nu + nu_tilde;
  // SA-neg: fn = (cn1 + chi^3) / (cn1 - chi^3) (Allmaras et al. 2012, eq. 22)
  const double chi = nu_tilde / nu;
  const double c3 = chi * chi * chi;
  return nu + nu_tilde * (cn1 + c3) / (cn1 - c3);
}

double diffusivity_derivative(double nu_tilde, double nu) {
  if (nu_tilde >= 0.0)
    return 1.0;
  using D1 = Dual<1>;
  const D1 x = D1::variable(0, nu_tilde);
  const D1 chi = x / nu;
  const D1 c3 = chi * chi * chi;
  return (nu + x * (cn1 + c3) / (cn1 - c3)).d[0];
}

namespace {

// P - D of the nu_tilde >= 0 branch (standard SA with the S-tilde clipping of TMR note 1(c)),
// templated on the scalar of nu_tilde so that a Dual gives its exact derivative.
template <typename T, typename W>
void production_destruction(const T& nu_tilde, double nu, const W& vorticity, double d,
                            bool with_ft2, T& production, T& destruction) {
  using std::exp;
  using std::pow;
  const double kd2 = kappa * kappa * d * d;
  const T chi = nu_tilde / nu;
  const T chi3 = chi * chi * chi;
  const T f1 = chi3 / (chi3 + cv1 * cv1 * cv1);
  const T fv2 = 1.0 - chi / (1.0 + chi * f1);
  const T s_bar = nu_tilde * fv2 / kd2;
  const T s_tilde =
      s_bar >= -cv2 * vorticity
          ? vorticity + s_bar
          : vorticity + vorticity * (cv2 * cv2 * vorticity + cv3 * s_bar) /
                            ((cv3 - 2.0 * cv2) * vorticity - s_bar);
  const T ft2 = with_ft2 ? T(ct3 * exp(-ct4 * chi * chi)) : T(0.0);
  production = cb1 * (1.0 - ft2) * s_tilde * nu_tilde;
  T r(10.0);
  if (s_tilde > 0.0) {
    const T ratio = nu_tilde / (s_tilde * kd2);
    if (ratio < 10.0)
      r = ratio;
  }
  const T r3 = r * r * r;
  const T g = r + cw2 * (r3 * r3 - r);
  const T g3 = g * g * g;
  const double c6 = cw3 * cw3 * cw3 * cw3 * cw3 * cw3;
  const T fw = g * pow((1.0 + c6) / (g3 * g3 + c6), 1.0 / 6.0);
  destruction = (cw1 * fw - cb1 / (kappa * kappa) * ft2) * nu_tilde * nu_tilde / (d * d);
}

}  // namespace

Source source(double nu_tilde, double nu, double vorticity, double d, bool with_ft2) {
  Source s;
  if (nu_tilde < 0.0) {
    // SA-neg (Allmaras et al. 2012, eqs. 20-21): production cb1 (1 - ct3) Omega nu_tilde,
    // destruction -cw1 (nu_tilde/d)^2
    s.production = cb1 * (1.0 - ct3) * vorticity * nu_tilde;
    s.destruction = -cw1 * nu_tilde * nu_tilde / (d * d);
    // d(P - D)/d nu_tilde = cb1 (1 - ct3) Omega + 2 cw1 nu_tilde / d^2; both terms < 0 here
    s.d_source_exact = cb1 * (1.0 - ct3) * vorticity + 2.0 * cw1 * nu_tilde / (d * d);
    s.d_source = std::min(s.d_source_exact, 0.0);
    return s;
  }
  // The whole source is linearised, exactly (forward AD): near the wall the production falls
  // with nu_tilde through fv2 in S-tilde, and leaving that explicit makes the implicit step
  // overshoot into a two-iteration cycle. Only the stabilising (negative) part is kept.
  using D1 = Dual<1>;
  D1 production, destruction;
  production_destruction(D1::variable(0, nu_tilde), nu, vorticity, d, with_ft2, production,
                         destruction);
  s.production = production.v;
  s.destruction = destruction.v;
  s.d_source_exact = production.d[0] - destruction.d[0];
  s.d_source = std::min(s.d_source_exact, 0.0);
  return s;
}

double source_vorticity_derivative(double nu_tilde, double nu, double vorticity, double d,
                                   bool with_ft2) {
  if (nu_tilde < 0.0)
    return cb1 * (1.0 - ct3) * nu_tilde;
  using D1 = Dual<1>;
  D1 production, destruction;
  production_destruction(D1(nu_tilde), nu, D1::variable(0, vorticity), d, with_ft2, production,
                         destruction);
  return production.d[0] - destruction.d[0];
}

double source_derivative(double nu_tilde, double nu, double vorticity, double d, bool with_ft2) {
  if (nu_tilde < 0.0)
    return cb1 * (1.0 - ct3) * vorticity + 2.0 * cw1 * nu_tilde / (d * d);
  using D1 = Dual<1>;
  D1 production, destruction;
  production_destruction(D1::variable(0, nu_tilde), nu, vorticity, d, with_ft2, production,
                         destruction);
  return production.d[0] - destruction.d[0];
}

}  // namespace tfmb::flow::sa
