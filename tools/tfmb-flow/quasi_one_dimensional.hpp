// Quasi-one-dimensional nozzle flow of a perfect gas: isentropic area-Mach relation with at most
// one normal shock (Anderson 2003, Modern Compressible Flow, ch. 5; eqs. 5.20, 3.57, 3.59, 3.63).
// Two uses: the exact reference of the NPARC CDV nozzle verification, and the start state of an
// internal flow (a duct from an inflow to an outflow boundary), whose choked throat and normal
// shock it places where the one-dimensional theory puts them instead of letting the pseudo-time
// march find them from gas at rest (tools/tfmb-flow/README.md, "Quasi-one-dimensional start").
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "gas.hpp"
#include "mesh_dual.hpp"

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
// Mass flow per unit throat area of a choked throat, rho* a* from the total conditions p0 [Pa]
// and t0 [K] (Anderson 2003, eq. 5.21) [kg/(s m^2)].
double choked_mass_flux(double p0, double t0, double gamma, double gas_r);

class Quasi1dNozzle {
 public:
  // area(x) > 0 on [x_inlet, x_exit], smallest at x_throat; p_exit_ratio = p_exit / p0.
  Quasi1dNozzle(std::function<double(double)> area, double x_inlet, double x_throat, double x_exit,
                double gamma, double p_exit_ratio);

  bool choked() const { return choked_; }
  bool has_shock() const { return has_shock_; }
  double shock_position() const { return shock_x_; }  // meaningful when has_shock()
  double mach(double x) const;
  double pressure_ratio(double x) const;        // p / p0 (inlet total pressure)
  double total_pressure_ratio(double x) const;  // the local total pressure / p0 (below 1 behind the shock)
  // Mass flow for inlet total conditions, in the units of area (per unit width for a 2D
  // channel whose "area" is its height) [kg/s].
  double mass_flow(double p0, double t0, double gas_r) const;

 private:
  std::function<double(double)> area_;
  double x_throat_, x_exit_, gamma_;
  bool choked_ = false, has_shock_ = false;
  double shock_x_ = 0.0;
  double a_star_1_ = 0.0;  // sonic area upstream of any shock
  double a_star_2_ = 0.0;  // sonic area downstream of the shock
  double p0_ratio_ = 1.0;  // p02 / p01 across the shock
  bool exit_supersonic_ = false;
};

// The flow area of a duct along x at evenly spaced stations: the length of the line x = const
// inside the fluid (planar, per unit depth) or the area of the annuli it sweeps about the axis
// y = 0 (axisymmetric), summed over the cells it crosses.
struct DuctSections {
  std::vector<double> x;     // [m], increasing
  std::vector<double> area;  // [m] (planar) or [m^2] (axisymmetric)
  // Linear between stations, the end stations' values beyond them.
  double area_at(double x) const;
};
DuctSections duct_sections(const Mesh& mesh, Geometry geometry, int stations);

// What the quasi-1D start found, for the log.
struct Quasi1dStart {
  std::vector<State> states;  // primitive (rho, u, v, p) per node, velocity along +x
  double throat_x = 0.0, throat_area = 0.0, exit_area = 0.0;
  bool choked = false, has_shock = false;
  double shock_x = 0.0;
  std::string summary() const;
};

// The quasi-1D flow from inlet total conditions (p0, t0) to the outflow static pressure
// p_exit < p0 through the duct the mesh fills between its smallest and largest x (inflow at the
// smallest), evaluated at every node. The throat is the smallest section.
Quasi1dStart quasi_one_dimensional_start(const Mesh& mesh, Geometry geometry, const PerfectGas& gas,
                                         double p0, double t0, double p_exit);

}  // namespace tfmb::flow
