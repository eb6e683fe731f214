#pragma once
// Per beam element temperatures from the solid temperature field, for tfmb-matmap (mean T) and
// tfmb-beam (thermal curvature from the through-thickness difference).
//
// For the solid cells mapped to one beam element, with z the through-thickness coordinate
// (distance from the beam reference line, positive towards the outer surface):
//   A = int dA, T_mean = int T dA / A, z_c = int z dA / A
//   linear fit T ~ T_mean + g (z - z_c):  g = int T (z - z_c) dA / int (z - z_c)^2 dA
//   thickness t = max z - min z over the cells' nodes, dT = g t
// For a rectangular section centred on the reference line (z_c = 0, int z^2 dA = A t^2 / 12)
// this is dT = 12 int T z dA / (t^2 A) * t, the first-moment formula.
#include "tfmb-heat/mesh.hpp"

#include <Eigen/Dense>

#include <cstdint>
#include <vector>

namespace tfmb::heat {

struct BeamThermalOutputs {
  std::vector<double> area;                    // [m^2] solid area per beam element
  std::vector<double> mean_temperature;        // [K], area-weighted
  std::vector<double> temperature_gradient;    // g [K/m] through the thickness (towards +z)
  std::vector<double> thickness;               // t [m]
  std::vector<double> temperature_difference;  // dT = g t [K], outer minus inner
  std::vector<double> z_centroid;              // z_c [m]
};

/// cell_to_beam: per global cell the beam element id (or -1 for cells outside every beam);
/// node_z: per node z [m]. Throws std::invalid_argument for size mismatches, ids out of
/// range or a beam element without cells.
BeamThermalOutputs beam_element_temperatures(const SolidMesh& mesh,
                                             const Eigen::VectorXd& node_temperature,
                                             const std::vector<std::int64_t>& cell_to_beam,
                                             const Eigen::VectorXd& node_z,
                                             std::size_t beam_element_count);

}  // namespace tfmb::heat
