// Mass of the discretised beams: consistent translational mass (int N_i N_j m ds, constant) and
// nodal rotary inertia lumped in each node's material frame (int N_j ds times the section's
// inertia per length). With the reference line through the section's mass centre there is no
// coupling between the two (off-diagonal blocks of the 6x6 sectional mass are zero).
#pragma once

#include <Eigen/Sparse>
#include <vector>

#include "tfmb-beam/model.hpp"

namespace tfmb::beam {

struct MassModel {
  /// Scalar node-to-node translational mass: M_trans = kron(mass_scalar, I3) [kg].
  Eigen::SparseMatrix<double> mass_scalar;
  /// Rotary inertia of each node in its material frame [kg m^2].
  std::vector<Eigen::Matrix3d> nodal_inertia;
};

MassModel build_mass(const Model& model);

}  // namespace tfmb::beam
