// Unit tests of the tfmb-loads building blocks: projection, trace integrals, expressions.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "tfmb-loads/beam_line.hpp"
#include "tfmb-loads/displace.hpp"
#include "tfmb-loads/expression.hpp"
#include "tfmb-loads/trace.hpp"

using namespace tfmb::loads;

TEST(BeamLine, ProjectionOnAStraightLineIsOrthogonal) {
  const BeamLine beam({{0, 0}, {1, 0}, {3, 0}});
  const BeamProjection p = beam.project({2.0, 0.7});
  EXPECT_EQ(p.element, 1u);
  EXPECT_NEAR(p.xi, 0.5, 1e-15);
  EXPECT_NEAR(p.arc_length, 2.0, 1e-15);
  EXPECT_NEAR(p.point.y(), 0.0, 1e-15);
  const BeamProjection before = beam.project({-0.25, 0.1});
  EXPECT_EQ(before.element, 0u);
  EXPECT_DOUBLE_EQ(before.xi, 0.0);
  EXPECT_NEAR(before.overshoot, 0.25, 1e-15);
}

TEST(BeamLine, ProjectionIsContinuousAcrossAKink) {
  const BeamLine beam({{0, 0}, {1, 0}, {2, 1}});
  // A point on the bisector node line through node 1 maps to node 1 from both elements.
  const Vec2 bisector_normal = Vec2(-beam.node_tangent(1).y(), beam.node_tangent(1).x());
  const BeamProjection p = beam.project(Vec2(1, 0) + 0.1 * bisector_normal);
  EXPECT_NEAR(p.arc_length, 1.0, 1e-14);
}

TEST(Trace, UniformPressureResultantDependsOnlyOnTheEndPoints) {
  // For uniform p, int -p n ds = -p * rot90(B - A) for any polyline from A to B.
  WallTrace t;
  t.name = "t";
  t.points = {{0, 0}, {0.3, 0.1}, {0.5, -0.2}, {1.0, 0.0}};
  t.pressure.assign(4, 2.0);
  t.wall_shear.assign(4, 0.0);
  const Resultant r = integrate_traces({&t});
  EXPECT_NEAR(r.force.x(), 0.0, 1e-15);
  EXPECT_NEAR(r.force.y(), -2.0, 1e-15);  // n = left normal (0, 1) on the chord
  // Moment about the origin: int x x (-p n) ds = -p/2 (|B|^2 - |A|^2) for the left normal.
  EXPECT_NEAR(r.moment, -1.0, 1e-15);
}

TEST(Expression, EvaluatesArithmeticAndFunctions) {
  const Expression e("1 + 2*x^2 - sin(pi*y)/2 + -3", {"x", "y"});
  EXPECT_NEAR(e({2.0, 0.5}), 1 + 8 - 0.5 - 3, 1e-15);
  EXPECT_NEAR(Expression("2^3^2", {})({}), 512.0, 1e-12);
  EXPECT_THROW(Expression("1 + z", {"x"}), std::invalid_argument);
  EXPECT_THROW(Expression("(1 + x", {"x"}), std::invalid_argument);
  const auto a = parse_assignments("p = 1; tau=x ;", {"p", "tau"});
  EXPECT_EQ(a.size(), 2u);
  EXPECT_THROW(parse_assignments("q=1", {"p"}), std::invalid_argument);
}

TEST(Displace, WienerMilenkovicAngle) {
  const double phi = 0.7;
  EXPECT_NEAR(wiener_milenkovic_angle(4.0 * std::tan(phi / 4.0)), phi, 1e-15);
}
