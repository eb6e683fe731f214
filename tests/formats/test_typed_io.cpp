// The typed readers and writers of formats/: what a writer writes its reader reads back, and the
// checks the schema cannot make are made (one located line per problem).
#include <gtest/gtest.h>
#include <hdf5.h>

#include <cmath>
#include <filesystem>
#include <numbers>

#include "tfmb/common/errors.hpp"
#include "tfmb/formats/flowmesh.hpp"
#include "tfmb/formats/loads.hpp"
#include "tfmb/formats/material_db.hpp"
#include "tfmb/formats/materials.hpp"
#include "tfmb/formats/solidmesh.hpp"
#include "tfmb/formats/strain.hpp"
#include "tfmb/formats/structure.hpp"

namespace fs = std::filesystem;
using namespace tfmb;

namespace {

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::path(TFMB_BINARY_DIR) / "test-typed-io";
  fs::create_directories(dir);
  return dir / name;
}

formats::MaterialsFlap materials_flap(std::size_t elements) {
  formats::MaterialsFlap f;
  f.name = "upper";
  f.material = f.material_given = "Ti-6Al-4V";
  f.thickness = 0.01;
  f.width = 1.0;
  f.reference_temperature = f.stress_free_temperature = 294.0;
  f.shear_modulus_basis = f.allowable_strain_basis = "test";
  formats::MaterialElements& e = f.elements;
  for (std::size_t k = 0; k < elements; ++k) {
    for (auto* v : {&e.temperature, &e.youngs_modulus, &e.shear_modulus, &e.density,
                    &e.yield_strength, &e.ultimate_strength})
      v->push_back(400.0 + static_cast<double>(k));
    for (auto* v : {&e.delta_temperature, &e.thermal_strain, &e.thermal_strain_inner,
                    &e.thermal_strain_outer, &e.thermal_curvature})
      v->push_back(1e-3 * static_cast<double>(k));
    e.poisson_ratio.push_back(0.3);
    e.thermal_expansion.push_back(9e-6);
    e.allowable_strain.push_back(5e-3);
    e.section_stiffness.push_back(Eigen::Matrix<double, 6, 6>::Identity() *
                                  (1e6 + static_cast<double>(k)));
    e.section_mass.push_back(Eigen::Matrix<double, 6, 6>::Identity());
    e.clamped.push_back(k % 2);
  }
  return f;
}

}  // namespace

TEST(TypedIo, MaterialsRoundTripAndASingularSectionIsRefused) {
  formats::Header header;
  header.creator = "test";
  const fs::path file = scratch("materials.h5");
  formats::write_materials(file, header, {materials_flap(3)}, {});
  const formats::Materials back = formats::read_materials(file);
  ASSERT_EQ(back.flaps.size(), 1u);
  const formats::MaterialsFlap& f = back.flaps[0];
  EXPECT_EQ(f.elements.size(), 3u);
  EXPECT_EQ(f.elements.section_stiffness[2](5, 5), 1e6 + 2.0);
  EXPECT_EQ(f.elements.clamped, (std::vector<std::int64_t>{0, 1, 0}));
  EXPECT_TRUE(f.has_strength);

  formats::MaterialsFlap singular = materials_flap(3);
  singular.elements.section_stiffness[1](3, 3) = 0.0;
  formats::write_materials(file, header, {singular}, {});
  try {
    formats::read_materials(file);
    FAIL() << "a singular section was read";
  } catch (const BadInput& e) {
    EXPECT_NE(
        std::string(e.what()).find("/flaps/upper/section_stiffness: element 1: diagonal entry 3"),
        std::string::npos)
        << e.what();
  }
}

namespace {

// A loads file's frame with no flap yet, and a flap "lower" of width 1 m without nodes.
formats::Loads empty_loads() {
  formats::Loads loads;
  loads.header.creator = "test";
  loads.method = "conservative";
  loads.load_basis = "flap width";
  return loads;
}

formats::LoadsFlap lower_flap() {
  formats::LoadsFlap f;
  f.name = "lower";
  f.width = 1.0;
  return f;
}

}  // namespace

TEST(TypedIo, LoadsRoundTripAndAReversedArcLengthIsRefused) {
  formats::Loads loads = empty_loads();
  formats::LoadsFlap f = lower_flap();
  f.traces = {"lower_inner", "lower_outer"};
  f.s = {0.0, 0.1, 0.2};
  for (int i = 0; i < 3; ++i) {
    f.distributed_force.emplace_back(1.0 * i, 2.0, 0.0);
    f.distributed_moment.emplace_back(0.0, 0.0, 0.5);
    f.nodal_force.emplace_back(0.1 * i, 0.2, 0.0);
    f.nodal_moment.emplace_back(0.0, 0.0, 0.05 * i);
  }
  f.total_force = f.mapped_force = Eigen::Vector3d(0.3, 0.6, 0.0);
  f.total_moment = f.mapped_moment = Eigen::Vector3d(0.0, 0.0, 0.15);
  loads.flaps = {f};
  const fs::path file = scratch("loads.h5");
  formats::write_loads(file, loads, {});
  const formats::Loads back = formats::read_loads(file);
  ASSERT_EQ(back.flaps.size(), 1u);
  EXPECT_EQ(back.flaps[0].traces, f.traces);
  EXPECT_EQ(back.flaps[0].nodal_force[2], f.nodal_force[2]);
  EXPECT_EQ(back.flaps[0].mapped_moment, f.mapped_moment);
  EXPECT_EQ(back.method, "conservative");

  loads.flaps[0].s = {0.0, 0.2, 0.1};
  formats::write_loads(file, loads, {});
  EXPECT_THROW(
      {
        try {
          formats::read_loads(file);
        } catch (const BadInput& e) {
          EXPECT_NE(std::string(e.what()).find("/flaps/lower/s: arc length decreases at node 2"),
                    std::string::npos)
              << e.what();
          throw;
        }
      },
      BadInput);
}

// With positions, an arc-length step lies between the nodes' distance and pi/2 times it (an arc
// of up to a half turn): the mutation suite's 1e300 m arc length changed nodal-forces' lumping.
TEST(TypedIo, LoadsArcLengthMustFitThePositions) {
  formats::Loads loads = empty_loads();
  formats::LoadsFlap f = lower_flap();
  f.traces = {"lower_inner"};
  // a quarter circle of radius 0.1 m in two steps: arc 0.0785 m per chord 0.0765 m
  const double r = 0.1, step = 0.25 * std::numbers::pi;
  for (int i = 0; i < 3; ++i) {
    f.s.push_back(r * step * i);
    f.position.emplace_back(r * std::cos(step * i), r * std::sin(step * i));
    f.distributed_force.emplace_back(0.0, 0.0, 0.0);
    f.distributed_moment.emplace_back(0.0, 0.0, 0.0);
    f.nodal_force.emplace_back(0.0, 0.0, 0.0);
    f.nodal_moment.emplace_back(0.0, 0.0, 0.0);
  }
  f.total_force = f.mapped_force = f.total_moment = f.mapped_moment = Eigen::Vector3d::Zero();
  loads.flaps = {f};
  const fs::path file = scratch("loads_arc.h5");
  formats::write_loads(file, loads, {});
  EXPECT_EQ(formats::read_loads(file).flaps[0].s[2], f.s[2]);
  for (const double last_step : {0.05, 1e300}) {  // shorter than the chord; absurdly long
    loads.flaps[0].s[2] = f.s[1] + last_step;
    formats::write_loads(file, loads, {});
    try {
      formats::read_loads(file);
      ADD_FAILURE() << "arc length step to " << loads.flaps[0].s[2] << " m taken";
    } catch (const BadInput& e) {
      EXPECT_NE(std::string(e.what()).find("/flaps/lower/s: node 2: an arc length step of"),
                std::string::npos)
          << e.what();
    }
  }
}

// tfmb-matmap and tfmb-heat resolve a model's material name by the one rule of the database
// reader (they had two: heat kept '-' and '_' significant, so "Ti_6Al_4V" failed there only).
TEST(TypedIo, MaterialNamesResolveByOneRule) {
  EXPECT_TRUE(formats::same_material_name("Ti-6Al-4V", "ti_6al 4v"));
  EXPECT_FALSE(formats::same_material_name("Ti-6Al-4V", "Ti-6Al-4V-ELI"));
  const formats::MaterialDatabase db =
      formats::read_material_db(fs::path(TFMB_SOURCE_DIR) / "data" / "materials-db.h5");
  ASSERT_FALSE(db.materials.empty());
  const formats::DatabaseMaterial& first = db.materials.front();
  std::string spelled = first.name;
  for (char& c : spelled)
    if (c == '-')
      c = '_';
  EXPECT_EQ(db.find(spelled), &first);
  EXPECT_EQ(db.find("no such material"), nullptr);
}

// A database with a negative Young's modulus or conductivity passed every stage before; the
// reader refuses it with the row (a copy of the project's database with one value changed).
TEST(TypedIo, AMaterialDatabaseWithANegativeModulusIsRefused) {
  const fs::path copy = scratch("materials-db-negative.h5");
  fs::copy_file(fs::path(TFMB_SOURCE_DIR) / "data" / "materials-db.h5", copy,
                fs::copy_options::overwrite_existing);
  {
    const hid_t file = H5Fopen(copy.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
    ASSERT_GE(file, 0);
    const hid_t dataset = H5Dopen2(file, "/materials/Ti-6Al-4V/youngs_modulus/value", H5P_DEFAULT);
    ASSERT_GE(dataset, 0);
    const hid_t space = H5Dget_space(dataset);
    std::vector<double> values(static_cast<std::size_t>(H5Sget_simple_extent_npoints(space)));
    H5Dread(dataset, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data());
    values[1] = -values[1];
    H5Dwrite(dataset, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data());
    H5Sclose(space);
    H5Dclose(dataset);
    H5Fclose(file);
  }
  try {
    formats::read_material_db(copy);
    FAIL() << "a negative Young's modulus was read";
  } catch (const BadInput& e) {
    EXPECT_NE(std::string(e.what()).find("/materials/Ti-6Al-4V/youngs_modulus/value: row 1"),
              std::string::npos)
        << e.what();
  }
}

// A solid mesh whose nodes all sit on the reference line (through-thickness coordinate 0) gave a
// through-thickness temperature difference of 0 instead of refusing the file.
TEST(TypedIo, ASolidMeshWithoutThicknessIsRefused) {
  formats::SolidMesh solid;
  solid.header.creator = "test";
  solid.mesh.points.resize(4, 2);
  solid.mesh.points << 0.0, -0.005, 1.0, -0.005, 1.0, 0.005, 0.0, 0.005;
  solid.mesh.quads.resize(1, 4);
  solid.mesh.quads << 0, 1, 2, 3;
  solid.flap_names = {"upper"};
  solid.cell_flap = {0};
  solid.cell_element = {0};
  solid.point_thickness_coordinate = {-0.005, -0.005, 0.005, 0.005};
  auto face = [](const char* kind, const char* side, std::int64_t a, std::int64_t b) {
    formats::Boundary boundary;
    boundary.kind = kind;
    boundary.flap = "upper";
    boundary.side = side;
    boundary.edges.resize(1, 2);
    boundary.edges << a, b;
    return boundary;
  };
  solid.mesh.boundaries["upper_inner"] = face("solid_inner", "inner", 0, 1);
  solid.mesh.boundaries["upper_outer"] = face("solid_outer", "outer", 3, 2);
  solid.mesh.boundaries["upper_start"] = face("solid_end", "end", 0, 3);
  solid.mesh.boundaries["upper_end"] = face("solid_end", "end", 1, 2);
  const fs::path file = scratch("solidmesh.h5");
  formats::write_solidmesh(file, solid, {});
  EXPECT_EQ(formats::read_solidmesh(file).point_thickness_coordinate[2], 0.005);
  solid.point_thickness_coordinate = {0.0, 0.0, 0.0, 0.0};
  formats::write_solidmesh(file, solid, {});
  EXPECT_THROW(formats::read_solidmesh(file), BadInput);
}

// The flow mesh's quality report round-trips with what is absent staying absent (an imported
// mesh carries none), and a mesh without boundaries is refused (nothing to apply conditions to).
TEST(TypedIo, FlowMeshRoundTripAndAMeshWithoutBoundariesIsRefused) {
  formats::FlowMesh mesh;
  mesh.header.creator = "test";
  mesh.mesh.points.resize(4, 2);
  mesh.mesh.points << 0.0, 0.0, 1.0, 0.0, 1.0, 1.0, 0.0, 1.0;
  mesh.mesh.quads.resize(1, 4);
  mesh.mesh.quads << 0, 1, 2, 3;
  formats::Boundary wall;
  wall.kind = "wall";
  wall.flap = "upper";
  wall.side = "inner";
  wall.edges.resize(1, 2);
  wall.edges << 2, 3;
  mesh.mesh.boundaries["upper_inner"] = wall;
  formats::Boundary farfield;
  farfield.kind = "farfield";
  farfield.edges.resize(3, 2);
  farfield.edges << 3, 0, 0, 1, 1, 2;
  mesh.mesh.boundaries["farfield"] = farfield;
  mesh.quality.min_angle = 90.0;
  mesh.quality.boundary_layers = 3;
  const fs::path file = scratch("flowmesh.h5");
  formats::write_flowmesh(file, mesh, {});
  const formats::FlowMesh back = formats::read_flowmesh(file);
  EXPECT_EQ(back.mesh.points, mesh.mesh.points);
  EXPECT_EQ(back.mesh.boundaries.at("upper_inner").side, "inner");
  EXPECT_EQ(back.quality.min_angle, 90.0);
  EXPECT_EQ(back.quality.boundary_layers, 3);
  EXPECT_FALSE(back.quality.estimated_yplus.has_value());
  EXPECT_EQ(back.source, file);
  mesh.mesh.boundaries.clear();
  formats::write_flowmesh(file, mesh, {});
  EXPECT_THROW(formats::read_flowmesh(file), BadInput);
}

// The mesh block's topology (formats/README.md, mesh block; flowmesh.md): a degenerate or
// clockwise cell, a boundary edge that is no cell edge, turned round, inside the mesh or missing
// are refused in one line naming the file and the dataset. Before, tfmb-flow took a turned edge
// and a gap in the boundaries silently (its results changed) and a non-cell edge as exit 4
// (issue 23's mutation suite, tests/formats/mutation_suite.py).
TEST(TypedIo, FlowMeshTopologyIsChecked) {
  formats::FlowMesh good;
  good.header.creator = "test";
  good.mesh.points.resize(6, 2);
  good.mesh.points << 0.0, 0.0, 1.0, 0.0, 2.0, 0.0, 0.0, 1.0, 1.0, 1.0, 2.0, 1.0;
  good.mesh.quads.resize(2, 4);
  good.mesh.quads << 0, 1, 4, 3, 1, 2, 5, 4;
  formats::Boundary wall;
  wall.kind = "wall";
  wall.edges.resize(2, 2);
  wall.edges << 0, 1, 1, 2;
  good.mesh.boundaries["wall"] = wall;
  formats::Boundary farfield;
  farfield.kind = "farfield";
  farfield.edges.resize(4, 2);
  farfield.edges << 2, 5, 5, 4, 4, 3, 3, 0;
  good.mesh.boundaries["farfield"] = farfield;
  const fs::path file = scratch("topology.h5");
  formats::write_flowmesh(file, good, {});
  EXPECT_NO_THROW(formats::read_flowmesh(file));

  auto refused = [&](const char* label, const formats::FlowMesh& bad, const std::string& located) {
    formats::write_flowmesh(file, bad, {});
    try {
      formats::read_flowmesh(file);
      ADD_FAILURE() << label << ": accepted";
    } catch (const BadInput& e) {
      const std::string message = e.what();
      EXPECT_EQ(message.rfind(file.string() + ": " + located, 0), 0u) << label << ": " << message;
      EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }
  };
  formats::FlowMesh bad = good;
  bad.mesh.quads.row(1) << 1, 2, 5, 5;
  refused("degenerate cell", bad, "/mesh/cells/quad: cell row 1 repeats node 5");
  bad = good;
  bad.mesh.quads.row(0) << 0, 3, 4, 1;
  refused("clockwise cell", bad, "/mesh/cells/quad: cell row 0 is clockwise");
  bad = good;
  bad.mesh.boundaries["wall"].edges.row(1) << 2, 1;
  refused(
      "edge turned round", bad,
      "/mesh/boundaries/wall/edges: edge row 1 (2, 1) does not run with the domain on its left");
  bad = good;
  bad.mesh.boundaries["wall"].edges.row(1) << 1, 5;
  refused("no cell edge", bad,
          "/mesh/boundaries/wall/edges: edge row 1 (1, 5) is not an edge of a cell");
  bad = good;
  bad.mesh.boundaries["wall"].edges.resize(1, 2);
  bad.mesh.boundaries["wall"].edges << 0, 1;
  refused("gap", bad, "/mesh/boundaries: the mesh's boundary edge (1, 2) is in no boundary");
  bad = good;
  bad.mesh.boundaries["farfield"].edges.row(0) << 1, 4;
  refused("inner edge", bad, "/mesh/boundaries/farfield/edges: edge row 0 (1, 4) is an inner edge");
  bad = good;
  bad.mesh.boundaries["farfield"].edges.row(0) << 0, 1;
  refused("edge twice", bad, "/mesh/boundaries/");
}

// A solid mesh's boundary is one head-to-tail chain (solidmesh.md): a row turned round in
// tfmb-heat's inner wall changed the temperatures silently.
TEST(TypedIo, SolidMeshBoundaryChainsAreChecked) {
  formats::SolidMesh solid;
  solid.header.creator = "test";
  solid.mesh.points.resize(6, 2);
  solid.mesh.points << 0.0, -0.005, 1.0, -0.005, 2.0, -0.005, 0.0, 0.005, 1.0, 0.005, 2.0, 0.005;
  solid.mesh.quads.resize(2, 4);
  solid.mesh.quads << 0, 1, 4, 3, 1, 2, 5, 4;
  solid.flap_names = {"upper"};
  solid.cell_flap = {0, 0};
  solid.cell_element = {0, 1};
  solid.point_thickness_coordinate = {-0.005, -0.005, -0.005, 0.005, 0.005, 0.005};
  auto face = [](const char* kind, const char* side, std::vector<std::int64_t> nodes) {
    formats::Boundary boundary;
    boundary.kind = kind;
    boundary.flap = "upper";
    boundary.side = side;
    boundary.edges =
        h5::MatrixXiR::Map(nodes.data(), static_cast<Eigen::Index>(nodes.size() / 2), 2);
    return boundary;
  };
  solid.mesh.boundaries["upper_inner"] = face("solid_inner", "inner", {0, 1, 1, 2});
  solid.mesh.boundaries["upper_outer"] = face("solid_outer", "outer", {3, 4, 4, 5});
  solid.mesh.boundaries["upper_start"] = face("solid_end", "end", {0, 3});
  solid.mesh.boundaries["upper_end"] = face("solid_end", "end", {2, 5});
  const fs::path file = scratch("solid-chain.h5");
  formats::write_solidmesh(file, solid, {});
  EXPECT_NO_THROW(formats::read_solidmesh(file));
  solid.mesh.boundaries["upper_inner"] = face("solid_inner", "inner", {0, 1, 2, 1});
  formats::write_solidmesh(file, solid, {});
  try {
    formats::read_solidmesh(file);
    ADD_FAILURE() << "a turned edge was accepted";
  } catch (const BadInput& e) {
    EXPECT_NE(std::string(e.what()).find(file.string() +
                                         ": /mesh/boundaries/upper_inner/edges: "
                                         "edge row 1 (2, 1) does not start where edge row 0 ends"),
              std::string::npos)
        << e.what();
  }
  solid.mesh.boundaries["upper_inner"] = face("solid_inner", "inner", {0, 1});
  formats::write_solidmesh(file, solid, {});
  EXPECT_THROW(formats::read_solidmesh(file), BadInput);
}

// What tfmb-strain writes reads back column by column; a worst flap that names no flap of the
// file is refused (tfmb-plot would mark the worst margin nowhere).
TEST(TypedIo, StrainRoundTripAndAWorstFlapThatIsNoFlapIsRefused) {
  formats::Strain strain;
  strain.header.creator = "test";
  strain.mechanical_basis = "mechanical";
  strain.worst_margin_total = -0.1;
  strain.worst_margin_mechanical = 0.5;
  strain.worst_margin_thermal = 2.0;
  strain.worst_flap = "upper";
  strain.worst_surface = "inner";
  strain.worst_segment = 1;
  strain.worst_position = {0.2, 0.1};
  formats::StrainFlap flap;
  flap.name = "upper";
  flap.element = {0, 1};
  flap.s = {0.05, 0.15};
  flap.position = {{0.1, 0.1}, {0.2, 0.1}};
  for (auto* column : {&flap.mechanical_inner, &flap.mechanical_outer, &flap.thermal_inner,
                       &flap.thermal_outer, &flap.total_inner, &flap.total_outer, &flap.allowable,
                       &flap.margin_mechanical, &flap.margin_thermal, &flap.margin_total})
    *column = {1e-3, 2e-3};
  flap.margin_total = {0.3, -0.1};
  strain.flaps.push_back(flap);
  formats::StrainWorst worst;
  worst.flap = "upper";
  worst.surface = "inner";
  worst.segment = 1;
  worst.element = 1;
  worst.s = 0.15;
  worst.position = {0.2, 0.1};
  worst.total_strain = 2e-3;
  worst.margin_total = -0.1;
  strain.worst.push_back(worst);
  const fs::path file = scratch("strain.h5");
  formats::write_strain(file, strain, {});
  const formats::Strain back = formats::read_strain(file);
  EXPECT_EQ(back.worst_margin_total, -0.1);
  EXPECT_EQ(back.flaps.at(0).margin_total, flap.margin_total);
  EXPECT_EQ(back.flaps.at(0).position.at(1), flap.position.at(1));
  EXPECT_EQ(back.worst.at(0).segment, 1);
  EXPECT_EQ(back.worst_position, strain.worst_position);
  strain.worst_flap = "lower";
  formats::write_strain(file, strain, {});
  EXPECT_THROW(formats::read_strain(file), BadInput);
}

// The static load path of structure.h5 (1.3): written and read back whole; a file without it
// (before 1.3, or a dynamic run) reads with no path; a path length that decreases and a limit
// point outside the path are refused with the dataset named.
TEST(TypedIo, StructurePathRoundTripAndABrokenPathIsRefused) {
  formats::Structure s;
  s.header.creator = "test";
  s.analysis = "static";
  s.converged = true;
  s.points = {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0.5, 0, 0), Eigen::Vector3d(1, 0, 0)};
  s.segments = {{0, 1}, {1, 2}};
  s.displacement = s.rotation = std::vector<Eigen::Vector3d>(3, Eigen::Vector3d::Zero());
  s.sectional_strain = s.sectional_force =
      std::vector<formats::Vector6>(2, formats::Vector6::Zero());
  s.flaps = {{"beam", {0, 1, 2}, {0, 1}}};
  const fs::path file = scratch("structure.h5");
  formats::write_structure(file, s, {});
  EXPECT_FALSE(formats::read_structure(file).path.has_value());

  formats::StructurePath p;
  p.method = "arc_length";
  p.monitor = "beam:end (0, -1, 0)";
  p.load_factor = {0.0, 0.6, 0.9, 0.7, 1.0};
  p.arc_length = {0.0, 0.1, 0.2, 0.3, 0.4};
  p.max_displacement = {0.0, 0.1, 0.2, 0.3, 0.4};
  p.characteristic_displacement = {0.0, 0.1, 0.2, 0.25, 0.4};
  p.node_displacement = {Eigen::Vector3d::Zero(), Eigen::Vector3d(0, -0.1, 0),
                         Eigen::Vector3d(0, -0.2, 0), Eigen::Vector3d(0, -0.25, 0),
                         Eigen::Vector3d(0, -0.4, 0)};
  p.iterations = {0, 4, 5, 6, 4};
  p.limit_points_load = {2, 3};
  p.limit_points_displacement = {};
  s.path = p;
  formats::write_structure(file, s, {});
  const formats::Structure back = formats::read_structure(file);
  ASSERT_TRUE(back.path.has_value());
  EXPECT_EQ(back.path->method, "arc_length");
  EXPECT_EQ(back.path->monitor, p.monitor);
  EXPECT_EQ(back.path->load_factor, p.load_factor);
  EXPECT_EQ(back.path->arc_length, p.arc_length);
  EXPECT_EQ(back.path->characteristic_displacement, p.characteristic_displacement);
  EXPECT_EQ(back.path->node_displacement, p.node_displacement);
  EXPECT_EQ(back.path->iterations, p.iterations);
  EXPECT_EQ(back.path->limit_points_load, p.limit_points_load);
  EXPECT_TRUE(back.path->limit_points_displacement.empty());

  auto refused = [&](const std::string& expected) {
    formats::write_structure(file, s, {});
    try {
      formats::read_structure(file);
      ADD_FAILURE() << "accepted; expected: " << expected;
    } catch (const BadInput& e) {
      EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
    }
  };
  s.path->arc_length = {0.0, 0.2, 0.1, 0.3, 0.4};
  refused("/path/arc_length");
  s.path = p;
  s.path->limit_points_load = {2, 5};
  refused("/path/limit_points_load");
}
