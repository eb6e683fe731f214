// Wiener-Milenkovic (conformal rotation vector) parameters.
//
// Convention (FORMULATION.md sec. 1): c = 4 tan(phi/4) n, c0 = 2 - c.c/8, and R(c) maps material
// components to spatial ones. |c| <= 4 covers |phi| <= pi; the composition below always returns
// the member of the pair {c, shadow(c)} with |c| <= 4, which is how rotations past 360 degrees are
// carried (rescaling). The functions are templated on the scalar so that the beam element and the
// joints can evaluate them with Hyper<N> to get exact derivatives.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>

#include "tfmb-beam/hyper_dual.hpp"

namespace tfmb::beam {

template <typename T>
using Vec3 = Eigen::Matrix<T, 3, 1>;
template <typename T>
using Mat3 = Eigen::Matrix<T, 3, 3>;

/// S(a) with S(a) b = a x b.
template <typename T>
Mat3<T> skew(const Vec3<T>& a) {
  Mat3<T> s;
  s << T(0.0), -a(2), a(1), a(2), T(0.0), -a(0), -a(1), a(0), T(0.0);
  return s;
}

/// axial(S) for a (nearly) skew matrix: the vector part of (S - S^T)/2.
inline Eigen::Vector3d axial(const Eigen::Matrix3d& s) {
  return 0.5 * Eigen::Vector3d(s(2, 1) - s(1, 2), s(0, 2) - s(2, 0), s(1, 0) - s(0, 1));
}

template <typename T>
T wm_c0(const Vec3<T>& c) {
  return 2.0 - c.dot(c) / 8.0;
}

/// Rotation tensor R(c) = I + 2 (c0 S(c) + S(c)^2) / (4 - c0)^2  (Bauchau 2011, eq. for the
/// Wiener-Milenkovic parameters; FORMULATION.md sec. 1).
template <typename T>
Mat3<T> wm_rotation(const Vec3<T>& c) {
  // Expanded with S(c)^2 = c c^T - (c.c) I to keep the operation count low (this is evaluated
  // with Hyper numbers in the element).
  const T cc = c(0) * c(0) + c(1) * c(1) + c(2) * c(2);
  const T c0 = 2.0 - cc / 8.0;
  const T d = 4.0 - c0;
  const T f = 2.0 / (d * d);
  const T fc0 = f * c0;
  Mat3<T> r;
  for (int i = 0; i < 3; ++i) {
    r(i, i) = 1.0 + f * (c(i) * c(i) - cc);
    for (int j = i + 1; j < 3; ++j) {
      const T sym = f * (c(i) * c(j));
      const int k = 3 - i - j;
      // S(c)_ij = -eps_ijk c_k
      const T skw = fc0 * c(k) * (((j - i + 3) % 3 == 1) ? -1.0 : 1.0);
      r(i, j) = sym + skw;
      r(j, i) = sym - skw;
    }
  }
  return r;
}

/// Tangent tensor H(c): spatial virtual rotation delta psi = H(c) delta c (FORMULATION.md sec. 1).
template <typename T>
Mat3<T> wm_tangent(const Vec3<T>& c) {
  const T c0 = wm_c0(c);
  const T d = 4.0 - c0;
  Mat3<T> h = skew(c) + c * c.transpose() / 4.0;
  for (int i = 0; i < 3; ++i) h(i, i) += c0;
  return h * (2.0 / (d * d));
}

/// H(c)^T v = 2 (c0 v - c x v + c (c.v)/4) / (4 - c0)^2, without forming H (material curvature
/// k = H(r)^T r' in the element).
template <typename T>
Vec3<T> wm_tangent_transpose_times(const Vec3<T>& c, const Vec3<T>& v) {
  const T c0 = wm_c0(c);
  const T d = 4.0 - c0;
  const T f = 2.0 / (d * d);
  const T cv = (c(0) * v(0) + c(1) * v(1) + c(2) * v(2)) * 0.25;
  Vec3<T> r;
  r(0) = f * (c0 * v(0) - (c(1) * v(2) - c(2) * v(1)) + c(0) * cv);
  r(1) = f * (c0 * v(1) - (c(2) * v(0) - c(0) * v(2)) + c(1) * cv);
  r(2) = f * (c0 * v(2) - (c(0) * v(1) - c(1) * v(0)) + c(2) * cv);
  return r;
}

/// H(c)^-1 = (c0 I - S(c) + c c^T/4) / 2, a polynomial (FORMULATION.md sec. 1).
template <typename T>
Mat3<T> wm_tangent_inverse(const Vec3<T>& c) {
  const T c0 = wm_c0(c);
  Mat3<T> h = -skew(c) + c * c.transpose() / 4.0;
  for (int i = 0; i < 3; ++i) h(i, i) += c0;
  return h * 0.5;
}

/// Parameters of R(b) R(a) (first a, then b), choosing the representative with |c| <= 4
/// (Bauchau & Trainelli 2003; FORMULATION.md sec. 1, "Composition").
template <typename T>
Vec3<T> wm_compose(const Vec3<T>& a, const Vec3<T>& b) {
  const T a0 = wm_c0(a);
  const T b0 = wm_c0(b);
  const T d1 = (4.0 - a0) * (4.0 - b0);
  const T d2 = a0 * b0 - a.dot(b);
  const Vec3<T> num = (a * b0 + b * a0 + b.cross(a)) * 4.0;
  if (value_of(d2) >= 0.0) return num / (d1 + d2);
  return -num / (d1 - d2);
}

/// Parameters of the inverse rotation.
template <typename T>
Vec3<T> wm_inverse(const Vec3<T>& c) {
  return -c;
}

/// Replace c by its shadow -16 c/|c|^2 when |c| > 4: same rotation, |c| <= 4 (the other
/// stereographic projection of the quaternion; FORMULATION.md sec. 1). The unit test checks the
/// rotation is unchanged.
Eigen::Vector3d wm_rescale(const Eigen::Vector3d& c);

/// Parameters (|c| <= 4) of a rotation tensor, through the unit quaternion: c = 4 qv/(1 + q0), q0 >= 0.
Eigen::Vector3d wm_from_rotation(const Eigen::Matrix3d& r);

/// Parameters of a rotation by angle phi about the unit axis n (any phi; rescaled to |c| <= 4).
Eigen::Vector3d wm_from_axis_angle(const Eigen::Vector3d& axis, double angle);

/// Rotation angle in [0, pi] of the rotation with parameters c.
double wm_angle(const Eigen::Vector3d& c);

/// d(H(c) a)/dc for a fixed vector a (FORMULATION.md sec. 1), needed for gyroscopic linearisation.
Eigen::Matrix3d wm_tangent_times_vector_derivative(const Eigen::Vector3d& c, const Eigen::Vector3d& a);

}  // namespace tfmb::beam
