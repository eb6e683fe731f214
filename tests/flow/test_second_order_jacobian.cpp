// The assembled Jacobian of the second-order residual (SolverSettings::jacobian_order 2) against
// the derivative of the residual itself: the difference quotient that is the matrix-free Krylov
// operator, with the limiter held at the same values in both.
//
// An inviscid channel over a bump, 33 x 13 nodes clustered to the bump wall (so that the
// wall-aligned reconstruction stencil is active there), part of the quads split, marched 40
// second-order steps from a uniform start so that it has gradients, a live limiter, inflow,
// outflow and a slip wall. With the exact Roe Jacobian the only differences are the difference
// quotient's own error; the first-order Jacobian, as a check that the comparison can fail, is
// off by the reconstruction it leaves out.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <set>

#include "mesh_generate.hpp"
#include "tfmb-flow/solver.hpp"

using namespace tfmb::flow;

namespace {

Mesh bump_channel() {
  StructuredMeshSpec spec;
  spec.ni = 33;
  spec.nj = 13;
  spec.map = [](double xi, double eta) {
    const double x = 0.3 * xi;
    const double bump =
        (xi > 0.3 && xi < 0.7) ? 0.004 * std::pow(std::sin(M_PI * (xi - 0.3) / 0.4), 2) : 0.0;
    const double stretched = (std::exp(3.0 * eta) - 1.0) / (std::exp(3.0) - 1.0);
    return Vec2{x, bump + (0.05 - bump) * stretched};
  };
  spec.split = [](int i, int j) { return (i + 2 * j) % 5 == 0; };
  spec.bottom = "wall";
  spec.right = "outlet";
  spec.top = "top";
  spec.left = "inlet";
  return structured_mesh(spec);
}

SolverSettings settings(int jacobian_order) {
  SolverSettings s;
  s.order = 2;
  s.jacobian_order = jacobian_order;
  s.roe_jacobian = RoeJacobian::exact;
  s.matrix_free = MatrixFree::off;
  s.max_iterations = 40;
  s.residual_drop = 1e-12;
  s.reference_state = {1.16, 347.0, 347.0, 1.0e5};
  return s;
}

FlowSolver make_solver(const Mesh& mesh, int jacobian_order) {
  const PerfectGas gas{1.4, 287.05};
  BoundaryCondition wall, out, top, in;
  wall.kind = BcKind::slip_wall;
  out.kind = BcKind::pressure_outflow;
  out.static_pressure = 1.0e5;
  top.kind = BcKind::symmetry;
  in.kind = BcKind::stagnation_inflow;
  in.total_pressure = 1.2e5;
  in.total_temperature = 300.0;
  return FlowSolver(mesh, Geometry::planar, gas, {wall, out, top, in}, settings(jacobian_order));
}

// Largest |a - b| relative to the largest |b|.
double relative_error(const std::vector<double>& a, const std::vector<double>& b) {
  double diff = 0.0, big = 0.0;
  for (std::size_t k = 0; k < a.size(); ++k) {
    diff = std::max(diff, std::abs(a[k] - b[k]));
    big = std::max(big, std::abs(b[k]));
  }
  return diff / std::max(big, 1e-300);
}

}  // namespace

TEST(SecondOrderJacobian, IsTheDerivativeOfTheSecondOrderResidual) {
  const Mesh mesh = bump_channel();
  FlowSolver marched = make_solver(mesh, 2);
  marched.set_uniform({1.16, 100.0, 0.0, 1.0e5});
  marched.solve();
  const std::vector<State> w = marched.primitive();

  const int n = static_cast<int>(w.size());
  std::mt19937 random(11);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::vector<double> x(4 * static_cast<std::size_t>(n));
  const std::vector<double> scale = {1.0, 100.0, 100.0, 2.5e5};
  for (int i = 0; i < n; ++i) {
    for (int v = 0; v < 4; ++v)
      x[4 * i + v] = 1e-3 * scale[v] * unit(random);
  }
  double errors[2];
  for (int order : {1, 2}) {
    FlowSolver solver = make_solver(mesh, order);
    solver.set_primitive(w);
    const std::vector<double> assembled = solver.jacobian_product(x, true);
    const std::vector<double> differenced = solver.jacobian_product(x, false);
    errors[order - 1] = relative_error(assembled, differenced);
  }
  std::printf(
      "d R / d U x, assembled against differences: %.2e (second-order Jacobian), %.2e "
      "(first-order Jacobian)\n",
      errors[1], errors[0]);
  EXPECT_LT(errors[1], 1e-5);
  EXPECT_GT(errors[0], 1e-2);
}

// On a 3 x 3 quad grid the median dual's edges are the 12 sides; the pairs at distance 2 add
// the 6 two apart along a grid line and the 8 across a cell's diagonal.
TEST(SecondOrderJacobian, PatternHoldsNeighboursOfNeighbours) {
  StructuredMeshSpec spec;
  spec.ni = 3;
  spec.nj = 3;
  const DualMesh dual = build_dual(structured_mesh(spec), Geometry::planar);
  const auto pairs = second_neighbour_pairs(dual);
  EXPECT_EQ(pairs.size(), 26u);
  std::set<std::array<int, 2>> unique(pairs.begin(), pairs.end());
  EXPECT_EQ(unique.size(), pairs.size());
  for (const auto& p : pairs)
    EXPECT_LT(p[0], p[1]);
}
