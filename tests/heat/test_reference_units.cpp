// Unit tests of the small building blocks: shape functions, quadrature, property tables,
// wall traces and arc length.
#include "heat_test_support.hpp"
#include "tfmb-heat/boundary_geometry.hpp"
#include "tfmb-heat/property_table.hpp"
#include "tfmb-heat/quadrature.hpp"
#include "tfmb-heat/shape_functions.hpp"
#include "tfmb-heat/trace.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

using namespace tfmb::heat;

namespace {
const ElementType kAllTypes[] = {ElementType::tri3, ElementType::quad4, ElementType::tri6,
                                 ElementType::quad8, ElementType::quad9};
constexpr double kEps = 1e-13;
}  // namespace

TEST(HeatShapeFunctions, KroneckerAtNodesAndPartitionOfUnity) {
  for (auto type : kAllTypes) {
    const int n = nodes_per_element(type);
    std::vector<double> v(n), dx(n), dy(n);
    const auto nodes = reference_node_coordinates(type);
    for (int a = 0; a < n; ++a) {
      shape_functions(type, nodes[a][0], nodes[a][1], v.data(), dx.data(), dy.data());
      for (int b = 0; b < n; ++b) EXPECT_NEAR(v[b], a == b ? 1.0 : 0.0, kEps) << element_name(type);
    }
    // An interior point: values sum to one, derivatives sum to zero.
    shape_functions(type, 0.21, 0.17, v.data(), dx.data(), dy.data());
    double sum = 0, sum_dx = 0, sum_dy = 0;
    for (int a = 0; a < n; ++a) sum += v[a], sum_dx += dx[a], sum_dy += dy[a];
    EXPECT_NEAR(sum, 1.0, kEps) << element_name(type);
    EXPECT_NEAR(sum_dx, 0.0, kEps) << element_name(type);
    EXPECT_NEAR(sum_dy, 0.0, kEps) << element_name(type);
  }
}

TEST(HeatShapeFunctions, DerivativesMatchFiniteDifferences) {
  const double h = 1e-6;
  for (auto type : kAllTypes) {
    const int n = nodes_per_element(type);
    std::vector<double> v(n), dx(n), dy(n), vp(n), vm(n), tmp1(n), tmp2(n);
    const double xi = 0.23, eta = 0.31;
    shape_functions(type, xi, eta, v.data(), dx.data(), dy.data());
    shape_functions(type, xi + h, eta, vp.data(), tmp1.data(), tmp2.data());
    shape_functions(type, xi - h, eta, vm.data(), tmp1.data(), tmp2.data());
    // Central differences of quadratics are exact up to rounding: tolerance ~ eps / h.
    for (int a = 0; a < n; ++a) EXPECT_NEAR(dx[a], (vp[a] - vm[a]) / (2 * h), 1e-8) << element_name(type);
    shape_functions(type, xi, eta + h, vp.data(), tmp1.data(), tmp2.data());
    shape_functions(type, xi, eta - h, vm.data(), tmp1.data(), tmp2.data());
    for (int a = 0; a < n; ++a) EXPECT_NEAR(dy[a], (vp[a] - vm[a]) / (2 * h), 1e-8) << element_name(type);
  }
}

TEST(HeatShapeFunctions, ReproduceQuadraticFieldsOnQuadraticElements) {
  // Completeness: tri6, quad8 and quad9 all contain the complete quadratic polynomials.
  auto f = [](double x, double y) { return 1.0 + 2 * x - 3 * y + 0.5 * x * x - 0.7 * x * y + 1.1 * y * y; };
  for (auto type : {ElementType::tri6, ElementType::quad8, ElementType::quad9}) {
    const int n = nodes_per_element(type);
    std::vector<double> v(n), dx(n), dy(n);
    const auto nodes = reference_node_coordinates(type);
    shape_functions(type, 0.13, 0.29, v.data(), dx.data(), dy.data());
    double value = 0;
    for (int a = 0; a < n; ++a) value += v[a] * f(nodes[a][0], nodes[a][1]);
    EXPECT_NEAR(value, f(0.13, 0.29), kEps) << element_name(type);
  }
}

TEST(HeatShapeFunctions, EdgeFunctions) {
  double n[3], dn[3];
  edge_shape_functions(3, 0.0, n, dn);
  EXPECT_NEAR(n[2], 1.0, kEps);
  edge_shape_functions(3, -1.0, n, dn);
  EXPECT_NEAR(n[0], 1.0, kEps);
  edge_shape_functions(2, 0.5, n, dn);
  EXPECT_NEAR(n[0], 0.25, kEps);
  EXPECT_NEAR(dn[1], 0.5, kEps);
}

TEST(HeatQuadrature, GaussLegendreIsExactToDegree2nMinus1) {
  for (int n = 1; n <= 6; ++n) {
    const auto rule = gauss_legendre(n);
    for (int degree = 0; degree <= 2 * n - 1; ++degree) {
      double sum = 0;
      for (std::size_t q = 0; q < rule.points.size(); ++q) sum += rule.weights[q] * std::pow(rule.points[q], degree);
      const double exact = degree % 2 ? 0.0 : 2.0 / (degree + 1);
      EXPECT_NEAR(sum, exact, 1e-14) << "n " << n << " degree " << degree;
    }
  }
}

TEST(HeatQuadrature, TriangleRulesIntegrateMonomialsExactly) {
  // int_T x^i y^j = i! j! / (i + j + 2)!
  auto factorial = [](int k) { double f = 1; for (int i = 2; i <= k; ++i) f *= i; return f; };
  for (int degree : {1, 2, 4, 5}) {
    const auto rule = triangle_rule(degree);
    for (int i = 0; i <= degree; ++i) {
      for (int j = 0; i + j <= degree; ++j) {
        double sum = 0;
        for (std::size_t q = 0; q < rule.points.size(); ++q) {
          sum += rule.weights[q] * std::pow(rule.points[q][0], i) * std::pow(rule.points[q][1], j);
        }
        // Dunavant's tabulated points carry 15 digits.
        EXPECT_NEAR(sum, factorial(i) * factorial(j) / factorial(i + j + 2), 1e-14)
            << "degree " << degree << " x^" << i << " y^" << j;
      }
    }
  }
  EXPECT_EQ(quad_gauss(3).weights.size(), 9u);
}

TEST(HeatPropertyTable, InterpolatesClampsAndReportsRange) {
  const PropertyTable k({300, 500, 900}, {6.0, 8.0, 16.0});
  EXPECT_DOUBLE_EQ(k.value(400), 7.0);
  EXPECT_DOUBLE_EQ(k.slope(400), 0.01);
  EXPECT_DOUBLE_EQ(k.value(700), 12.0);
  EXPECT_DOUBLE_EQ(k.slope(700), 0.02);
  EXPECT_DOUBLE_EQ(k.value(200), 6.0);
  EXPECT_DOUBLE_EQ(k.slope(1000), 0.0);
  EXPECT_TRUE(k.contains(900));
  EXPECT_FALSE(k.contains(901));
  const auto c = PropertyTable::constant(3.0);
  EXPECT_TRUE(c.contains(1e6));
  EXPECT_DOUBLE_EQ(c.value(-5), 3.0);
  EXPECT_THROW(PropertyTable({300, 300}, {1, 2}), std::invalid_argument);
  EXPECT_THROW(PropertyTable({300, 400}, {1}), std::invalid_argument);
}

TEST(HeatPropertyTable, RejectsNonPositiveConductivity) {
  Material m{"bad", PropertyTable({300, 600}, {5.0, 0.0}), {}, {}};
  try {
    validate_material(m, false);
    FAIL() << "expected invalid_argument";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("conductivity"), std::string::npos) << error.what();
  }
  // Steady runs need no capacity; transient runs do.
  Material ok{"ok", PropertyTable::constant(5.0), {}, {}};
  EXPECT_NO_THROW(validate_material(ok, false));
  EXPECT_THROW(validate_material(ok, true), std::invalid_argument);
}

TEST(HeatTrace, InterpolatesAndRefusesUncoveredPoints) {
  const Trace t({0.0, 1.0, 3.0}, {10.0, 20.0, 0.0}, "wall 'w': T");
  EXPECT_DOUBLE_EQ(t.at(0.5, 0.0), 15.0);
  EXPECT_DOUBLE_EQ(t.at(2.0, 0.0), 10.0);
  EXPECT_DOUBLE_EQ(t.at(3.0 + 1e-12, 1e-9), 0.0);
  EXPECT_THROW(t.at(3.1, 1e-9), std::invalid_argument);
  EXPECT_THROW(Trace({0.0, 0.0}, {1, 2}), std::invalid_argument);
}

TEST(HeatBoundaryGeometry, ArcLengthAlongStripSidesAndReversedEdges) {
  StripMeshOptions o;
  o.length = 2.0;
  o.thickness = 0.1;
  o.cells_along = 4;
  o.cells_through = 1;
  for (auto type : {ElementType::quad4, ElementType::quad8}) {
    o.type = type;
    auto mesh = make_strip_mesh(o);
    auto s = boundary_arc_length(mesh, mesh.boundaries.at("bottom"));
    const auto& curve = mesh.boundaries.at("bottom");
    for (std::size_t i = 0; i < s.size(); ++i) EXPECT_NEAR(s[i], mesh.points(curve.nodes[i], 0), 1e-14);
    EXPECT_NEAR(boundary_length(mesh, curve), 2.0, 1e-14);
    // Reversing every edge keeps s measured from the chain start.
    auto reversed = curve;
    const auto npe = static_cast<std::size_t>(curve.nodes_per_edge);
    for (std::size_t e = 0; e < curve.size(); ++e) std::swap(reversed.nodes[e * npe], reversed.nodes[e * npe + 1]);
    s = boundary_arc_length(mesh, reversed);
    for (std::size_t i = 0; i < s.size(); ++i) EXPECT_NEAR(s[i], mesh.points(reversed.nodes[i], 0), 1e-14);
    // A broken chain cannot carry an arc-length trace.
    auto broken = curve;
    std::swap(broken.nodes[0], broken.nodes[npe * 2]);
    std::swap(broken.nodes[1], broken.nodes[npe * 2 + 1]);
    EXPECT_THROW(boundary_arc_length(mesh, broken), std::invalid_argument);
  }
}

#include "tfmb-heat/wall_mapping.hpp"

TEST(HeatWallMapping, TraceIsReexpressedInTheSolidArcLength) {
  StripMeshOptions o;
  o.length = 1.0;
  o.thickness = 0.1;
  o.cells_along = 5;
  o.cells_through = 1;
  const auto mesh = make_strip_mesh(o);
  const auto& bottom = mesh.boundaries.at("bottom");
  // A flow trace running from x = 1 to x = 0, slightly off the wall (a different discretisation
  // of the same surface), with T = 500 + 100 x.
  std::vector<double> x, y, t;
  for (int i = 0; i <= 20; ++i) {
    x.push_back(1.0 - i / 20.0);
    y.push_back(-1e-4);
    t.push_back(500.0 + 100.0 * x.back());
  }
  const auto trace = map_trace_to_boundary(mesh, bottom, x, y, t, "flow wall", 1e-3);
  EXPECT_NEAR(trace.at(0.25, 1e-12), 525.0, 1e-12);
  EXPECT_NEAR(trace.at(1.0, 1e-12), 600.0, 1e-12);
  // Points far from the wall belong to another wall.
  y[3] = 0.05;
  EXPECT_THROW(map_trace_to_boundary(mesh, bottom, x, y, t, "flow wall", 1e-3), std::invalid_argument);
}
