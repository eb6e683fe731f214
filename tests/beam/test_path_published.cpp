// The load path through the file stage against a published path: Lee's frame, started coarse
// with the arc length, through its limit points in load (snap-through) and in displacement
// (snap-back), compared row by row with Simo & Vu-Quoc's (1986) path
// (refdata/beam/lee_frame_dead_load_path_simo_vu_quoc.csv).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <string>
#include <vector>

#include "refdata.hpp"
#include "stage_models.hpp"
#include "tfmb-beam/run.hpp"
#include "tfmb/formats/structure.hpp"

using namespace tfmb;
using namespace beam_test;

namespace {

struct PlanePoint {
  double x, y;
};

/// Euclidean distance from p to the polyline through `line` (in the order given).
double distance_to_polyline(PlanePoint p, const std::vector<PlanePoint>& line) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i + 1 < line.size(); ++i) {
    const double ax = line[i].x, ay = line[i].y;
    const double dx = line[i + 1].x - ax, dy = line[i + 1].y - ay;
    const double length2 = dx * dx + dy * dy;
    const double t =
        length2 > 0.0 ? std::clamp(((p.x - ax) * dx + (p.y - ay) * dy) / length2, 0.0, 1.0) : 0.0;
    best = std::min(best, std::hypot(p.x - ax - t * dx, p.y - ay - t * dy));
  }
  return best;
}

/// One curve of the reference file in normalised coordinates (displacement / L, P / P_limit),
/// from the unloaded state: the path starts there, the digitised points only near it.
std::vector<PlanePoint> reference_curve(const Table& table, const std::string& curve, double length,
                                        double limit_load) {
  const int displacement = table.col("displacement"), load = table.col("load"),
            name = table.col("curve");
  std::vector<PlanePoint> line = {{0.0, 0.0}};
  for (std::size_t r = 0; r < table.rows.size(); ++r)
    if (table.text[r][static_cast<std::size_t>(name)] == curve)
      line.push_back({table.rows[r][static_cast<std::size_t>(displacement)] / length,
                      table.rows[r][static_cast<std::size_t>(load)] / limit_load});
  return line;
}

/// The shallow two-bar truss with a soft spring on top (see the test below): bars "left" from
/// (-a, 0) and "right" to (a, 0) meeting at the apex (0, h), pinned to the ground and joined by a
/// revolute joint; the spring, a bar "spring" from the apex up to (0, h + spring_length), joined
/// to the apex by a revolute joint, its top held by a pin sliding along y.
struct TrussWithSpring {
  double half_span = 1.0, rise = 0.1;  // [m]
  double bar_ea = 1e5, bar_ei = 1e3;   // [N], [N m^2]
  double spring_length = 0.5;          // [m]
  double spring_ea = 250.0;            // [N]: spring stiffness spring_ea / spring_length
  double spring_ei = 100.0;            // [N m^2]: keeps the spring bar far from buckling
};

fs::path write_truss_with_spring_model(const fs::path& dir, const TrussWithSpring& t) {
  const fs::path file = write_cantilever_model(dir, "revolute");
  formats::Document doc = formats::read_document(h5::Reader(file));
  const Eigen::Vector2d left(-t.half_span, 0.0), apex(0.0, t.rise), right(t.half_span, 0.0),
      top(0.0, t.rise + t.spring_length);
  const double shear = 10.0 * t.bar_ea;  // [N] GA: no part in straight bars under end forces
  add_straight_flap(doc, "left", 0, left, apex, 2, t.bar_ea, shear, t.bar_ei);
  add_straight_flap(doc, "right", 1, apex, right, 2, t.bar_ea, shear, t.bar_ei);
  add_straight_flap(doc, "spring", 2, apex, top, 2, t.spring_ea, shear, t.spring_ei);
  erase_prefix(doc, "/flaps/sample");
  for (const auto& [name, other] :
       {std::pair<std::string, std::string>{"apex", "right"}, {"apex_spring", "spring"}}) {
    const std::string g = "/joints/" + name;
    copy_prefix(doc, "/joints/sample", g);
    doc.attributes[g]["kind"].text = "revolute";
    // the example joint's torsional stiffness (revolute_spring's attribute) stays in the file:
    // a revolute joint must ignore it and be an ideal hinge
    doc.attributes[g]["flap_a"].text = "left";
    doc.attributes[g]["end_a"].text = "end";
    doc.attributes[g]["flap_b"].text = other;
    doc.attributes[g]["end_b"].text = "start";
    doc.datasets[g + "/point"].floats = {apex.x(), apex.y()};
  }
  erase_prefix(doc, "/joints/sample");
  for (const auto& [name, flap, end, at, kind] :
       {std::tuple<std::string, std::string, std::string, Eigen::Vector2d, std::string>{
            "left_foot", "left", "start", left, "pinned"},
        {"right_foot", "right", "end", right, "pinned"},
        {"guide", "spring", "end", top, "sliding_pinned"}}) {
    const std::string g = "/supports/" + name;
    copy_prefix(doc, "/supports/sample", g);
    doc.attributes[g]["flap"].text = flap;
    doc.attributes[g]["end"].text = end;
    doc.attributes[g]["kind"].text = kind;
    doc.datasets[g + "/point"].floats = {at.x(), at.y()};
    if (kind == "sliding_pinned") {
      doc.datasets[g + "/axis"] = doc.datasets[g + "/point"];
      doc.datasets[g + "/axis"].floats = {0.0, 1.0};
      doc.attributes[g + "/axis"] = doc.attributes[g + "/point"];
      doc.attributes[g + "/axis"]["units"].text = "1";
    }
  }
  erase_prefix(doc, "/supports/sample");
  formats::write_document(doc, file);
  return file;
}

}  // namespace

// Lee's frame as in Stage.LeeFrameByArcLengthFromTenLoadSteps (members of 1.2 m at Lee's
// slenderness, EI = 100 N m^2, the dead load on the beam at L/5 from the corner) loaded to
// P L^2 / EI = 35, inside the range the published path covers (it ends near 39), and run with
// --arc-length from 10 load steps: the first arc is the one of P L^2 / EI = 3.5.
//
// Reference: Simo & Vu-Quoc (1986), the load against the horizontal and the vertical displacement
// of the load point, as digitised by a third party (refdata file header). Both are compared in
// the coordinates (displacement / L, P / P_limit) with P_limit = 18.532 EI / L^2, the published
// limit load; every converged row must lie within 0.03 of each reference polyline (from the
// origin through the digitised points). Why 0.03: the digitised peaks lie 0.7 % and 1.2 % above
// the published limit load, reading errors of about 0.012 in these coordinates; the polyline
// through points 0.06 apart (median) cuts the curved parts of the path; the model is not Simo &
// Vu-Quoc's mesh (our finer library model's peak is 0.07 % from theirs, README). So twice the
// reading error, rounded up. A model 5 % too stiff or too soft moves the peak by 0.05 and fails
// (measured: largest distances 0.044 and 0.058).
TEST(PublishedPath, LeeFrameFollowsSimoVuQuocFromTenLoadSteps) {
  const fs::path dir = scratch("lee-frame-published-path");
  const double length = 1.2, ei = 100.0;  // as write_lee_frame_model builds it
  const double scaled_limit = 18.532;     // P_limit L^2 / EI, Simo & Vu-Quoc (1986)
  const double final_load = 35.0 * ei / (length * length);  // [N], P L^2 / EI = 35
  const formats::StructurePath p =
      run_arc_length_path(write_lee_frame_model(dir), "short:end:0,-" + std::to_string(final_load),
                          dir / "structure.h5");
  const std::size_t rows = p.load_factor.size();
  ASSERT_EQ(p.node_displacement.size(), rows);

  // (c) the run ends at the full load
  EXPECT_DOUBLE_EQ(p.load_factor.back(), 1.0);

  // (a) two limit points in load (the peak, then the minimum on the unloading branch) and two in
  // the downward travel of the load point (it turns back, then forward again), from /path's
  // lists, in the published path's order: peak, turn back, turn forward, minimum
  ASSERT_EQ(p.limit_points_load.size(), 2u);
  ASSERT_EQ(p.limit_points_displacement.size(), 2u);
  auto scaled_load = [&](std::size_t row) {
    return p.load_factor[row] * final_load * length * length / ei;
  };
  const auto peak_row = static_cast<std::size_t>(p.limit_points_load[0]);
  const auto valley_row = static_cast<std::size_t>(p.limit_points_load[1]);
  EXPECT_GT(scaled_load(peak_row), 0.0);
  EXPECT_LT(scaled_load(valley_row), 0.0);
  const auto turn_back_row = static_cast<std::size_t>(p.limit_points_displacement[0]);
  const auto turn_forward_row = static_cast<std::size_t>(p.limit_points_displacement[1]);
  EXPECT_LT(peak_row, turn_back_row);
  EXPECT_LT(turn_back_row, turn_forward_row);
  EXPECT_LT(turn_forward_row, valley_row);
  EXPECT_GT(p.characteristic_displacement[turn_back_row],
            p.characteristic_displacement[turn_forward_row]);

  // (b) every converged row on the published path
  const Table table = read_table(refdata_dir() + "/lee_frame_dead_load_path_simo_vu_quoc.csv");
  const double reference_length = 120.0;  // [in]; the file's loads are P L^2 / EI already
  const auto horizontal = reference_curve(table, "horizontal", reference_length, scaled_limit);
  const auto vertical = reference_curve(table, "vertical", reference_length, scaled_limit);
  ASSERT_EQ(horizontal.size(), 1u + 86u);  // the origin and the digitised points
  ASSERT_EQ(vertical.size(), 1u + 65u);
  const double tolerance = 0.03;
  double worst_horizontal = 0.0, worst_vertical = 0.0;
  std::size_t worst_horizontal_row = 0, worst_vertical_row = 0;
  for (std::size_t r = 0; r < rows; ++r) {
    const double load = scaled_load(r) / scaled_limit;
    const double u = p.node_displacement[r].x() / length;   // away from the column
    const double v = -p.node_displacement[r].y() / length;  // downward, along the load
    const double dh = distance_to_polyline({u, load}, horizontal);
    const double dv = distance_to_polyline({v, load}, vertical);
    EXPECT_LT(dh, tolerance) << "row " << r << ": u/L " << u << ", P/P_limit " << load;
    EXPECT_LT(dv, tolerance) << "row " << r << ": v/L " << v << ", P/P_limit " << load;
    if (dh > worst_horizontal) {
      worst_horizontal = dh;
      worst_horizontal_row = r;
    }
    if (dv > worst_vertical) {
      worst_vertical = dv;
      worst_vertical_row = r;
    }
  }
  std::cout << "[Lee frame vs Simo & Vu-Quoc] " << rows - 1 << " steps; limit rows load "
            << peak_row << " (P L^2/EI " << scaled_load(peak_row) << "), " << valley_row << " ("
            << scaled_load(valley_row) << "), displacement " << turn_back_row << ", "
            << turn_forward_row << "; largest distance to the published path: horizontal "
            << worst_horizontal << " (row " << worst_horizontal_row << "), vertical "
            << worst_vertical << " (row " << worst_vertical_row << ")\n";
}

// The shallow two-bar (von Mises) truss loaded through a soft spring, the textbook example of a
// path with limit points in load and in displacement (Crisfield 1991, Non-linear Finite Element
// Analysis of Solids and Structures, vol. 1, the shallow truss with a spring in the arc-length
// chapter), with its exact path for the strain measure of the beam element. Pinned bars under
// end forces stay straight and carry only an axial force; for a geometrically exact beam
// (Reissner, Simo) the axial strain of a straight bar is its stretch minus one, so with the
// apex moved down by w the bars of length l(w) = sqrt(a^2 + (h - w)^2) carry the compression
// EA (1 - l / l0), l0 = l(0), and the vertical equilibrium of the apex gives the load
//     P(w) = 2 EA (1 - l(w) / l0) (h - w) / l(w)
// (a snap-through: P rises to a maximum, falls through zero at w = h, has a minimum and rises
// again on the inverted branch). The spring bar carries P and shortens by P L_s / EA_s exactly
// (the same strain measure), so the load point moves down by
//     Delta = w + P(w) L_s / EA_s,
// which turns back wherever dP/dw < -EA_s / L_s: with EA_s / L_s = 500 N/m against the steepest
// softening slope of 993 N/m the load point snaps back. Here a = 1 m, h = 0.1 m, EA = 1e5 N:
// P_max = 38.11 N; loaded to 1.5 P_max on the inverted branch with --arc-length from 10 load
// steps. Each converged row (Delta, P) gives w = Delta - P L_s / EA_s and must satisfy
// P = P(w): |P - P(w)| / P_max bounds its distance to the exact path in (w, P / P_max). The
// arc-length solver converges the residual to 1e-9 relative; the rows were measured within 9e-8
// P_max of the exact path, and the tolerance is 1e-6 P_max. What it tells apart: Green's strain in
// the bars would move the path by up to 1.7e-3 P_max, bars 5 % stiffer by 0.07 P_max (measured: the
// test fails), and a torsional stiffness of 1 N m/rad in the hinges by 0.028 P_max (measured: it
// failed while tfmb-beam gave a revolute joint the example's stray revolute_spring stiffness).
TEST(PublishedPath, ShallowTrussWithSpringSnapsThroughAndBack) {
  const fs::path dir = scratch("truss-with-spring-path");
  const TrussWithSpring t;
  const double l0 = std::hypot(t.half_span, t.rise);
  auto exact_load = [&](double w) {
    const double l = std::hypot(t.half_span, t.rise - w);
    return 2.0 * t.bar_ea * (1.0 - l / l0) * (t.rise - w) / l;
  };
  // the limit load of the exact path (at w = h (1 - 1/sqrt(3)) in the shallow limit; found here
  // by a fine scan, to 1e-9 relative)
  double limit_load = 0.0;
  for (int i = 0; i <= 200000; ++i)
    limit_load = std::max(limit_load, exact_load(t.rise * i / 200000.0));
  const double final_load = 1.5 * limit_load;
  const formats::StructurePath p =
      run_arc_length_path(write_truss_with_spring_model(dir, t),
                          "spring:end:0,-" + std::to_string(final_load), dir / "structure.h5");
  const std::size_t rows = p.load_factor.size();
  ASSERT_EQ(p.node_displacement.size(), rows);
  EXPECT_DOUBLE_EQ(p.load_factor.back(), 1.0);
  ASSERT_EQ(p.limit_points_load.size(), 2u);
  ASSERT_EQ(p.limit_points_displacement.size(), 2u);
  const auto peak_row = static_cast<std::size_t>(p.limit_points_load[0]);
  const auto valley_row = static_cast<std::size_t>(p.limit_points_load[1]);
  const auto turn_back_row = static_cast<std::size_t>(p.limit_points_displacement[0]);
  const auto turn_forward_row = static_cast<std::size_t>(p.limit_points_displacement[1]);
  EXPECT_LT(peak_row, turn_back_row);
  EXPECT_LT(turn_back_row, turn_forward_row);
  EXPECT_LT(turn_forward_row, valley_row);

  double worst = 0.0;
  std::size_t worst_row = 0;
  for (std::size_t r = 0; r < rows; ++r) {
    const double load = p.load_factor[r] * final_load;
    const double travel = -p.node_displacement[r].y();  // downward, along the load
    const double w = travel - load * t.spring_length / t.spring_ea;
    const double error = std::abs(load - exact_load(w)) / limit_load;
    EXPECT_LT(error, 1e-6) << "row " << r << ": w " << w << ", P " << load;
    if (error > worst) {
      worst = error;
      worst_row = r;
    }
  }
  std::cout << "[truss with spring] " << rows - 1 << " steps, limit load " << limit_load
            << " N; limit rows load " << peak_row << " (P/P_max "
            << p.load_factor[peak_row] * final_load / limit_load << "), " << valley_row << " ("
            << p.load_factor[valley_row] * final_load / limit_load << "), displacement "
            << turn_back_row << ", " << turn_forward_row << "; largest |P - P(w)| / P_max " << worst
            << " (row " << worst_row << ")\n";
}
