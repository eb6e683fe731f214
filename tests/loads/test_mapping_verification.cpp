// Verification of the load and displacement mappings against analytic solutions.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <numbers>
#include <cstdio>
#include <Eigen/Geometry>

#include "tfmb-loads/displace.hpp"
#include "tfmb-loads/mapping.hpp"

using namespace tfmb::loads;

namespace {

using Field = std::function<double(const Vec2&)>;

struct StraightCase {
  Vec2 start{0.2, 0.1};
  double angle = 0.17;   // [rad]
  double length = 0.3;   // [m]
  double thickness = 0.004;
  double width = 0.5;
  Vec2 tangent() const { return {std::cos(angle), std::sin(angle)}; }
  Vec2 normal() const { return {-std::sin(angle), std::cos(angle)}; }
  BeamLine beam(int nodes) const {
    std::vector<Vec2> r;
    for (int i = 0; i < nodes; ++i) r.push_back(start + length * i / (nodes - 1.0) * tangent());
    return BeamLine(r);
  }
  // Inner wall at -t/2 (fluid further on that side), outer at +t/2; ordered start to end.
  WallTrace wall(Side side, int points, const Field& p, const Field& tau) const {
    WallTrace w;
    w.name = side == Side::inner ? "inner" : "outer";
    w.side = side;
    const double offset = (side == Side::inner ? -0.5 : 0.5) * thickness;
    for (int i = 0; i < points; ++i) {
      const Vec2 x = start + length * i / (points - 1.0) * tangent() + offset * normal();
      w.points.push_back(x);
      w.pressure.push_back(p(x));
      w.wall_shear.push_back(tau(x));
    }
    // The outward normal of the inner wall is -normal = -(left normal of the point order).
    w.normal_sign = side == Side::inner ? -1.0 : 1.0;
    return w;
  }
};


}  // namespace

// A linear pressure and shear field on a straight flap is reproduced exactly by both methods:
// the traces are linear along the walls, so the distributed load is linear along the beam.
TEST(LoadsVerification, LinearPressureIsReproducedExactlyByBothMethods) {
  const StraightCase c;
  const Field p_in = [](const Vec2& x) { return 3e5 - 4e5 * x.x() + 1e5 * x.y(); };
  const Field p_out = [](const Vec2& x) { return 1e5 + 2e4 * x.x(); };
  const Field tau_in = [](const Vec2& x) { return 120.0 + 300.0 * x.x(); };
  const Field tau_out = [](const Vec2& x) { return -40.0 + 80.0 * x.y(); };
  // Trace points do not coincide with beam nodes (37 vs 11).
  const WallTrace inner = c.wall(Side::inner, 37, p_in, tau_in);
  const WallTrace outer = c.wall(Side::outer, 23, p_out, tau_out);
  const BeamLine beam = c.beam(11);
  const Vec2 t = c.tangent(), n = c.normal();
  for (Method method : {Method::linear, Method::conservative}) {
    const FlapLoads l = map_loads(method, beam, {&inner, &outer}, c.width);
    double scale = 0.0;
    for (std::size_t i = 0; i < beam.node_count(); ++i) {
      const Vec2 r = beam.nodes()[i];
      const Vec2 xi = r - 0.5 * c.thickness * n, xo = r + 0.5 * c.thickness * n;
      // Analytic: inner traction p_in n + tau_in t, outer -p_out n + tau_out t; offsets -+t/2 n.
      const Vec2 q = c.width * ((p_in(xi) - p_out(xo)) * n + (tau_in(xi) + tau_out(xo)) * t);
      const double m = c.width * 0.5 * c.thickness * (tau_in(xi) - tau_out(xo));
      scale = std::max(scale, q.norm());
      EXPECT_LT((l.distributed_force[i] - q).norm(), 1e-9 * scale) << method_name(method) << " node " << i;
      EXPECT_NEAR(l.distributed_moment[i], m, 1e-9 * std::abs(m) + 1e-9) << method_name(method) << " node " << i;
    }
    EXPECT_LT((l.mapped.force - l.traces.force).norm(), 1e-10 * l.traces.force.norm()) << method_name(method);
    EXPECT_NEAR(l.mapped.moment, l.traces.moment, 1e-10 * l.traces.force.norm() * c.length) << method_name(method);
  }
}

// The conservative method keeps each flap's total force and moment (about the origin) equal
// to the integral of the traces to 1e-10 relative, for any field and non-matching grids,
// here a curved, kinked beam with end faces and two inner traces.
TEST(LoadsVerification, ConservativeKeepsForceAndMomentTo1e10) {
  std::vector<Vec2> r;
  for (int i = 0; i < 9; ++i) {
    const double a = 0.6 * i / 8.0;
    r.emplace_back(1.0 + 0.5 * std::sin(a), 0.3 + 0.5 * (1 - std::cos(a)) + 0.01 * (i % 2));
  }
  const BeamLine beam(r);
  auto offset_wall = [&](double d, int points, double from, double to) {
    std::vector<Vec2> w;
    for (int k = 0; k < points; ++k) {
      const double s = from + (to - from) * k / (points - 1.0);
      const BeamProjection dummy{};
      (void)dummy;
      // Point at arc length s on the beam, offset along the element normal.
      std::size_t j = 0;
      while (j + 1 < beam.element_count() && beam.arc_length()[j + 1] < s) ++j;
      const double xi = (s - beam.arc_length()[j]) / beam.element_length(j);
      w.push_back(beam.nodes()[j] + xi * (beam.nodes()[j + 1] - beam.nodes()[j]) + d * beam.element_normal(j));
    }
    return w;
  };
  const double L = beam.length();
  auto make = [](std::string name, Side side, std::vector<Vec2> pts, double sign) {
    WallTrace t;
    t.name = std::move(name);
    t.side = side;
    t.points = std::move(pts);
    for (const Vec2& x : t.points) {
      t.pressure.push_back(2e5 * (1.0 + 0.3 * std::sin(7.0 * x.x()) * std::cos(3.0 * x.y())));
      t.wall_shear.push_back(150.0 * std::cos(5.0 * x.x()));
    }
    t.normal_sign = sign;
    return t;
  };
  const WallTrace inner_a = make("inner_a", Side::inner, offset_wall(-0.002, 29, 0.0, 0.4 * L), -1.0);
  const WallTrace inner_b = make("inner_b", Side::inner, offset_wall(-0.002, 41, 0.4 * L, L), -1.0);
  const WallTrace outer = make("outer", Side::outer, offset_wall(0.002, 17, 0.0, L), 1.0);
  const WallTrace end = make("end", Side::end, {outer.points.back(), inner_b.points.back()}, 1.0);
  const FlapLoads l = map_loads(Method::conservative, beam, {&inner_a, &inner_b, &outer, &end}, 0.7);
  const double f = l.traces.force.norm();
  EXPECT_LT((l.mapped.force - l.traces.force).norm() / f, 1e-10);
  EXPECT_LT(std::abs(l.mapped.moment - l.traces.moment) / std::max(std::abs(l.traces.moment), f * L), 1e-10);
  std::printf("[figures] conservative totals: force %.2e, moment %.2e relative\n",
              (l.mapped.force - l.traces.force).norm() / f,
              std::abs(l.mapped.moment - l.traces.moment) / std::max(std::abs(l.traces.moment), f * L));
  // The distributed loads (L2 projection) carry the same totals as the nodal loads.
  std::vector<Vec2> nf;
  std::vector<double> nm;
  consistent_nodal_loads(beam, l.distributed_force, l.distributed_moment, nf, nm);
  const Resultant from_distributed = nodal_resultant(beam, nf, nm);
  EXPECT_LT((from_distributed.force - l.traces.force).norm() / f, 1e-10);
  EXPECT_LT(std::abs(from_distributed.moment - l.traces.moment) / (f * L), 1e-10);
}

namespace {

// Uniform pressures on the two walls of a circular-arc flap (centre c, beam radius R,
// angles a0..a1): the resultant on a wall of radius rho is
//   F = -/+ p rho (sin a1 - sin a0, cos a0 - cos a1) w   (inner: +, outer: -)
// (the pressure force on an arc is p times its chord rotated by 90 degrees), all along
// radial lines, so the moment about the centre vanishes and about the origin is c x F.
struct ArcCase {
  Vec2 centre{0.4, -0.9};
  double radius = 1.0, a0 = 1.2, a1 = 1.9, thickness = 0.01, width = 0.4;
  double p_in = 3e5, p_out = 1e5;
  Vec2 analytic_force() const {
    const Vec2 chord(std::sin(a1) - std::sin(a0), std::cos(a0) - std::cos(a1));
    return width * (p_in * (radius - thickness / 2) - p_out * (radius + thickness / 2)) * chord;
  }
  FlapLoads map(Method method, int beam_nodes, int wall_points) const {
    std::vector<Vec2> r;
    for (int i = 0; i < beam_nodes; ++i) {
      const double a = a0 + (a1 - a0) * i / (beam_nodes - 1.0);
      r.push_back(centre + radius * Vec2(std::cos(a), std::sin(a)));
    }
    const BeamLine beam(r);
    WallTrace in, out;
    in.side = Side::inner;
    out.side = Side::outer;
    for (int k = 0; k < wall_points; ++k) {
      const double a = a0 + (a1 - a0) * k / (wall_points - 1.0);
      const Vec2 e(std::cos(a), std::sin(a));
      in.points.push_back(centre + (radius - thickness / 2) * e);
      out.points.push_back(centre + (radius + thickness / 2) * e);
    }
    in.pressure.assign(in.points.size(), p_in);
    out.pressure.assign(out.points.size(), p_out);
    in.wall_shear.assign(in.points.size(), 0.0);
    out.wall_shear.assign(out.points.size(), 0.0);
    // Counter-clockwise order: the left normal points to the centre. Inner: out of the
    // solid = towards the centre (+1); outer: away from it (-1).
    in.normal_sign = 1.0;
    out.normal_sign = -1.0;
    return map_loads(method, beam, {&in, &out}, width);
  }
};

}  // namespace

TEST(LoadsVerification, UniformPressureOnAnArcGivesTheAnalyticResultant) {
  const ArcCase c;
  const Vec2 F = c.analytic_force();
  const double M = c.centre.x() * F.y() - c.centre.y() * F.x();
  // Conservative: the chord polygon carries the arc's exact resultant.
  const FlapLoads cons = c.map(Method::conservative, 9, 50);
  EXPECT_LT((cons.mapped.force - F).norm() / F.norm(), 1e-12);
  std::printf("[figures] arc, conservative: resultant error %.2e relative\n", (cons.mapped.force - F).norm() / F.norm());
  EXPECT_LT(std::abs(cons.mapped.moment - M) / (F.norm() * c.radius), 1e-12);
  // Linear: second-order in the element length (chord-based length ratio, straight
  // elements, interpolated wall normals); the error falls by 4 per halving.
  double previous = 0.0;
  for (int nodes : {9, 17, 33, 65}) {
    // Trace spacing refined with the beam (seven wall segments per element).
    const FlapLoads lin = c.map(Method::linear, nodes, 7 * (nodes - 1) + 1);
    const double error = (lin.mapped.force - F).norm() / F.norm();
    std::printf("[figures] arc, linear, %d elements: resultant error %.3e relative\n", nodes - 1, error);
    if (previous > 0.0) {
      const double order = std::log2(previous / error);
      EXPECT_GT(order, 1.8) << nodes;
      EXPECT_LT(order, 2.3) << nodes;
    }
    previous = error;
  }
  EXPECT_LT(previous, 1e-4);
}

// Refining the flow trace of a smooth pressure: the trace integral (trapezoidal in the
// piecewise-linear trace) and the linear method's nodal loads (interpolation of the trace)
// converge at second order in the trace spacing.
TEST(LoadsVerification, TraceRefinementConvergesAtSecondOrder) {
  const StraightCase c;
  // 1.3 periods: not periodic over the flap, so the trapezoidal trace integral is only
  // second-order accurate (a whole number of periods would be integrated exactly).
  const double k = 1.3 * 2.0 * std::numbers::pi / c.length;
  const Field p_in = [&](const Vec2& x) {
    return 2e5 * (1.0 + 0.3 * std::sin(k * (x - c.start).dot(c.tangent()) + 0.4));
  };
  const Field zero = [](const Vec2&) { return 0.0; };
  const BeamLine beam = c.beam(8);
  // Exact total normal force: w int p ds = w 2e5 (L + 0.3 (cos 0.4 - cos(kL + 0.4)) / k).
  const double exact_total =
      c.width * 2e5 * (c.length + 0.3 * (std::cos(0.4) - std::cos(k * c.length + 0.4)) / k);
  double previous_total = 0.0, previous_nodal = 0.0;
  for (int points : {21, 41, 81, 161}) {
    const WallTrace inner = c.wall(Side::inner, points, p_in, zero);
    const WallTrace outer = c.wall(Side::outer, points, zero, zero);
    const FlapLoads l = map_loads(Method::linear, beam, {&inner, &outer}, c.width);
    const double total_error = std::abs(l.traces.force.dot(c.normal()) - exact_total) / exact_total;
    double nodal_error = 0.0;
    for (std::size_t i = 0; i < beam.node_count(); ++i) {
      const Vec2 x = beam.nodes()[i] - 0.5 * c.thickness * c.normal();
      nodal_error = std::max(nodal_error, std::abs(l.distributed_force[i].dot(c.normal()) - c.width * p_in(x)));
    }
    std::printf("[figures] trace refinement, %d points: total error %.3e, nodal load error %.3e N/m\n", points,
                total_error, nodal_error);
    if (previous_total > 0.0) {
      EXPECT_NEAR(std::log2(previous_total / total_error), 2.0, 0.15) << points;
      EXPECT_NEAR(std::log2(previous_nodal / nodal_error), 2.0, 0.3) << points;
    }
    previous_total = total_error;
    previous_nodal = nodal_error;
  }
}

// A rigid rotation and translation of a curved flap moves every wall point exactly.
TEST(DisplaceVerification, RigidMotionIsMappedExactly) {
  std::vector<Vec2> r;
  for (int i = 0; i < 7; ++i) {
    const double a = 0.1 + 0.5 * i / 6.0;
    r.emplace_back(0.3 + std::cos(a), -0.2 + std::sin(a));
  }
  const BeamLine beam(r);
  const double phi = 0.23;
  const Vec2 shift(0.011, -0.004), pivot(0.5, 0.2);
  const Eigen::Matrix2d R = Eigen::Rotation2Dd(phi).toRotationMatrix();
  BeamMotion motion;
  for (const Vec2& x : r) {
    motion.displacement.push_back(shift + (R - Eigen::Matrix2d::Identity()) * (x - pivot));
    motion.rotation.push_back(phi);
  }
  std::vector<Vec2> wall;
  for (int k = 0; k < 40; ++k) {
    const double a = 0.08 + 0.54 * k / 39.0;
    const double rho = k % 2 ? 1.003 : 0.997;
    wall.emplace_back(0.3 + rho * std::cos(a), -0.2 + rho * std::sin(a));
  }
  const std::vector<Vec2> d = wall_displacement(beam, motion, wall);
  for (std::size_t k = 0; k < wall.size(); ++k) {
    const Vec2 exact = shift + (R - Eigen::Matrix2d::Identity()) * (wall[k] - pivot);
    EXPECT_LT((d[k] - exact).norm(), 1e-14) << k;
  }
}
