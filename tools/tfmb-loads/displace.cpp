#include "displace.hpp"

#include <cmath>
#include <Eigen/Geometry>

namespace tfmb::loads {

double wiener_milenkovic_angle(double c_z) { return 4.0 * std::atan(c_z / 4.0); }

std::vector<Vec2> wall_displacement(const BeamLine& beam, const BeamMotion& motion,
                                    const std::vector<Vec2>& wall_points) {
  std::vector<Vec2> out;
  out.reserve(wall_points.size());
  for (const Vec2& x : wall_points) {
    const BeamProjection b = beam.project(x);
    const std::size_t j = b.element;
    const Vec2 u = (1.0 - b.xi) * motion.displacement[j] + b.xi * motion.displacement[j + 1];
    const double phi = (1.0 - b.xi) * motion.rotation[j] + b.xi * motion.rotation[j + 1];
    const Eigen::Matrix2d rotation = Eigen::Rotation2Dd(phi).toRotationMatrix();
    out.push_back(u + (rotation - Eigen::Matrix2d::Identity()) * (x - b.point));
  }
  return out;
}

}  // namespace tfmb::loads
