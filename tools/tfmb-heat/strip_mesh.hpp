#pragma once
// Structured strip meshes [0, length] x [0, thickness] for tests and the benchmark.
#include "tfmb-heat/mesh.hpp"

#include <functional>

namespace tfmb::heat {

struct StripMeshOptions {
  double length = 1.0;     // [m] along x
  double thickness = 0.01; // [m] along y
  int cells_along = 10;
  int cells_through = 2;
  ElementType type = ElementType::quad4;  // quads, or triangles (each quad split in two)
  /// Optional map applied to every node after generation (distortion); must keep the boundary
  /// on its straight sides for the tagged edges to stay meaningful.
  std::function<void(double&, double&)> map;
  /// Cells with centre x < this value are split into triangles (mixed meshes); quad types only.
  double triangles_below_x = -1e300;
};

/// Boundaries "bottom" (y = 0, increasing x), "right" (x = length, increasing y),
/// "top" (y = thickness, increasing x), "left" (x = 0, increasing y). Material 0 everywhere.
SolidMesh make_strip_mesh(const StripMeshOptions& options);

}  // namespace tfmb::heat
