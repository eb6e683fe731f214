#include <gtest/gtest.h>

#include "tfmb-flow/mesh_dual.hpp"
#include "test_meshes.hpp"

using namespace tfmb::flow;

namespace {
double polygon_area(const Mesh& m) {
  // the mapped region's area by summing the cells (shoelace per cell, orientation-free)
  double total = 0.0;
  auto add = [&](const int* ids, int nv) {
    double a = 0.0;
    for (int k = 0; k < nv; ++k) {
      const Vec2 p = m.points[ids[k]], q = m.points[ids[(k + 1) % nv]];
      a += p.x * q.y - q.x * p.y;
    }
    total += 0.5 * std::abs(a);
  };
  for (const auto& t : m.triangles) add(t.data(), 3);
  for (const auto& q : m.quads) add(q.data(), 4);
  return total;
}
}  // namespace

TEST(MeshDual, ClosureAndVolumesOnDistortedMixedMesh) {
  const Mesh mesh = test_meshes::distorted_mixed_mesh();
  ASSERT_GT(mesh.triangles.size(), 50u);
  ASSERT_GT(mesh.quads.size(), 50u);
  check_mesh(mesh);
  const DualMesh dual = build_dual(mesh, Geometry::planar);
  double scale = 0.0;
  for (const auto& n : dual.edge_normal) scale = std::max(scale, norm(n));
  for (const Vec2& s : dual_closure(dual)) {
    EXPECT_NEAR(s.x, 0.0, 1e-14 * scale);
    EXPECT_NEAR(s.y, 0.0, 1e-14 * scale);
  }
  double total = 0.0;
  for (double v : dual.volume) {
    EXPECT_GT(v, 0.0);
    total += v;
  }
  EXPECT_NEAR(total, polygon_area(mesh), 1e-13 * total);
  EXPECT_EQ(dual.boundary_faces.size(), 2 * (2 * 16 + 2 * 10u));
}

TEST(MeshDual, AxisymmetricClosureIsPlanarAreaTimesRadialUnitVector) {
  const Mesh mesh = test_meshes::distorted_mixed_mesh();
  const DualMesh dual = build_dual(mesh, Geometry::axisymmetric);
  const auto closure = dual_closure(dual);
  double first_moment = 0.0;
  for (int i = 0; i < dual.num_nodes; ++i) {
    EXPECT_NEAR(closure[i].x, 0.0, 1e-14);
    EXPECT_NEAR(closure[i].y, dual.area[i], 1e-14);
    first_moment += dual.volume[i];
  }
  // integral of y dA over the region, computed cell by cell with the triangle centroid rule
  double expected = 0.0;
  auto tri = [&](Vec2 a, Vec2 b, Vec2 c) {
    const double area = 0.5 * std::abs((b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y));
    expected += area * (a.y + b.y + c.y) / 3.0;
  };
  for (const auto& t : mesh.triangles) tri(mesh.points[t[0]], mesh.points[t[1]], mesh.points[t[2]]);
  for (const auto& q : mesh.quads) {
    tri(mesh.points[q[0]], mesh.points[q[1]], mesh.points[q[2]]);
    tri(mesh.points[q[0]], mesh.points[q[2]], mesh.points[q[3]]);
  }
  EXPECT_NEAR(first_moment, expected, 1e-13 * expected);
}

TEST(MeshDual, UntaggedBoundaryIsRejected) {
  Mesh mesh = test_meshes::distorted_mixed_mesh(5, 4, 0.0);
  mesh.boundaries.pop_back();
  EXPECT_THROW(check_mesh(mesh), std::invalid_argument);
}
