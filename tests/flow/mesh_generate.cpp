#include "mesh_generate.hpp"

#include <random>

namespace tfmb::flow {

Mesh structured_mesh(const StructuredMeshSpec& s) {
  Mesh mesh;
  auto id = [&](int i, int j) { return j * s.ni + i; };
  mesh.points.resize(static_cast<std::size_t>(s.ni) * s.nj);
  std::mt19937 rng(s.seed);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  const double dxi = 1.0 / (s.ni - 1);
  const double deta = 1.0 / (s.nj - 1);
  for (int j = 0; j < s.nj; ++j) {
    for (int i = 0; i < s.ni; ++i) {
      double xi = i * dxi;
      double eta = j * deta;
      if (s.jitter > 0.0 && i > 0 && j > 0 && i < s.ni - 1 && j < s.nj - 1) {
        xi += s.jitter * dxi * uniform(rng);
        eta += s.jitter * deta * uniform(rng);
      }
      mesh.points[id(i, j)] = s.map(xi, eta);
    }
  }
  for (int j = 0; j + 1 < s.nj; ++j) {
    for (int i = 0; i + 1 < s.ni; ++i) {
      const int a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
      if (s.split(i, j)) {
        // alternate the diagonal so the triangles carry no directional bias
        if ((i + j) % 2 == 0) {
          mesh.triangles.push_back({a, b, c});
          mesh.triangles.push_back({a, c, d});
        } else {
          mesh.triangles.push_back({a, b, d});
          mesh.triangles.push_back({b, c, d});
        }
      } else {
        mesh.quads.push_back({a, b, c, d});
      }
    }
  }
  BoundaryCurve bottom{s.bottom, {}}, right{s.right, {}}, top{s.top, {}}, left{s.left, {}};
  for (int i = 0; i + 1 < s.ni; ++i) {
    bottom.edges.push_back({id(i, 0), id(i + 1, 0)});
    top.edges.push_back({id(i, s.nj - 1), id(i + 1, s.nj - 1)});
  }
  for (int j = 0; j + 1 < s.nj; ++j) {
    left.edges.push_back({id(0, j), id(0, j + 1)});
    right.edges.push_back({id(s.ni - 1, j), id(s.ni - 1, j + 1)});
  }
  mesh.boundaries = {bottom, right, top, left};
  return mesh;
}

}  // namespace tfmb::flow
