// Gradients of a linear field on a distorted mixed mesh: the weighted least-squares fit is exact
// for it, at interior and boundary nodes. (A median-dual Green-Gauss sum with edge-average face
// values is not, on distorted quads: 14 % off on this mesh.)
#include <gtest/gtest.h>

#include <cmath>

#include "tfmb-flow/gradient_lsq.hpp"
#include "tfmb-flow/mesh_dual.hpp"
#include "mesh_generate.hpp"
#include "test_meshes.hpp"

using namespace tfmb::flow;

namespace {
std::vector<State> linear_field(const DualMesh& dual) {
  std::vector<State> q(dual.num_nodes);
  for (int i = 0; i < dual.num_nodes; ++i) {
    const Vec2 x = dual.coords[i];
    q[i] = {1.0 + 2.0 * x.x - 3.0 * x.y, -0.5 * x.x, 4.0 * x.y, 7.0 + x.x + x.y};
  }
  return q;
}
constexpr double kExact[8] = {2.0, -3.0, -0.5, 0.0, 0.0, 4.0, 1.0, 1.0};

void expect_exact(const std::vector<std::array<double, 8>>& grad, double tol) {
  for (const auto& g : grad) {
    for (int k = 0; k < 8; ++k)
      ASSERT_NEAR(g[k], kExact[k], tol) << "component " << k;
  }
}
}  // namespace

TEST(Gradient, LeastSquaresIsExactForLinearFields) {
  const DualMesh dual = build_dual(test_meshes::distorted_mixed_mesh(), Geometry::planar);
  std::vector<std::array<double, 8>> grad;
  lsq_gradients(dual, build_lsq_gradient(dual), linear_field(dual), grad);
  expect_exact(grad, 1e-11);
}

namespace {
// Quarter-annulus wall layer around the inner wall r = 1 (curvature radius 1): 21 nodes along
// the wall (4.5 degrees apart, 0.079 along the wall), 12 layers, first cell 1e-5 growing by 1.5:
// the along-wall neighbours lie Delta s^2 / 2R = 3e-3 off the tangent, hundreds of first cells.
Mesh curved_wall_layer(double curvature) {
  StructuredMeshSpec spec;
  spec.ni = 21;
  spec.nj = 12;
  spec.bottom = "wall";
  spec.map = [curvature](double xi, double eta) {
    const int layer = static_cast<int>(std::lround(eta * 11.0));
    double n = 0.0, h = 1e-5;
    for (int k = 0; k < layer; ++k, h *= 1.5)
      n += h;
    const double s = 0.25 * M_PI * xi;  // arc length along the wall
    if (curvature == 0.0)
      return Vec2{s, n};
    const double r = 1.0 / curvature + n, angle = s * curvature;
    return Vec2{r * std::sin(angle), 1.0 / curvature - r * std::cos(angle)};
  };
  return structured_mesh(spec);
}

// The wall-aligned stencil of curved_wall_layer's mesh ("wall" the only wall); checks that the
// wall layer's stretched nodes were mapped.
StencilGeometry aligned_stencil_of_wall_layer(const Mesh& mesh, const DualMesh& dual) {
  std::vector<char> wall_curves(mesh.boundaries.size(), 0);
  wall_curves[mesh.boundary_index("wall")] = 1;
  int mapped = 0;
  StencilGeometry aligned = wall_aligned_stencil(mesh, dual, wall_curves, 4.0, &mapped);
  EXPECT_GT(mapped, 100);
  return aligned;
}
}  // namespace

TEST(Gradient, WallAlignedStencilReconstructsAWallLayerProfileAlongACurvedWall) {
  // A boundary-layer-like field that depends on the wall distance only: along the wall (same
  // layer) it is constant, so the reconstruction to the along-wall faces must return the node
  // value. Cartesian vectors pick up the wall-normal gradient times the curvature offset.
  const Mesh mesh = curved_wall_layer(1.0);
  const DualMesh dual = build_dual(mesh, Geometry::planar);
  const StencilGeometry cartesian = cartesian_stencil(dual);
  const StencilGeometry aligned = aligned_stencil_of_wall_layer(mesh, dual);
  std::vector<State> q(dual.num_nodes);
  for (int i = 0; i < dual.num_nodes; ++i) {
    const double n = norm(dual.coords[i] - Vec2{0.0, 1.0}) - 1.0;
    const double profile = std::tanh(n / 1e-4);
    q[i] = {profile, profile, profile, profile};
  }
  auto worst_along_wall_error = [&](const StencilGeometry& g) {
    std::vector<std::array<double, 8>> grad;
    lsq_gradients(dual, build_lsq_gradient(dual, g.to_neighbour), q, grad);
    const auto& ne = dual.node_edges;
    double worst = 0.0;
    for (int i = 0; i < dual.num_nodes; ++i) {
      for (int k = ne.offsets[i]; k < ne.offsets[i + 1]; ++k) {
        const int j = ne.neighbour[k];
        // along-wall neighbours on the first four layers (same wall distance)
        if (std::abs(q[j][0] - q[i][0]) > 1e-9 || q[i][0] > 0.9)
          continue;
        const Vec2 half = 0.5 * g.to_neighbour[k];
        worst = std::max(worst, std::abs(grad[i][0] * half.x + grad[i][1] * half.y));
      }
    }
    return worst;
  };
  const double aligned_error = worst_along_wall_error(aligned);
  const double cartesian_error = worst_along_wall_error(cartesian);
  EXPECT_LT(aligned_error, 1e-3);   // measured 0
  EXPECT_GT(cartesian_error, 1.0);  // the profile's whole range and more
}

TEST(Gradient, WallAlignedStencilIsCartesianOnAStraightWall) {
  const Mesh mesh = curved_wall_layer(0.0);
  const DualMesh dual = build_dual(mesh, Geometry::planar);
  const StencilGeometry cartesian = cartesian_stencil(dual);
  const StencilGeometry aligned = aligned_stencil_of_wall_layer(mesh, dual);
  for (std::size_t k = 0; k < aligned.to_neighbour.size(); ++k) {
    ASSERT_NEAR(aligned.to_neighbour[k].x, cartesian.to_neighbour[k].x, 1e-12);
    ASSERT_NEAR(aligned.to_neighbour[k].y, cartesian.to_neighbour[k].y, 1e-12);
  }
  for (std::size_t f = 0; f < aligned.to_face.size(); ++f) {
    ASSERT_NEAR(aligned.to_face[f].x, cartesian.to_face[f].x, 1e-12);
    ASSERT_NEAR(aligned.to_face[f].y, cartesian.to_face[f].y, 1e-12);
  }
}
