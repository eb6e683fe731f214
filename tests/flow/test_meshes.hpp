// Small meshes shared by the flow tests.
#pragma once

#include <cmath>

#include "mesh_generate.hpp"

namespace tfmb::flow::test_meshes {

// A sheared, curved, randomly jittered mixed mesh of a 2 x 1 region (about 40 % triangles).
inline Mesh distorted_mixed_mesh(int ni = 17, int nj = 11, double jitter = 0.3) {
  StructuredMeshSpec spec;
  spec.ni = ni;
  spec.nj = nj;
  spec.map = [](double xi, double eta) {
    return Vec2{2.0 * xi + 0.2 * eta + 0.05 * std::sin(3.0 * eta), 0.1 + eta + 0.1 * std::sin(3.1 * xi)};
  };
  spec.split = [](int i, int j) { return (i * 7 + j * 3) % 5 < 2; };
  spec.jitter = jitter;
  return structured_mesh(spec);
}

}  // namespace tfmb::flow::test_meshes
