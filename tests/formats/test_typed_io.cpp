// The typed readers and writers of formats/: what a writer writes its reader reads back, and the
// checks the schema cannot make are made (one located line per problem).
#include <gtest/gtest.h>

#include <hdf5.h>

#include <filesystem>

#include "tfmb/common/errors.hpp"
#include "tfmb/formats/loads.hpp"
#include "tfmb/formats/material_db.hpp"
#include "tfmb/formats/materials.hpp"
#include "tfmb/formats/solidmesh.hpp"

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

TEST(TypedIo, LoadsRoundTripAndAReversedArcLengthIsRefused) {
  formats::Loads loads;
  loads.header.creator = "test";
  loads.method = "conservative";
  loads.load_basis = "flap width";
  formats::LoadsFlap f;
  f.name = "lower";
  f.width = 1.0;
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
  const fs::path file = scratch("solidmesh.h5");
  formats::write_solidmesh(file, solid, {});
  EXPECT_EQ(formats::read_solidmesh(file).point_thickness_coordinate[2], 0.005);
  solid.point_thickness_coordinate = {0.0, 0.0, 0.0, 0.0};
  formats::write_solidmesh(file, solid, {});
  EXPECT_THROW(formats::read_solidmesh(file), BadInput);
}
