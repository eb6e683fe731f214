// Flexible joint (bushing) between two handles k and l with finite-deformation measures.
//
// Source: Bauchau & Han, "Flexible joints in structural and multibody dynamics" (the second seed,
// ../shared/seeds/001_0c8aaaec75a1d91c.txt; equation numbers below are the seed's). The relative
// motion of handle l with respect to handle k, resolved in the joint's material frame, is
// parameterised by the Wiener-Milenkovic rotation parameters p and the displacement parameters
// q = H(p)^-1 u (derivation in tools/tfmb-beam/README.md, "Flexible joint"), sigma = p.q:
//
//   proposed measures (eq. 16):  e = mu(sigma, p) q + lambda(sigma, p) p,   kappa = mu(sigma, p) p
//   typical measures  (eq. 34):  e = u (relative displacement in frame k),   kappa = axial(R_rel)
//
// Strain energy A = 1/2 E^T D E, E = (e, kappa), D a constant 6x6 stiffness in the material frame
// (eq. 20). The proposed measures are objective and change sign when k and l are swapped, so the
// energy (and the response) does not depend on which handle is called k; the typical ones are
// not (the stretch is resolved in frame k).
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "tfmb-beam/model.hpp"
#include "tfmb-beam/rotation_wm.hpp"

namespace tfmb::beam {

enum class FlexibleMeasure {
  proposed,  // the seed's tensorial measures, eq. (16)
  typical,   // relative displacement in frame k and axial vector of the relative rotation, eq. (34)
};

/// One term coefficient * sigma^sigma_power * |p|^p_power of a measure function. p_power must be
/// even: odd powers of |p| are not differentiable at zero relative rotation (the seed's appendix B
/// needs lambda_p/p and mu_p/p regular at p = 0).
struct MeasureTerm {
  double coefficient = 0.0;
  int sigma_power = 0;
  int p_power = 0;
};

/// lambda(sigma, p) or mu(sigma, p): a polynomial in sigma and p, multiplied by
/// (1 - p^2/16)/(1 + p^2/16) when `wm_cosine_factor` is set. With |p| = 4 tan(phi/4) that factor
/// is cos(phi/2); the seed's default mu is that factor alone.
struct MeasureFunction {
  std::vector<MeasureTerm> terms;
  bool wm_cosine_factor = false;

  template <typename T>
  T operator()(const T& sigma, const T& p_squared) const {
    T value(0.0);
    for (const MeasureTerm& t : terms) {
      T term(t.coefficient);
      for (int i = 0; i < t.sigma_power; ++i) term = term * sigma;
      for (int i = 0; i < t.p_power / 2; ++i) term = term * p_squared;
      value = value + term;
    }
    if (wm_cosine_factor) value = value * (1.0 - p_squared / 16.0) / (1.0 + p_squared / 16.0);
    return value;
  }
  /// Value for small motion (sigma = p = 0).
  double small_motion_limit() const;
  /// Readable formula, e.g. "1 + p^2" or "(1 - p^2/16)/(1 + p^2/16)".
  std::string formula() const;
};

struct MeasureFunctions {
  std::string name;  // "default", "1a" ... "4d", or "custom"
  MeasureFunction lambda;
  MeasureFunction mu;
};

/// The seed's choices by name: "default" (lambda = 0, mu = (1 - p^2/16)/(1 + p^2/16), used in its
/// example 1) and the sixteen cases "1a" ... "4d" of its example 2 (Table 1; our reading of the
/// OCR text, see README.md). Throws std::invalid_argument for an unknown name.
MeasureFunctions seed_measure_functions(const std::string& name);
/// Names accepted by seed_measure_functions, in order.
std::vector<std::string> seed_measure_function_names();

/// Throws std::invalid_argument (message names the function, its formula and the violated limit)
/// unless mu -> 1 and lambda -> 0 for small motion (seed eqs. 18 and 19) and every power of |p| is
/// even.
void check_measure_functions(const MeasureFunctions& functions);

struct FlexibleJointLaw {
  Matrix6d stiffness = Matrix6d::Identity();  // D [N/m, N, N m/rad] in the joint's material frame
  FlexibleMeasure measure = FlexibleMeasure::proposed;
  MeasureFunctions functions = seed_measure_functions("default");
  /// Joint axes in the reference configuration (columns, spatial components): the material frame
  /// in which D is given. Both handles carry this frame; it moves with each handle's rotation.
  Eigen::Matrix3d frame = Eigen::Matrix3d::Identity();
};

/// Deformation measures E = (e, kappa) from the relative displacement u and the relative rotation
/// parameters p (material components; Wiener-Milenkovic, |p| <= 4).
template <typename T>
Eigen::Matrix<T, 6, 1> flexible_joint_measures(const FlexibleJointLaw& law, const Vec3<T>& u, const Vec3<T>& p) {
  Eigen::Matrix<T, 6, 1> e;
  if (law.measure == FlexibleMeasure::typical) {
    // axial(R(p)) = sin(phi) n = 2 c0 p/(4 - c0)^2 (skew part of R(p), FORMULATION.md sec. 1).
    const T c0 = wm_c0(p);
    const T f = 2.0 * c0 / ((4.0 - c0) * (4.0 - c0));
    for (int i = 0; i < 3; ++i) {
      e(i) = u(i);
      e(3 + i) = f * p(i);
    }
    return e;
  }
  const Vec3<T> q = wm_tangent_inverse(p) * u;  // q = H(p)^-1 u (README: eigenvector of C)
  const T sigma = p.dot(q);
  const T p_squared = p.dot(p);
  const T lambda = law.functions.lambda(sigma, p_squared);
  const T mu = law.functions.mu(sigma, p_squared);
  for (int i = 0; i < 3; ++i) {
    e(i) = mu * q(i) + lambda * p(i);
    e(3 + i) = mu * p(i);
  }
  return e;
}

/// Position and rotation (Wiener-Milenkovic parameters from the reference configuration) of a handle.
struct HandleState {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  // [m]
  Eigen::Vector3d rotation = Eigen::Vector3d::Zero();  // frame = R(rotation) * reference frame
};

struct FlexibleJointResponse {
  double energy = 0.0;                       // A = 1/2 E^T D E [J]
  Vector6d measures = Vector6d::Zero();      // E = (stretch e, wryness kappa), material frame
  Eigen::Vector3d relative_displacement = Eigen::Vector3d::Zero();  // u, material frame [m]
  Eigen::Vector3d relative_rotation = Eigen::Vector3d::Zero();      // p, Wiener-Milenkovic
  /// dA/d(du_k, dpsi_k, du_l, dpsi_l) with spatial displacement and rotation increments: the
  /// joint's internal forces (the forces the joint applies to the handles are minus these).
  Eigen::Matrix<double, 12, 1> force = Eigen::Matrix<double, 12, 1>::Zero();
  /// Consistent tangent: derivative of `force` when the handles are updated as x <- x + du,
  /// R <- R(dpsi) R. Not symmetric away from equilibrium (spatial rotation increments).
  Eigen::Matrix<double, 12, 12> tangent = Eigen::Matrix<double, 12, 12>::Zero();
};

/// Evaluates the joint between handles k and l whose reference positions coincide (the seed's
/// configuration: points K and L both at B in the reference configuration).
FlexibleJointResponse evaluate_flexible_joint(const FlexibleJointLaw& law, const HandleState& k, const HandleState& l);

}  // namespace tfmb::beam
