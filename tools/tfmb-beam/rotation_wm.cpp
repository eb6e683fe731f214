#include "tfmb-beam/rotation_wm.hpp"

namespace tfmb::beam {

Eigen::Vector3d wm_rescale(const Eigen::Vector3d& c) {
  // The two parameter vectors of one rotation come from q and -q: c = 4 qv/(1 + q0) and
  // c' = -4 qv/(1 - q0), so |c| |c'| = 16 and c' = -16 c / |c|^2.
  const double n2 = c.squaredNorm();
  if (n2 <= 16.0) return c;
  return -16.0 * c / n2;
}

Eigen::Vector3d wm_from_rotation(const Eigen::Matrix3d& r) {
  Eigen::Quaterniond q(r);
  q.normalize();
  double q0 = q.w();
  Eigen::Vector3d qv = q.vec();
  if (q0 < 0.0) {  // -q is the same rotation; q0 >= 0 gives |c| <= 4
    q0 = -q0;
    qv = -qv;
  }
  // Stereographic projection of the unit quaternion (FORMULATION.md sec. 1).
  return 4.0 * qv / (1.0 + q0);
}

Eigen::Vector3d wm_from_axis_angle(const Eigen::Vector3d& axis, double angle) {
  const double two_pi = 2.0 * M_PI;
  double phi = std::fmod(angle, two_pi);
  if (phi > M_PI) phi -= two_pi;
  if (phi < -M_PI) phi += two_pi;
  return 4.0 * std::tan(phi / 4.0) * axis.normalized();
}

double wm_angle(const Eigen::Vector3d& c) { return 4.0 * std::atan(c.norm() / 4.0); }

Eigen::Matrix3d wm_tangent_times_vector_derivative(const Eigen::Vector3d& c, const Eigen::Vector3d& a) {
  const double c0 = wm_c0(c);
  const double d = 4.0 - c0;
  const double f = 2.0 / (d * d);
  const Eigen::Matrix3d id = Eigen::Matrix3d::Identity();
  const Eigen::Matrix3d term1 =
      f * (-a * c.transpose() / 4.0 - skew(a) + (c * a.transpose() + c.dot(a) * id) / 4.0);
  const Eigen::Vector3d w = c0 * a + c.cross(a) + c * c.dot(a) / 4.0;
  return term1 - (w * c.transpose()) / (d * d * d);
}

}  // namespace tfmb::beam
