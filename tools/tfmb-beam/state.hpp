// Solution state of a model: nodal positions and rotations, joint unknowns, multipliers.
#pragma once

#include <Eigen/Core>
#include <vector>

namespace tfmb::beam {

struct State {
  std::vector<Eigen::Vector3d> position;   // current nodal positions [m]
  /// Wiener-Milenkovic parameters of the nodal rotation from the reference frame:
  /// frame = R(rotation) * reference frame; kept with |c| <= 4 (rescaled past 180 degrees).
  std::vector<Eigen::Vector3d> rotation;
  Eigen::VectorXd joint_dofs;    // extra joint unknowns, e.g. revolute relative angles [rad]
  Eigen::VectorXd multipliers;   // scaled Lagrange multipliers (actual = scale * value)
};

}  // namespace tfmb::beam
