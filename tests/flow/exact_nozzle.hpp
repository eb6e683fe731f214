// Exact quasi-one-dimensional nozzle flow of a perfect gas: isentropic area-Mach relation with
// at most one normal shock (Anderson 2003, Modern Compressible Flow, ch. 5; eqs. 5.20, 3.57,
// 3.59, 3.63). The reference for the NPARC CDV nozzle verification.
#pragma once

#include <functional>

namespace tfmb::flow {

// A/A* as a function of the Mach number (Anderson 2003, eq. 5.20).
double area_ratio_of_mach(double mach, double gamma);
// Inverse of area_ratio_of_mach on the subsonic or supersonic branch.
double mach_of_area_ratio(double area_ratio, double gamma, bool supersonic);
// p/p0 of isentropic flow (Anderson 2003, eq. 3.30).
double isentropic_pressure_ratio(double mach, double gamma);
// Normal shock: downstream Mach, and p02/p01 (Anderson 2003, eqs. 3.51, 3.57, 3.63).
double normal_shock_mach(double m1, double gamma);
double normal_shock_total_pressure_ratio(double m1, double gamma);

class Quasi1dNozzle {
 public:
  // area(x) > 0 on [x_inlet, x_exit], smallest at x_throat; p_exit_ratio = p_exit / p0.
  Quasi1dNozzle(std::function<double(double)> area, double x_inlet, double x_throat, double x_exit, double gamma,
                double p_exit_ratio);

  bool choked() const { return choked_; }
  bool has_shock() const { return has_shock_; }
  double shock_position() const { return shock_x_; }  // meaningful when has_shock()
  double mach(double x) const;
  double pressure_ratio(double x) const;  // p / p0 (inlet total pressure)
  // Mass flow for inlet total conditions, in the units of area (per unit width for a 2D
  // channel whose "area" is its height) [kg/s].
  double mass_flow(double p0, double t0, double gas_r) const;

 private:
  std::function<double(double)> area_;
  double x_throat_, x_exit_, gamma_;
  bool choked_ = false, has_shock_ = false;
  double shock_x_ = 0.0;
  double a_star_1_ = 0.0;       // sonic area upstream of any shock
  double a_star_2_ = 0.0;       // sonic area downstream of the shock
  double p0_ratio_ = 1.0;       // p02 / p01 across the shock
  bool exit_supersonic_ = false;
};

}  // namespace tfmb::flow
