// Mesh generators for tests and benchmarks: logically structured grids mapped to a physical
// region, with a chosen share of quads split into triangles so that every code path of the
// mixed-mesh solver is exercised. Not a replacement for tfmb-mesh.
#pragma once

#include <functional>
#include <string>

#include "tfmb-flow/mesh.hpp"

namespace tfmb::flow {

struct StructuredMeshSpec {
  int ni = 11;  // nodes along xi
  int nj = 11;  // nodes along eta
  // (xi, eta) in [0,1]^2 -> physical point [m]
  std::function<Vec2(double, double)> map = [](double xi, double eta) { return Vec2{xi, eta}; };
  // Split cell (i, j) into two triangles when this returns true.
  std::function<bool(int, int)> split = [](int, int) { return false; };
  // Move interior nodes by up to this fraction of the local spacing, pseudo-randomly (fixed seed).
  double jitter = 0.0;
  unsigned seed = 12345;
  // Names of the four sides: eta = 0, xi = 1, eta = 1, xi = 0. Each side is ordered along
  // increasing xi (bottom, top) or increasing eta (left, right).
  std::string bottom = "bottom", right = "right", top = "top", left = "left";
};

Mesh structured_mesh(const StructuredMeshSpec& spec);

}  // namespace tfmb::flow
