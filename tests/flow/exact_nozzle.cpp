#include "exact_nozzle.hpp"

#include <cmath>
#include <stdexcept>

namespace tfmb::flow {

double area_ratio_of_mach(double m, double g) {
  return 1.0 / m * std::pow(2.0 / (g + 1.0) * (1.0 + 0.5 * (g - 1.0) * m * m), 0.5 * (g + 1.0) / (g - 1.0));
}

double mach_of_area_ratio(double ratio, double g, bool supersonic) {
  if (ratio < 1.0) throw std::invalid_argument("area ratio below 1");
  double lo = supersonic ? 1.0 : 1e-12;
  double hi = supersonic ? 100.0 : 1.0;
  // area ratio decreases on the subsonic branch and increases on the supersonic one
  for (int k = 0; k < 200; ++k) {
    const double mid = 0.5 * (lo + hi);
    const bool above = area_ratio_of_mach(mid, g) > ratio;
    if (above == supersonic) hi = mid;
    else lo = mid;
  }
  return 0.5 * (lo + hi);
}

double isentropic_pressure_ratio(double m, double g) {
  return std::pow(1.0 + 0.5 * (g - 1.0) * m * m, -g / (g - 1.0));
}

double normal_shock_mach(double m1, double g) {
  return std::sqrt((1.0 + 0.5 * (g - 1.0) * m1 * m1) / (g * m1 * m1 - 0.5 * (g - 1.0)));
}

double normal_shock_total_pressure_ratio(double m1, double g) {
  const double m2 = normal_shock_mach(m1, g);
  const double p2_p1 = 1.0 + 2.0 * g / (g + 1.0) * (m1 * m1 - 1.0);
  return p2_p1 * isentropic_pressure_ratio(m1, g) / isentropic_pressure_ratio(m2, g);
}

Quasi1dNozzle::Quasi1dNozzle(std::function<double(double)> area, double x_inlet, double x_throat, double x_exit,
                             double g, double pe)
    : area_(std::move(area)), x_throat_(x_throat), x_exit_(x_exit), gamma_(g) {
  (void)x_inlet;
  const double a_t = area_(x_throat);
  const double a_e = area_(x_exit);
  const double pe_subsonic_choked = isentropic_pressure_ratio(mach_of_area_ratio(a_e / a_t, g, false), g);
  if (pe >= 1.0) throw std::invalid_argument("exit pressure ratio must be below 1");
  if (pe >= pe_subsonic_choked) {
    const double me = std::sqrt(2.0 / (g - 1.0) * (std::pow(pe, -(g - 1.0) / g) - 1.0));
    a_star_1_ = a_star_2_ = a_e / area_ratio_of_mach(me, g);
    return;
  }
  choked_ = true;
  a_star_1_ = a_t;
  const double m_exit_sup = mach_of_area_ratio(a_e / a_t, g, true);
  const double pe_shock_at_exit = isentropic_pressure_ratio(m_exit_sup, g) *
                                  (1.0 + 2.0 * g / (g + 1.0) * (m_exit_sup * m_exit_sup - 1.0));
  if (pe <= pe_shock_at_exit) {
    exit_supersonic_ = true;
    a_star_2_ = a_t;
    return;
  }
  has_shock_ = true;
  auto exit_pressure = [&](double xs) {
    const double m1 = mach_of_area_ratio(area_(xs) / a_t, g, true);
    const double r = normal_shock_total_pressure_ratio(m1, g);
    const double me = mach_of_area_ratio(a_e / (a_t / r), g, false);
    return r * isentropic_pressure_ratio(me, g);
  };
  double lo = x_throat, hi = x_exit;  // exit pressure falls as the shock moves downstream
  for (int k = 0; k < 200; ++k) {
    const double mid = 0.5 * (lo + hi);
    if (exit_pressure(mid) > pe) lo = mid;
    else hi = mid;
  }
  shock_x_ = 0.5 * (lo + hi);
  p0_ratio_ = normal_shock_total_pressure_ratio(mach_of_area_ratio(area_(shock_x_) / a_t, g, true), g);
  a_star_2_ = a_t / p0_ratio_;
}

double Quasi1dNozzle::mach(double x) const {
  if (!choked_) return mach_of_area_ratio(area_(x) / a_star_1_, gamma_, false);
  if (x <= x_throat_) return mach_of_area_ratio(area_(x) / a_star_1_, gamma_, false);
  if (has_shock_ && x > shock_x_) return mach_of_area_ratio(area_(x) / a_star_2_, gamma_, false);
  return mach_of_area_ratio(area_(x) / a_star_1_, gamma_, true);
}

double Quasi1dNozzle::pressure_ratio(double x) const {
  const double p0 = (has_shock_ && x > shock_x_) ? p0_ratio_ : 1.0;
  return p0 * isentropic_pressure_ratio(mach(x), gamma_);
}

double Quasi1dNozzle::mass_flow(double p0, double t0, double r) const {
  // rho* a* A* with the sonic state of the inlet total conditions (Anderson 2003, eq. 5.21)
  const double g = gamma_;
  return p0 * a_star_1_ / std::sqrt(r * t0) * std::sqrt(g) * std::pow(2.0 / (g + 1.0), 0.5 * (g + 1.0) / (g - 1.0));
}

}  // namespace tfmb::flow
