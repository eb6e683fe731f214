// Model building: sections against closed-form values, --set overrides, the STEP path against
// the CSV it was written from, the domain loop.
#include <gtest/gtest.h>

#include <cmath>

#include "run_tool.hpp"
#include "tfmb-input/case_file.hpp"
#include "tfmb-input/model_build.hpp"
#include "tfmb/common/polyline.hpp"

using namespace tfmb::input;
using tfmb::geometry::distance_to;

TEST(Section, RectangleMatchesClosedForm) {
  const double t = 0.003, b = 1.0, e = 113.76e9, nu = 0.31, rho = 4430.0;
  const Section s = rectangle_section(t, b, e, nu, rho);
  const double g = e / (2 * (1 + nu));
  EXPECT_DOUBLE_EQ(s.stiffness(0, 0), e * b * t);
  EXPECT_DOUBLE_EQ(s.stiffness(1, 1), 5.0 / 6.0 * g * b * t);
  EXPECT_DOUBLE_EQ(s.stiffness(5, 5), e * b * t * t * t / 12.0);
  EXPECT_DOUBLE_EQ(s.stiffness(4, 4), e * t * b * b * b / 12.0);
  // Thin strip: J -> b t^3 / 3 (1 - 0.63 t/b) (Roark), within 0.1 %.
  EXPECT_NEAR(s.stiffness(3, 3) / g, b * t * t * t / 3.0 * (1 - 0.63 * t / b), 1e-3 * b * t * t * t / 3.0);
  EXPECT_DOUBLE_EQ(s.mass(0, 0), rho * b * t);
}

TEST(CaseFile, SetOverridesByTableAndByNamedElement) {
  const auto spec = read_case(std::filesystem::path(TFMB_SOURCE_DIR) / "cases/simple-nozzle/case.toml",
                              {"flow.nozzle_pressure_ratio=5.5", "flap.upper_2.thickness=0.004",
                               "joint.upper_12.kind=revolute"});
  EXPECT_DOUBLE_EQ(spec.settings.flow.nozzle_pressure_ratio, 5.5);
  EXPECT_DOUBLE_EQ(spec.flaps[1].flap.thickness, 0.004);
  EXPECT_EQ(spec.joints[0].joint.kind, "revolute");
  EXPECT_NE(spec.resolved_toml.find("5.5"), std::string::npos);
}

TEST(Geometry, StepCurvesMatchTheCsvTheyWereWrittenFrom) {
  const auto dir = std::filesystem::path(TFMB_SOURCE_DIR) / "cases/simple-nozzle";
  const auto csv = read_geometry(dir / "nozzle.csv", 1.0, 0);
  const auto step = read_geometry(dir / "nozzle.step", 1.0, 201);
  ASSERT_EQ(step.size(), csv.size());
  // The STEP holds splines through the CSV points: every CSV point lies on the sampled spline
  // within the chord error of 201 samples (curvature radius >= 0.1 m, spacing 1.3 mm: < 5 um).
  for (std::size_t c = 0; c < csv.size(); ++c) {
    const auto& sampled = step[c].points;
    for (const auto& p : csv[c].points) EXPECT_LT(distance_to(sampled, p), 5e-6) << csv[c].name;
  }
}

TEST(Model, SimpleNozzleDomainIsAClosedCounterClockwiseLoop) {
  const auto spec = read_case(std::filesystem::path(TFMB_SOURCE_DIR) / "cases/simple-nozzle/case.toml", {});
  const auto curves = read_geometry(spec.geometry.file, spec.geometry.scale, spec.geometry.curve_samples);
  std::ostringstream sink;
  const tfmb::Logger log("test", tfmb::Verbosity::quiet, sink);
  const Model model = build_model(spec, curves, log);
  ASSERT_EQ(model.flaps.size(), 6u);
  tfmb::geometry::Polyline loop;
  for (std::size_t i = 0; i < model.domain.boundaries.size(); ++i) {
    const auto& a = model.domain.boundaries[i];
    const auto& b = model.domain.boundaries[(i + 1) % model.domain.boundaries.size()];
    EXPECT_LT((a.points.back() - b.points.front()).norm(), 1e-12) << a.name << " -> " << b.name;
    loop.insert(loop.end(), a.points.begin(), a.points.end() - 1);
  }
  EXPECT_GT(tfmb::geometry::signed_area(loop), 0.0);
  // Beam nodes: elements + 1, ends exactly at the joints.
  for (const auto& f : model.flaps) EXPECT_EQ(f.reference_curve.size(), static_cast<std::size_t>(f.elements) + 1);
  for (const auto& j : model.joints) {
    const Flap* a = model.find_flap(j.flap_a);
    const auto& end = j.end_a == "start" ? a->reference_curve.front() : a->reference_curve.back();
    EXPECT_LT((end - j.point).norm(), 1e-12);
  }
  // Walls are half a thickness from the reference line.
  for (const auto& f : model.flaps) {
    for (const auto& p : f.inner_wall) EXPECT_NEAR(distance_to(f.reference_geometry, p), 0.5 * f.thickness, 1e-6);
  }
}

TEST(Geometry, GeoFileCurvesAreNamedByTheirPhysicalGroup) {
  const auto dir = tfmb::test::scratch_dir("input-geo");
  tfmb::test::write_text(dir / "two.geo",
                         "Point(1) = {0, 0.5, 0};\nPoint(2) = {1, 0.5, 0};\nPoint(3) = {2, 0.6, 0};\n"
                         "Line(1) = {1, 2};\nLine(2) = {2, 3};\n"
                         "Physical Curve(\"first\") = {1};\nPhysical Curve(\"second\") = {2};\n");
  const auto curves = read_geometry(dir / "two.geo", 0.5, 16);
  ASSERT_EQ(curves.size(), 2u);
  EXPECT_EQ(curves[0].name, "first");
  EXPECT_EQ(curves[1].name, "second");
  ASSERT_EQ(curves[0].points.size(), 2u);  // straight lines are not oversampled
  EXPECT_NEAR(curves[1].points.back().x(), 1.0, 1e-12);  // scale 0.5 applied
  EXPECT_NEAR(curves[1].points.back().y(), 0.3, 1e-12);
}

// Sliding supports (model 2.4): without `axis` the end slides along the flap's own direction at
// that end (the beam's end segment); a stated axis is normalised; either is written to model.h5.
TEST(Model, SlidingSupportAxisDefaultsToTheFlapDirection) {
  const auto toml = std::filesystem::path(TFMB_SOURCE_DIR) / "cases/simple-nozzle/case.toml";
  const auto spec = read_case(
      toml, {"support.upper_hinge_1.kind=sliding_pinned",
             "support.lower_hinge_1.kind=sliding_clamp", "support.lower_hinge_1.axis=[3.0, -4.0]"});
  const auto curves =
      read_geometry(spec.geometry.file, spec.geometry.scale, spec.geometry.curve_samples);
  std::ostringstream sink;
  const tfmb::Logger log("test", tfmb::Verbosity::quiet, sink);
  const Model model = build_model(spec, curves, log);
  int found = 0;
  for (const Support& s : model.supports) {
    if (s.name == "upper_hinge_1") {
      const Flap* f = model.find_flap(s.flap);
      const auto& c = f->reference_curve;
      const Point d = (c[c.size() - 1] - c[c.size() - 2]).normalized();
      EXPECT_EQ(s.kind, "sliding_pinned");
      EXPECT_NEAR((s.axis - d).norm(), 0.0, 1e-12);
      ++found;
    } else if (s.name == "lower_hinge_1") {
      EXPECT_NEAR((s.axis - Point(0.6, -0.8)).norm(), 0.0, 1e-12);
      ++found;
    } else {
      // Sliding in case.toml: the flap's direction; clamps and pins: none.
      EXPECT_EQ(s.slides(), !s.axis.isZero()) << s.name;
    }
  }
  EXPECT_EQ(found, 2);
  // A support without a name is addressed by its default name <flap>_<end>.
  const auto realistic =
      read_case(std::filesystem::path(TFMB_SOURCE_DIR) / "cases/realistic-nozzle/case.toml",
                {"support.upper_external_end.kind=sliding_pinned"});
  int sliding = 0;
  for (const auto& ss : realistic.supports)
    sliding += ss.support.kind == "sliding_pinned";
  EXPECT_EQ(sliding, 1);
}
