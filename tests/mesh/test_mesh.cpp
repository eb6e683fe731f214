// Flow mesh structure, solid mesh links and mesh deformation.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <iostream>
#include <set>

#include "run_tool.hpp"
#include "tfmb-input/case_file.hpp"
#include "tfmb-input/model_build.hpp"
#include "tfmb-mesh/mesh_tools.hpp"
#include "tfmb/common/errors.hpp"
#include "tfmb/common/polyline.hpp"
#include "tfmb/formats/files.hpp"

using namespace tfmb;

namespace {

input::Model load_case(const std::string& name, const std::vector<std::string>& overrides = {}) {
  const auto spec = input::read_case(
      std::filesystem::path(TFMB_SOURCE_DIR) / "cases" / name / "case.toml", overrides);
  std::vector<input::Curve> curves;
  if (!spec.geometry.file.empty())
    curves =
        input::read_geometry(spec.geometry.file, spec.geometry.scale, spec.geometry.curve_samples);
  static std::ostringstream sink;
  const Logger log("test", Verbosity::quiet, sink);
  return input::build_model(spec, curves, log);
}

const Logger& quiet() {
  static std::ostringstream sink;
  static const Logger log("test", Verbosity::quiet, sink);
  return log;
}

}  // namespace

TEST(FlowMesh, WallLayersHaveTheCaseFirstHeightAndGrowth) {
  const auto model = load_case("simple-nozzle");
  mesh::FlowMeshReport report;
  mesh::FlowMeshOptions options;
  options.scale = 4.0;
  const auto m = mesh::build_flow_mesh(model, options, report, quiet());
  ASSERT_GT(report.boundary_layers, 1);
  EXPECT_DOUBLE_EQ(report.first_layer_height, 4.0 * model.flow.first_cell_height);
  // The first quad on the inner wall of the throat flap: its wall-normal side is the first height.
  const auto& b = m.boundaries.at("upper_2_inner");
  const auto wall_node = b.edges(b.edges.rows() / 2, 0);
  double nearest = 1e300;
  for (Eigen::Index q = 0; q < m.quads.rows(); ++q) {
    for (int k = 0; k < 4; ++k) {
      if (m.quads(q, k) != wall_node)
        continue;
      for (int j : {(k + 1) % 4, (k + 3) % 4}) {
        const double d = (m.points.row(m.quads(q, j)) - m.points.row(wall_node)).norm();
        nearest = std::min(nearest, d);
      }
    }
  }
  // Mitred normals lengthen the first edge by 1/cos(half the wall turn), < 0.1 % on this smooth
  // wall.
  EXPECT_NEAR(nearest, report.first_layer_height, 1e-3 * report.first_layer_height);
  // Every boundary of the model's loop is in the mesh with its kind.
  for (const auto& piece : model.domain.boundaries) {
    ASSERT_TRUE(m.boundaries.count(piece.name)) << piece.name;
    EXPECT_EQ(m.boundaries.at(piece.name).kind, piece.kind);
    EXPECT_EQ(m.boundaries.at(piece.name).flap, piece.flap);
    EXPECT_EQ(m.boundaries.at(piece.name).side, piece.side);
  }
  EXPECT_GT(report.quality.min_angle, 15.0);
}

TEST(FlowMesh, FlatPlateFirstSpacingIsTheCaseValue) {
  const auto model = load_case("tmr-flatplate");
  mesh::FlowMeshReport report;
  mesh::FlowMeshOptions options;
  options.scale = 1.0;
  const auto m = mesh::build_flow_mesh(model, options, report, quiet());
  EXPECT_EQ(m.quads.rows(), (24 + 112) * 96);  // the TMR 137x97 grid's cell count
  EXPECT_NEAR(report.first_layer_height, 2e-6, 1e-12);
  // TMR (refdata/flow/tmr_flatplate_grid_family.csv): average y+ ~ 0.1 at 5e-7 on the finest
  // grid, so ~ 0.4 at 4x that spacing; our flat-plate estimate agrees within its crudeness.
  EXPECT_NEAR(report.estimated_yplus.value_or(-1.0), 0.4, 0.15);
}

TEST(SolidMesh, EveryCellLinksToItsBeamElement) {
  const auto model = load_case("realistic-nozzle");
  mesh::SolidLink link;
  const auto m = mesh::build_solid_mesh(model, link);
  ASSERT_EQ(link.cell_flap.size(), m.cell_count());
  for (std::size_t c = 0; c < link.cell_flap.size(); ++c) {
    const auto& flap = model.flaps[static_cast<std::size_t>(link.cell_flap[c])];
    const auto e = link.cell_element[c];
    ASSERT_GE(e, 0);
    ASSERT_LT(e, flap.elements);
    // The cell centre projects onto the reference line within element e's arc-length range.
    Eigen::Vector2d centre = Eigen::Vector2d::Zero();
    for (int k = 0; k < 4; ++k)
      centre += m.points.row(m.quads(static_cast<Eigen::Index>(c), k)).transpose() / 4.0;
    double s = 0.0;
    geometry::distance_to(flap.reference_geometry, centre, &s);
    const double element_length = geometry::length(flap.reference_geometry) / flap.elements;
    EXPECT_GE(s, e * element_length - 1e-9);
    EXPECT_LE(s, (e + 1) * element_length + 1e-9);
  }
  for (std::size_t i = 0; i < link.point_thickness_coordinate.size(); ++i) {
    EXPECT_LE(std::abs(link.point_thickness_coordinate[i]), 0.5 * 0.004 + 1e-12);
  }
}

namespace {

// Writes a walldisp file rotating the walls of one flap rigidly about `centre` by `angle`, with
// x0 the mesh's own wall nodes (with their ids, as tfmb-loads --mesh writes); or, with `shift`,
// translating them. The walls of `still_flap` are written too, with no displacement.
void write_rotation(const formats::Mesh& m, const std::string& flap, const Eigen::Vector2d& centre,
                    double angle, const Eigen::Vector2d& shift, const std::filesystem::path& file,
                    const std::string& still_flap = "") {
  h5::Writer w(file);
  formats::write_header(w, "walldisp", {});
  w.set_attr("/", "wall_source", "flowmesh");
  for (const auto& [name, b] : m.boundaries) {
    if (b.flap != flap && (still_flap.empty() || b.flap != still_flap))
      continue;
    const bool still = b.flap != flap;
    const Eigen::Matrix2d rotation =
        Eigen::Rotation2D<double>(still ? 0.0 : angle).toRotationMatrix();
    h5::MatrixXdR x0(b.edges.rows() + 1, 2), u(b.edges.rows() + 1, 2);
    std::vector<std::int64_t> nodes;
    for (Eigen::Index e = 0; e <= b.edges.rows(); ++e) {
      const auto node = e < b.edges.rows() ? b.edges(e, 0) : b.edges(e - 1, 1);
      const Eigen::Vector2d p = m.points.row(node).transpose();
      x0.row(e) = p.transpose();
      nodes.push_back(node);
      u.row(e) = (rotation * (p - centre) + centre - p + (still ? Eigen::Vector2d::Zero() : shift))
                     .transpose();
    }
    w.create_group("/walls/" + name);
    w.set_attr("/walls/" + name, "flap", b.flap);
    w.set_attr("/walls/" + name, "side", b.side);
    w.write("/walls/" + name + "/x0", x0, "m");
    w.write("/walls/" + name + "/displacement", u, "m");
    w.write("/walls/" + name + "/node", nodes, "1");
  }
  w.commit();
}

// The flow mesh of a model at --scale 4 (coarse: the deformation tests).
formats::Mesh coarse_flow_mesh(const input::Model& model) {
  mesh::FlowMeshReport report;
  mesh::FlowMeshOptions options;
  options.scale = 4.0;
  return mesh::build_flow_mesh(model, options, report, quiet());
}

Eigen::Vector2d joint_point(const input::Model& model, const std::string& name) {
  for (const auto& j : model.joints) {
    if (j.name == name)
      return j.point;
  }
  ADD_FAILURE() << "no joint " << name;
  return Eigen::Vector2d::Zero();
}

}  // namespace

TEST(Deform, RigidTwoDegreeRotationOfOneFlapKeepsCellsValidAndWallsExact) {
  const auto model = load_case("simple-nozzle");
  const auto m = coarse_flow_mesh(model);
  const auto dir = test::scratch_dir("deform-rotation");
  const Eigen::Vector2d hinge = joint_point(model, "upper_23");
  const double angle = 2.0 * M_PI / 180.0;
  write_rotation(m, "upper_3", hinge, angle, Eigen::Vector2d::Zero(), dir / "walldisp.h5");
  const auto walls = formats::read_walldisp(dir / "walldisp.h5").walls;
  ASSERT_EQ(walls.size(), 3u);  // inner, outer, end
  mesh::DeformReport deform_report;
  const auto moved = mesh::deform_mesh(m, walls, {}, deform_report);
  EXPECT_EQ(deform_report.quality.invalid_cells, 0u);
  EXPECT_GT(deform_report.quality.min_area, 0.0);
  EXPECT_EQ(moved.triangles, m.triangles);
  EXPECT_EQ(moved.quads, m.quads);
  const Eigen::Matrix2d rotation = Eigen::Rotation2D<double>(angle).toRotationMatrix();
  double worst = 0.0;
  std::set<std::int64_t> nodes;
  for (const auto& [name, b] : m.boundaries) {
    if (b.flap != "upper_3")
      continue;
    for (Eigen::Index e = 0; e < b.edges.rows(); ++e)
      nodes.insert({b.edges(e, 0), b.edges(e, 1)});
  }
  for (auto node : nodes) {
    const Eigen::Vector2d p = m.points.row(node).transpose();
    const Eigen::Vector2d expected = rotation * (p - hinge) + hinge;
    worst = std::max(worst, (moved.points.row(node).transpose() - expected).norm());
  }
  EXPECT_LT(worst, 1e-12) << "wall nodes must sit on the rotated wall";
  // Far-field nodes do not move.
  const auto& far = m.boundaries.at("farfield_upper");
  EXPECT_EQ((moved.points.row(far.edges(0, 0)) - m.points.row(far.edges(0, 0))).norm(), 0.0);
}

namespace {

// The nodes of a flap's wall boundaries.
std::set<std::int64_t> flap_wall_nodes(const formats::Mesh& m, const std::string& flap) {
  std::set<std::int64_t> nodes;
  for (const auto& [name, b] : m.boundaries) {
    if (b.flap != flap)
      continue;
    for (Eigen::Index e = 0; e < b.edges.rows(); ++e)
      nodes.insert({b.edges(e, 0), b.edges(e, 1)});
  }
  return nodes;
}

// Signed area of quad c (counter-clockwise positive) in `points`.
double quad_area(const formats::Mesh& m, const h5::MatrixXdR& points, Eigen::Index c) {
  double twice = 0.0;
  for (int k = 0; k < 4; ++k) {
    const auto a = m.quads(c, k), b = m.quads(c, (k + 1) % 4);
    twice += points(a, 0) * points(b, 1) - points(b, 0) * points(a, 1);
  }
  return 0.5 * twice;
}

}  // namespace

TEST(Deform, RotationsTurnTheWallLayersOfATurningFlapWithIt) {
  // upper_3 turned 30 deg about its hinge: by displacements alone, the wall-layer quads along it
  // are sheared (each node takes the displacement of the nearest wall nodes, not their turn);
  // with the rotations interpolated too (Luke, Collins & Blades 2012) the layers turn
  // rigidly, so their areas stay what they were.
  const auto model = load_case("simple-nozzle");
  const auto m = coarse_flow_mesh(model);
  const auto dir = test::scratch_dir("deform-turn");
  const Eigen::Vector2d hinge = joint_point(model, "upper_23");
  write_rotation(m, "upper_3", hinge, 30.0 * M_PI / 180.0, Eigen::Vector2d::Zero(),
                 dir / "walldisp.h5");
  const auto walls = formats::read_walldisp(dir / "walldisp.h5").walls;
  const auto on_flap = flap_wall_nodes(m, "upper_3");
  // the largest relative area change of the quads with a node on upper_3's walls, away from the
  // joint with upper_2 (held), where the turn must shear the cells whichever way
  auto worst_area_change = [&](bool rotations) {
    mesh::DeformReport deform_report;
    const auto moved = mesh::deform_mesh(m, walls, {rotations}, deform_report);
    EXPECT_EQ(deform_report.quality.invalid_cells, 0u);
    double worst = 0.0;
    int quads = 0;
    for (Eigen::Index c = 0; c < m.quads.rows(); ++c) {
      bool touches = false, near_joint = false;
      for (int k = 0; k < 4; ++k) {
        touches = touches || on_flap.count(m.quads(c, k));
        near_joint = near_joint || (m.points.row(m.quads(c, k)).transpose() - hinge).norm() < 0.05;
      }
      if (!touches || near_joint)
        continue;
      ++quads;
      const double before = quad_area(m, m.points, c);
      worst = std::max(worst, std::abs(quad_area(m, moved.points, c) / before - 1.0));
    }
    EXPECT_GT(quads, 20);
    return worst;
  };
  const double with_rotations = worst_area_change(true);
  const double without = worst_area_change(false);
  EXPECT_LT(with_rotations, 0.02);
  EXPECT_GT(without, 5.0 * with_rotations) << "the test would not tell the two apart";
  std::cout << "largest area change of upper_3's wall quads: " << with_rotations
            << " with rotations, " << without << " without\n";
}

TEST(Deform, NodeSharedByTwoFlapsTakesTheMeanOfTheirDisplacements) {
  // The inner and outer walls of upper_2 and upper_3 share a node at their joint. upper_3 turned
  // 5 deg about a point off the joint and upper_2 held: the walldisp gives the shared nodes two
  // displacements, and each takes their mean, whichever wall is read first.
  const auto model = load_case("simple-nozzle");
  const auto m = coarse_flow_mesh(model);
  const auto dir = test::scratch_dir("deform-shared");
  const Eigen::Vector2d centre(0.6, 0.0);
  const double angle = 5.0 * M_PI / 180.0;
  write_rotation(m, "upper_3", centre, angle, Eigen::Vector2d::Zero(), dir / "walldisp.h5",
                 "upper_2");
  auto walls = formats::read_walldisp(dir / "walldisp.h5").walls;
  std::set<std::int64_t> shared;
  for (auto node : flap_wall_nodes(m, "upper_3")) {
    if (flap_wall_nodes(m, "upper_2").count(node))
      shared.insert(node);
  }
  ASSERT_EQ(shared.size(), 2u);  // inner and outer corner
  const Eigen::Matrix2d rotation = Eigen::Rotation2D<double>(angle).toRotationMatrix();
  for (int order = 0; order < 2; ++order) {
    if (order == 1)
      std::reverse(walls.begin(), walls.end());
    mesh::DeformReport deform_report;
    const auto moved = mesh::deform_mesh(m, walls, {}, deform_report);
    for (auto node : shared) {
      const Eigen::Vector2d p = m.points.row(node).transpose();
      const Eigen::Vector2d expected = p + 0.5 * (rotation * (p - centre) + centre - p);
      EXPECT_LT((moved.points.row(node).transpose() - expected).norm(), 1e-12)
          << "node " << node << ", walls in order " << order;
    }
  }
}

TEST(Deform, ModelWallDisplacementMovesTheWholeFlapIncludingItsEndFace) {
  // tfmb-loads without --mesh writes one curve per model wall (<flap>_inner, <flap>_outer) and
  // no end face: the mesh's wall nodes on those curves move exactly, the end face and the
  // join nodes take the nearest curve point's displacement.
  const auto model = load_case("simple-nozzle");
  const auto m = coarse_flow_mesh(model);
  const input::Flap* flap = model.find_flap("upper_3");
  const Eigen::Vector2d hinge = joint_point(model, "upper_23");
  const double angle = 2.0 * M_PI / 180.0;
  const Eigen::Matrix2d rotation = Eigen::Rotation2D<double>(angle).toRotationMatrix();
  std::vector<mesh::WallDisplacement> walls;
  for (const auto& [side, line] :
       {std::pair{"inner", &flap->inner_wall}, std::pair{"outer", &flap->outer_wall}}) {
    mesh::WallDisplacement w;
    w.name = std::string("upper_3_") + side;
    w.flap = "upper_3";
    for (const auto& p : *line) {
      w.x0.push_back(p);
      w.displacement.push_back(rotation * (p - hinge) + hinge - p);
    }
    walls.push_back(w);
  }
  mesh::DeformReport deform_report;
  const auto moved = mesh::deform_mesh(m, walls, {}, deform_report);
  EXPECT_EQ(deform_report.quality.invalid_cells, 0u);
  EXPECT_GT(deform_report.projected_nodes, 0u);  // the end face at least
  EXPECT_LT(deform_report.largest_projection, flap->thickness);
  // The end face moved with the flap (to the accuracy of the nearest-point rule: theta * t).
  const auto& end = m.boundaries.at("upper_3_end");
  const auto node = end.edges(0, 0);
  const Eigen::Vector2d p = m.points.row(node).transpose();
  const Eigen::Vector2d expected = rotation * (p - hinge) + hinge;
  EXPECT_LT((moved.points.row(node).transpose() - expected).norm(), angle * flap->thickness);
  EXPECT_GT((moved.points.row(node) - m.points.row(node)).norm(), 0.5 * angle * 0.2);
}

TEST(Deform, FoldingDisplacementIsRefusedWithTheAdmissibleFraction) {
  const auto dir = test::scratch_dir("deform-fold");
  const auto model_file = dir / "model.h5";
  auto r = test::run_tool("tfmb-input " + std::string(TFMB_SOURCE_DIR) +
                              "/cases/simple-nozzle/case.toml -o " + model_file.string(),
                          dir);
  ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
  r = test::run_tool(
      "tfmb-mesh flow " + model_file.string() + " -o " + (dir / "flow.h5").string() + " --scale 4",
      dir);
  ASSERT_EQ(r.exit_code, 0) << r.stderr_text;
  const auto m = formats::read_mesh(h5::Reader(dir / "flow.h5"));
  // Push the last upper flap 5 cm towards the axis: the cells at its joint with the fixed flap
  // fold.
  write_rotation(m, "upper_3", Eigen::Vector2d::Zero(), 0.0, Eigen::Vector2d(0.0, -0.05),
                 dir / "walldisp.h5");
  r = test::run_tool("tfmb-mesh deform " + (dir / "flow.h5").string() + " " +
                         (dir / "walldisp.h5").string() + " -o " + (dir / "flow2.h5").string(),
                     dir);
  EXPECT_EQ(r.exit_code, 3) << r.stderr_text;
  const std::string key = "largest admissible fraction of this displacement is ";
  const auto at = r.stderr_text.find(key);
  ASSERT_NE(at, std::string::npos) << r.stderr_text;
  const double fraction = std::stod(r.stderr_text.substr(at + key.size()));
  EXPECT_GT(fraction, 0.0);
  EXPECT_LT(fraction, 1.0);
  EXPECT_FALSE(std::filesystem::exists(dir / "flow2.h5")) << "no output on refusal";
  // The reported fraction is the boundary: slightly less deforms, slightly more is refused.
  const auto walls = formats::read_walldisp(dir / "walldisp.h5").walls;
  auto scaled = [&](double f) {
    auto w = walls;
    for (auto& wall : w) {
      for (auto& u : wall.displacement)
        u *= f;
    }
    return w;
  };
  mesh::DeformReport report;
  EXPECT_NO_THROW(mesh::deform_mesh(m, scaled(0.99 * fraction), {}, report));
  EXPECT_THROW(mesh::deform_mesh(m, scaled(std::min(1.0, 1.01 * fraction)), {}, report),
               tfmb::BadInput);
}

TEST(Geometry, NparcChannelWallFollowsTheExactAreaLaw) {
  // refdata/flow/nparc_cdv_nozzle_definition.csv: A(x) [in^2] = 1.75 - 0.75 cos((0.2x - 1) pi) for
  // x < 5, 1.25 - 0.25 cos((0.2x - 1) pi) after; 2D: wall height = A per unit width. The case
  // samples it at 201 points: linear interpolation error <= A'' dx^2 / 8 = 0.296 * 0.05^2 / 8
  // = 9.3e-5 in.
  const auto model = load_case("nparc-cdv");
  mesh::FlowMeshReport report;
  const auto m = mesh::build_flow_mesh(model, {}, report, quiet());
  const auto& wall = m.boundaries.at("wall");
  const double inch = 0.0254;
  double worst = 0.0;
  for (Eigen::Index e = 0; e < wall.edges.rows(); ++e) {
    const double x = m.points(wall.edges(e, 0), 0) / inch, y = m.points(wall.edges(e, 0), 1) / inch;
    const double area = x < 5.0 ? 1.75 - 0.75 * std::cos((0.2 * x - 1.0) * M_PI)
                                : 1.25 - 0.25 * std::cos((0.2 * x - 1.0) * M_PI);
    worst = std::max(worst, std::abs(y - area));
  }
  EXPECT_LT(worst, 1e-4);
  EXPECT_EQ(m.quads.rows(), 120 * 30);
}

TEST(Geometry, BmgConicalIsAxisymmetricAboutAnAxisOnYZero) {
  // cases/bmg-conical: domain.geometry = "axisymmetric" makes the channel's lower line the axis
  // of revolution. The wall follows the contour of tests/flow/test_bmg_nozzle.cpp (throat radius
  // 0.775 in, throat arc 1.55 in, 15 deg cone; 30 deg cone cut by the 1.5955 in tube), sampled
  // at 0.01 in on the arc: chord sag dx^2 / (8 R) = 8e-6 in, so 2e-5 in covers it.
  const auto model = load_case("bmg-conical");
  EXPECT_EQ(model.geometry, "axisymmetric");
  mesh::FlowMeshReport report;
  const auto m = mesh::build_flow_mesh(model, {}, report, quiet());
  ASSERT_EQ(m.boundaries.count("axis"), 1u);
  EXPECT_EQ(m.boundaries.count("symmetry"), 0u);
  EXPECT_EQ(m.boundaries.at("axis").kind, "axis");
  for (Eigen::Index e = 0; e < m.boundaries.at("axis").edges.rows(); ++e)
    EXPECT_EQ(m.points(m.boundaries.at("axis").edges(e, 0), 1), 0.0);
  const double inch = 0.0254, rt = 0.775, rc = 1.55, tube = 1.5955;
  const double div = 15.0 * M_PI / 180.0, conv = 30.0 * M_PI / 180.0;
  auto radius = [&](double x) {  // [in], tests/flow/test_bmg_nozzle.cpp wall_radius_in
    const double xa = x >= 0.0 ? rc * std::sin(div) : -rc * std::sin(conv);
    if ((x >= 0.0 && x <= xa) || (x < 0.0 && x >= xa))
      return rt + rc - std::sqrt(rc * rc - x * x);
    if (x >= 0.0)
      return rt + rc * (1.0 - std::cos(div)) + (x - xa) * std::tan(div);
    return std::min(rt + rc * (1.0 - std::cos(conv)) + (xa - x) * std::tan(conv), tube);
  };
  const auto& wall = m.boundaries.at("wall");
  double worst = 0.0;
  for (Eigen::Index e = 0; e < wall.edges.rows(); ++e) {
    const double x = m.points(wall.edges(e, 0), 0) / inch, y = m.points(wall.edges(e, 0), 1) / inch;
    worst = std::max(worst, std::abs(y - radius(x)));
  }
  EXPECT_LT(worst, 2e-5);
  EXPECT_EQ(m.quads.rows(), 140 * 80);
  // The wall layer's first height is the case's 5e-7 m at the throat, the narrowest column.
  EXPECT_NEAR(report.first_layer_height, 5e-7, 1e-12);
}

TEST(Geometry, AxisymmetricNeedsAChannelDomain) {
  EXPECT_THROW(load_case("simple-nozzle", {"domain.geometry=axisymmetric"}), BadInput);
  EXPECT_THROW(load_case("bmg-conical", {"depth=2"}), BadInput);
}

// Model format 2.7: the reader refuses an axis that the geometry does not turn about, and an
// axisymmetric model without an axis.
TEST(Geometry, ModelReaderChecksTheAxisAgainstTheGeometry) {
  const auto dir = tfmb::test::scratch_dir("model-axis");
  const auto good = load_case("bmg-conical");
  formats::write_model(good, dir / "good.h5", "test", {});
  EXPECT_EQ(formats::read_model(dir / "good.h5").geometry, "axisymmetric");
  auto planar = good;
  planar.geometry = "planar";
  formats::write_model(planar, dir / "planar.h5", "test", {});
  EXPECT_THROW(formats::read_model(dir / "planar.h5"), BadInput);
  auto no_axis = good;
  for (auto& b : no_axis.domain.boundaries) {
    if (b.kind == "axis")
      b.kind = "symmetry";
  }
  formats::write_model(no_axis, dir / "no_axis.h5", "test", {});
  EXPECT_THROW(formats::read_model(dir / "no_axis.h5"), BadInput);
}

TEST(Geometry, NasaB1ThroatAndExitHeights) {
  // refdata/flow/mason_tp1704_B1_geometry_sonicline.csv: h_t 1.37 cm, h_e 2.46 cm (half-heights),
  // exit/throat 1.796. The model's inner walls (drawn as `reference = "inner"`, moved to the mid
  // line and back) must reproduce them to the rounding of b1.csv (1e-8 m) plus the arc chord
  // sag of the throat (r_c (1 - cos(0.87 deg)) = 7.8e-7 m).
  const auto model = load_case("nasa-2dcd");
  double throat = 1e300, exit_height = 0.0;
  for (const auto& b : model.domain.boundaries) {
    if (b.flap.rfind("upper", 0) != 0 || b.side != "inner")
      continue;
    for (const auto& p : b.points)
      throat = std::min(throat, p.y());
    if (b.flap == "upper_divergent")
      exit_height = b.points.front().y();  // loop runs exit -> throat
  }
  EXPECT_NEAR(throat, 0.0137, 1e-6);
  EXPECT_NEAR(exit_height, 0.0246, 1e-7);
  EXPECT_NEAR(exit_height / throat, 1.796, 1e-3);
}

TEST(FlowMesh, CellsPerCircleRefinesTheThroatArcOnly) {
  // B1's throat is a circular arc of radius r_c = 6.8 mm (refdata geometry) between straight
  // flaps. With mesh.cells_per_circle = N the wall spacing on the arc must be at most
  // 2 pi r_c / N (plus the chord sag of the 8-segment arc in b1.csv), while the straight flap far
  // from the throat keeps mesh.wall_size (1 mm).
  const int cells = 120;
  const double r_c = 0.0068, limit = 2.0 * M_PI * r_c / cells;
  mesh::FlowMeshOptions options;
  options.scale = 1.0;
  auto wall_x = [&](const std::vector<std::string>& overrides) {
    const auto model = load_case("nasa-2dcd", overrides);
    mesh::FlowMeshReport report;
    const auto m = mesh::build_flow_mesh(model, options, report, quiet());
    const auto& b = m.boundaries.at("upper_divergent_inner");
    std::set<double> xs;
    for (Eigen::Index e = 0; e < b.edges.rows(); ++e) {
      for (int k = 0; k < 2; ++k)
        xs.insert(m.points(b.edges(e, k), 0));
    }
    return std::vector<double>(xs.begin(), xs.end());
  };
  const auto plain = wall_x({"mesh.cells_per_circle=0"});
  const auto refined = wall_x({"mesh.cells_per_circle=" + std::to_string(cells)});
  // Divergent arc: 0 <= x <= r_c sin(10.85 deg) = 1.28 mm (intervals wholly on it).
  const double arc_end = r_c * std::sin(10.85 * M_PI / 180.0);
  double widest_on_arc = 0.0, widest_plain = 0.0;
  for (std::size_t i = 1; i < refined.size() && refined[i] <= arc_end; ++i)
    widest_on_arc = std::max(widest_on_arc, refined[i] - refined[i - 1]);
  for (std::size_t i = 1; i < plain.size() && plain[i - 1] < arc_end; ++i)
    widest_plain = std::max(widest_plain, plain[i] - plain[i - 1]);
  EXPECT_LT(widest_on_arc, 1.05 * limit);
  EXPECT_GT(widest_plain, 2.0 * limit);  // the option is what refined it
  // Downstream of the arc the spacing grades back to wall_size (1 mm) at rate 0.25.
  const double last = refined[refined.size() - 2] - refined[refined.size() - 3];
  EXPECT_NEAR(last, plain[plain.size() - 2] - plain[plain.size() - 3], 0.05e-3);
  EXPECT_GT(refined.size(), plain.size());
  EXPECT_LT(refined.size(), plain.size() + 20);
}

TEST(FlowMesh, EndCellsResolveTheFlapEndFaces) {
  // mesh.end_cells = N: each flap end face (B1's 5 mm thick trailing edges) gets at least
  // N / scale edges (at least 2); the default keeps the earlier 2.
  mesh::FlowMeshOptions options;
  options.scale = 4.0;
  auto end_edges = [&](const std::vector<std::string>& overrides) {
    const auto model = load_case("nasa-2dcd", overrides);
    mesh::FlowMeshReport report;
    const auto m = mesh::build_flow_mesh(model, options, report, quiet());
    std::size_t fewest = 1000000;
    int faces = 0;
    for (const auto& [name, b] : m.boundaries) {
      if (name.size() < 4 || name.compare(name.size() - 4, 4, "_end") != 0)
        continue;
      fewest = std::min(fewest, static_cast<std::size_t>(b.edges.rows()));
      ++faces;
    }
    EXPECT_GT(faces, 0);
    return fewest;
  };
  EXPECT_EQ(end_edges({}), 2u);
  EXPECT_GE(end_edges({"mesh.end_cells=40"}), 10u);
  EXPECT_EQ(end_edges({"mesh.end_cells=10"}), 2u);
}

TEST(FlowMesh, LayersStopBeforeTheyFoldOnAConcaveWall) {
  // The outer face of B1's flaps is the 6.8 mm throat arc offset 5 mm towards its centre: a
  // concave wall of 1.8 mm radius for the external flow. Resolved by cells_per_circle on the
  // coarse (scale 4) mesh at NPR 2.412 (thicker first layer), 30 layers would be 1.9 mm thick and
  // cross there; the stack must stop below half the crossing height and the mesh stay valid.
  const auto model = load_case("nasa-2dcd", {"flow.nozzle_pressure_ratio=2.412"});
  mesh::FlowMeshReport report;
  mesh::FlowMeshOptions options;
  options.scale = 4.0;
  const auto m = mesh::build_flow_mesh(model, options, report, quiet());
  EXPECT_GT(report.boundary_layers, 10);
  EXPECT_LT(report.boundary_layers, model.mesh.max_layers);
  EXPECT_GT(report.quality.min_angle, 10.0);
  for (Eigen::Index q = 0; q < m.quads.rows(); ++q) {
    const Eigen::Vector2d a = m.points.row(m.quads(q, 0)).head<2>(),
                          b = m.points.row(m.quads(q, 1)).head<2>(),
                          c = m.points.row(m.quads(q, 2)).head<2>(),
                          d = m.points.row(m.quads(q, 3)).head<2>();
    const double area = 0.5 * ((c - a).x() * (d - b).y() - (c - a).y() * (d - b).x());
    ASSERT_GT(area, 0.0) << "quad " << q;
  }
}
