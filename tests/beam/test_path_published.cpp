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
  beam::Options o;
  o.model = write_lee_frame_model(dir);
  o.point_loads = {"short:end:0,-" + std::to_string(final_load)};
  o.dead_loads = true;
  o.arc_length = true;
  o.load_steps = 10;
  o.output = dir / "structure.h5";
  const Logger log("tfmb-beam", Verbosity::quiet);
  ASSERT_EQ(beam::run(o, log), 0);

  const formats::Structure s = formats::read_structure(o.output);
  ASSERT_TRUE(s.path.has_value());
  const formats::StructurePath& p = *s.path;
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
