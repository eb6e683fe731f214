// Geometrically exact (Simo-Reissner) 3-node beam element in Wiener-Milenkovic form.
//
// Kinematics (FORMULATION.md sec. 2): deformed position x(s) interpolated from the nodes; section
// frame Lambda(s) = Lambda_2 R(r(s)) with r(s) = sum_j N_j(s) r_j, where r_j are the parameters of
// the nodal frames relative to the middle node (r_j = WM(Lambda_2^T Lambda_j)). Interpolating
// relative rotations makes the strain measures objective and path independent (Crisfield &
// Jelenic 1999). Strains: e = Lambda^T x' - e_ref, k = H(r)^T r' - k_ref (material components),
// with e_ref, k_ref the same measures in the reference configuration (stress-free reference, so a
// curved reference beam carries its initial curvature exactly). Two-point Gauss quadrature
// (reduced integration) removes shear locking.
//
// Nodal unknowns for Newton: displacement increments du and spatial rotation increments dtheta
// (WM parameters) with Lambda <- R(dtheta) Lambda. The residual components conjugate to dtheta
// are moments about spatial axes. The tangent is exact: the strains are evaluated with
// second-order forward AD (Hyper<9>, the nine nodal rotation increments), and the change of the
// spin-conjugate forces with the update adds -1/2 S(m) per node (derivative of H^-T at zero).
#pragma once

#include <Eigen/Core>
#include <array>

#include "tfmb-beam/model.hpp"

namespace tfmb::beam {

using Vector18d = Eigen::Matrix<double, 18, 1>;
using Matrix18d = Eigen::Matrix<double, 18, 18>;

constexpr int kGaussPoints = 2;

/// Reference data of one element, computed once.
struct ElementGeometry {
  std::array<double, kGaussPoints> weight_times_jacobian{};  // Gauss weight x ds/dxi [m]
  std::array<double, kGaussPoints> inverse_jacobian{};       // dxi/ds [1/m]
  std::array<Eigen::Vector3d, kGaussPoints> force_strain_ref{};   // Lambda0^T x0' (e1 for exact geometry)
  std::array<Eigen::Vector3d, kGaussPoints> moment_strain_ref{};  // initial curvature and twist
  double length = 0.0;  // reference length [m]
};

ElementGeometry make_element_geometry(const std::array<Eigen::Vector3d, 3>& position,
                                      const std::array<Eigen::Matrix3d, 3>& frame);

/// Current nodal positions and section frames of one element.
struct ElementState {
  std::array<Eigen::Vector3d, 3> position;
  std::array<Eigen::Matrix3d, 3> frame;
};

struct ElementLoads {
  Eigen::Vector3d dead_force_per_length = Eigen::Vector3d::Zero();      // spatial [N/m]
  Eigen::Vector3d follower_force_per_length = Eigen::Vector3d::Zero();  // deformed section frame [N/m]
};

struct ElementResult {
  Vector18d force = Vector18d::Zero();    // internal minus external, per node (force, moment)
  Matrix18d tangent = Matrix18d::Zero();  // d force / d (du, dtheta)
  std::array<Vector6d, kGaussPoints> strain{};  // mechanical strains (total minus initial)
  std::array<Vector6d, kGaussPoints> stress{};  // sectional forces and moments, material frame
  double strain_energy = 0.0;
};

/// Evaluates the element's force vector and, if `with_tangent`, its consistent tangent.
void evaluate_beam_element(const ElementGeometry& geometry, const Section& section,
                           const Vector6d& initial_strain, const ElementState& state,
                           const ElementLoads& loads, bool with_tangent, ElementResult& result);

/// Quadratic Lagrange shape functions on xi in [-1, 1] and their xi-derivatives.
inline std::array<double, 3> shape_quadratic(double xi) {
  return {0.5 * xi * (xi - 1.0), 1.0 - xi * xi, 0.5 * xi * (xi + 1.0)};
}
inline std::array<double, 3> shape_quadratic_derivative(double xi) { return {xi - 0.5, -2.0 * xi, xi + 0.5}; }
inline double gauss_point(int i) { return (i == 0 ? -1.0 : 1.0) / std::sqrt(3.0); }

}  // namespace tfmb::beam
