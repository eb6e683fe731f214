#pragma once
// Writes a planar steady heat-transfer problem as a CalculiX (ccx) input deck, for side-by-side
// comparisons, and reads the nodal temperatures back from ccx's .dat output.
// CalculiX 2.x User's Manual (G. Dhondt): *HEAT TRANSFER, CPS3/CPS4 plane elements, *FILM,
// *RADIATE, *DFLUX, *CONDUCTIVITY, *PHYSICAL CONSTANTS, *NODE PRINT (NT).
#include "tfmb-heat/problem.hpp"

#include <ostream>
#include <string>

namespace tfmb::heat {

/// Linear elements only; no contact, no volumetric source. Trace-valued film data (h, T_aw) and
/// fluxes are constant per face in ccx, so they are sampled at the edge midpoints (a difference
/// of second order in the edge length from tfmb-heat's Gauss-point sampling). Imposed
/// temperatures are nodal in both codes. Throws std::invalid_argument for unsupported input.
void write_calculix_input(std::ostream& out, const ThermalProblem& problem,
                          double initial_temperature);

/// Nodal temperatures [K] from the NT block of a ccx .dat file (last block wins).
Eigen::VectorXd read_calculix_temperatures(const std::string& dat_path, std::size_t node_count);

}  // namespace tfmb::heat
