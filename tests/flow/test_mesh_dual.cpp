#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "mesh_generate.hpp"
#include "test_meshes.hpp"
#include "tfmb-flow/mesh.hpp"
#include "tfmb-flow/mesh_dual.hpp"

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

TEST(MeshDual, EdgesRunInNodeOrderAndKeepTheirNormals) {
  // cells listed triangles first, then quads: the edges must still come in node order
  const Mesh mesh = test_meshes::distorted_mixed_mesh();
  const DualMesh dual = build_dual(mesh, Geometry::planar);
  ASSERT_GT(dual.num_edges(), 100);
  for (int e = 0; e < dual.num_edges(); ++e) {
    const auto [i, j] = dual.edges[e];
    EXPECT_LT(i, j);
    if (e > 0) {
      EXPECT_LT(dual.edges[e - 1], dual.edges[e]) << "edge " << e;
    }
    // each normal travelled with its edge: it points from the first node to the second
    const Vec2 along = dual.coords[j] - dual.coords[i];
    EXPECT_GT(dual.edge_normal[e].x * along.x + dual.edge_normal[e].y * along.y, 0.0)
        << "edge " << e;
    EXPECT_GT(dual.edge_normal_planar[e].x * along.x + dual.edge_normal_planar[e].y * along.y, 0.0)
        << "edge " << e;
  }
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

namespace {
// A boundary-layer strip: 0.05 m cells along x, wall-normal spacing from 1e-4 m growing by 1.3
// per layer from the bottom wall, every third cell split into triangles.
Mesh boundary_layer_strip(int ni, int nj) {
  StructuredMeshSpec spec;
  spec.ni = ni;
  spec.nj = nj;
  std::vector<double> y{0.0};
  for (int j = 1; j < nj; ++j)
    y.push_back(y.back() + 1e-4 * std::pow(1.3, j - 1));
  spec.map = [=](double xi, double eta) {
    const double j = eta * (nj - 1);
    const int j0 = std::min(static_cast<int>(j), nj - 2);
    return Vec2{xi * 0.05 * (ni - 1), y[j0] + (j - j0) * (y[j0 + 1] - y[j0])};
  };
  spec.split = [](int i, int j) { return (i + j) % 3 == 0; };
  return structured_mesh(spec);
}
}  // namespace

TEST(NodeOrdering, LinesFollowTheWallNormalColumnsOfStretchedCells) {
  const int ni = 21, nj = 25;
  const Mesh mesh = boundary_layer_strip(ni, nj);
  const auto lines = strong_coupling_lines(mesh);
  // Every line runs up one column, one layer at a time; the column's cells are flatter than
  // 1:4 while 1e-4 * 1.3^j < 0.05 / 4, i.e. up to layer 18, so each column holds a line from
  // the wall through at least layer 18 and none reaches the isotropic top.
  std::vector<int> lined_columns(ni, 0);
  for (const auto& line : lines) {
    ASSERT_GE(line.size(), 2u);
    const double x = mesh.points[line.front()].x;
    const bool upward = mesh.points[line.back()].y > mesh.points[line.front()].y;
    for (std::size_t k = 1; k < line.size(); ++k) {
      EXPECT_NEAR(mesh.points[line[k]].x, x, 1e-12);
      EXPECT_EQ(mesh.points[line[k]].y > mesh.points[line[k - 1]].y, upward);
    }
    double bottom = 1e9, top = 0.0;
    for (int node : line) {
      bottom = std::min(bottom, mesh.points[node].y);
      top = std::max(top, mesh.points[node].y);
    }
    EXPECT_EQ(bottom, 0.0);
    EXPECT_GE(top, 1e-4 * (std::pow(1.3, 18) - 1.0) / 0.3 - 1e-12);
    EXPECT_LT(top, 1e-4 * (std::pow(1.3, nj - 1) - 1.0) / 0.3);
    ++lined_columns[static_cast<int>(std::lround(x / 0.05))];
  }
  for (int i = 0; i < ni; ++i)
    EXPECT_EQ(lined_columns[i], 1) << "column " << i;

  // The ordering is a permutation that keeps each line contiguous and in its own order.
  const std::vector<int> order = line_ordering(rcm_ordering(mesh), lines);
  std::vector<int> seen(order.size(), 0);
  for (int id : order) {
    ASSERT_GE(id, 0);
    ASSERT_LT(id, static_cast<int>(order.size()));
    ++seen[id];
  }
  EXPECT_EQ(std::count(seen.begin(), seen.end(), 1), static_cast<long>(order.size()));
  for (const auto& line : lines) {
    const int step = order[line[1]] - order[line[0]];
    EXPECT_EQ(std::abs(step), 1);
    for (std::size_t k = 1; k < line.size(); ++k)
      EXPECT_EQ(order[line[k]] - order[line[k - 1]], step);
  }
}

TEST(NodeOrdering, IsotropicCellsMakeNoLines) {
  // cells of about 0.125 x 0.1 m, jittered by up to 10 %, diagonals at most 1.6 times an edge
  const Mesh mesh = test_meshes::distorted_mixed_mesh(17, 11, 0.1);
  EXPECT_TRUE(strong_coupling_lines(mesh).empty());
  const std::vector<int> rcm = rcm_ordering(mesh);
  EXPECT_EQ(line_ordering(rcm, {}), rcm);
}
