// Beam displacement and rotation -> displacement of wall points (the reverse mapping for
// two-way coupling).
//
// A wall point x projects to the beam point x_b (BeamLine::project) in element j at xi; the
// beam displacement u and rotation angle phi are interpolated linearly there, and the wall
// point follows the section rigidly (plane sections stay plane, the thickness offset rotates):
//   d = u_b + (R(phi_b) - I)(x - x_b)
// (Hodges, Nonlinear Composite Beam Theory, 2006, eq. 4.1 with zero warping). A rigid motion
// u(r) = c + (R - I)(r - o) is reproduced exactly: u is linear in r, so u_b is exact, and the
// offset term completes it to c + (R - I)(x - o).
#pragma once

#include <vector>

#include "beam_line.hpp"

namespace tfmb::loads {

// Planar rotation angle [rad] about z from Wiener-Milenkovic parameters c = 4 tan(phi/4) e
// (Bauchau, Flexible Multibody Dynamics, 2011, sec. 13.6).
double wiener_milenkovic_angle(double c_z);

struct BeamMotion {
  std::vector<Vec2> displacement;  // per node [m]
  std::vector<double> rotation;    // per node, angle about z [rad]
};

std::vector<Vec2> wall_displacement(const BeamLine& beam, const BeamMotion& motion,
                                    const std::vector<Vec2>& wall_points);

}  // namespace tfmb::loads
