// The flexible-joint seed's two examples as library calls (used by the verification tests and by
// tfmb-beam-flexible-joint-seed, which writes the case's CSV files).
#pragma once

#include <string>
#include <vector>

#include "tfmb-beam/flexible_joint.hpp"

namespace tfmb::beam::seed {

struct JointPoint {
  Eigen::Vector3d tip_displacement = Eigen::Vector3d::Zero();  // [m], example 1: tip of beam 2
  Vector6d measures = Vector6d::Zero();                        // (stretch, wryness) as the joint computes them
};

struct Example1Result {
  std::vector<double> a;        // load factors reached (the seed's a, 0 .. 9)
  std::vector<JointPoint> kl;   // handle k = end of beam 1 (the seed's solid lines)
  std::vector<JointPoint> lk;   // handles swapped (dashed lines)
  /// Largest difference between the two orders over all load levels: nodal positions relative to
  /// the largest nodal displacement; nodal rotation tensors (Frobenius) relative to the largest
  /// nodal rotation angle; joint measures |E_kl + E_lk| relative to the largest |E_kl|.
  double max_position_difference = 0.0;
  double max_rotation_difference = 0.0;
  double max_measure_difference = 0.0;
};

/// Example 1 with load levels `a_levels` (increasing, in (0, 9]), Newton converged to ~1e-12.
Example1Result run_example1(FlexibleMeasure measure, const std::vector<double>& a_levels, int elements_per_beam = 8);

struct Example2Result {
  std::vector<double> a;
  std::vector<Vector6d> measures;
};

/// Example 2 for one lambda/mu choice ("1a" ... "4d"); the joint's rotational stiffness diagonal
/// as printed in the seed (1000, 1000, 100) unless given.
Example2Result run_example2(const std::string& functions, const std::vector<double>& a_levels,
                            const Eigen::Vector3d& rotational_stiffness = Eigen::Vector3d(1000, 1000, 100));

/// Example 2 at load level a for the sixteen cases: max over cases of |E_case - E_1a| / |E_1a|.
double example2_spread(double a, const Eigen::Vector3d& rotational_stiffness = Eigen::Vector3d(1000, 1000, 100));

}  // namespace tfmb::beam::seed
