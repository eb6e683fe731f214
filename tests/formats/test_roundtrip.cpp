// Round trips of every file kind and byte-reproducible writes.
#include <gtest/gtest.h>

#include <cstdlib>

#include "test_support.hpp"
#include "tfmb/common/errors.hpp"
#include "tfmb/common/h5.hpp"
#include "tfmb/formats/files.hpp"
#include "tfmb/formats/schema.hpp"

namespace tfmb::formats {
namespace {

class EveryKind : public ::testing::TestWithParam<std::string> {};

TEST_P(EveryKind, ExampleIsValidAndRoundTripsExactly) {
  const Schema* schema = find_schema(GetParam());
  ASSERT_NE(schema, nullptr);
  const auto dir = test::scratch_dir();
  const Document original = example_document(*schema);
  write_document(original, dir / "a.h5");
  EXPECT_FALSE(std::filesystem::exists(dir / "a.h5.tmp"));
  h5::Reader file(dir / "a.h5");
  const auto problems = validate(file, *schema);
  for (const auto& p : problems) ADD_FAILURE() << p.message;
  const Document read_back = read_document(file);
  EXPECT_EQ(read_back.datasets, original.datasets);
  EXPECT_EQ(read_back.attributes, original.attributes);
  EXPECT_EQ(read_back.groups, original.groups);
}

TEST_P(EveryKind, TwoWritesOfTheSameContentAreByteIdentical) {
  const Schema* schema = find_schema(GetParam());
  const auto dir = test::scratch_dir();
  write_document(example_document(*schema), dir / "a.h5");
  write_document(example_document(*schema), dir / "b.h5");
  const std::string a = test::read_bytes(dir / "a.h5");
  ASSERT_FALSE(a.empty());
  EXPECT_TRUE(a == test::read_bytes(dir / "b.h5"));
}

std::vector<std::string> kinds() {
  std::vector<std::string> names;
  for (const auto& s : all_schemas()) names.push_back(s.kind);
  return names;
}

INSTANTIATE_TEST_SUITE_P(Formats, EveryKind, ::testing::ValuesIn(kinds()),
                         [](const auto& info) {
                           std::string name = info.param;
                           for (char& c : name) {
                             if (c == '-') c = '_';
                           }
                           return name;
                         });

Mesh two_cell_mesh() {
  Mesh mesh;
  mesh.points.resize(5, 2);
  mesh.points << 0, 0, 1, 0, 1, 1, 0, 1, 2, 0.5;
  mesh.quads.resize(1, 4);
  mesh.quads << 0, 1, 2, 3;
  mesh.triangles.resize(1, 3);
  mesh.triangles << 1, 4, 2;
  mesh.regions["fluid"] = {0, 1};
  Boundary wall;
  wall.edges.resize(2, 2);
  wall.edges << 0, 1, 1, 4;
  wall.kind = "wall";
  wall.flap = "flap1";
  wall.side = "inner";
  mesh.boundaries["lower_wall"] = wall;
  return mesh;
}

TEST(FormatsMesh, TypedMeshRoundTripAndSidecar) {
  const auto dir = test::scratch_dir();
  const Mesh mesh = two_cell_mesh();
  {
    h5::Writer file(dir / "m.h5");
    write_header(file, "flowmesh", {"test", "planar", 1.0});
    write_mesh(file, mesh);
    file.commit();
  }
  h5::Reader file = open_checked(dir / "m.h5", "flowmesh");
  const Mesh back = read_mesh(file);
  EXPECT_EQ(back.points, mesh.points);
  EXPECT_EQ(back.triangles, mesh.triangles);
  EXPECT_EQ(back.quads, mesh.quads);
  EXPECT_EQ(back.regions, mesh.regions);
  ASSERT_EQ(back.boundaries.count("lower_wall"), 1u);
  EXPECT_EQ(back.boundaries.at("lower_wall").edges, mesh.boundaries.at("lower_wall").edges);
  EXPECT_EQ(back.boundaries.at("lower_wall").side, "inner");
  const auto sidecar = write_xdmf_sidecar(dir / "m.h5");
  EXPECT_TRUE(std::filesystem::exists(sidecar));
}

// Every mesh boundary is its own polyline grid named after it (ParaView lists each wall by flap
// and side), with its own points copied exactly and the mesh point id of each as `node`; the
// mesh grid stays whole, and meshio reads the .meshio.xdmf variant (the mesh alone).
TEST(FormatsSidecar, MeshBoundariesAreNamedPolylines) {
  const auto dir = test::scratch_dir();
  const auto file = dir / "flowmesh.h5";
  {
    h5::Writer writer(file);
    write_header(writer, "flowmesh", {"test", "planar", 1.0});
    write_mesh(writer, two_cell_mesh());
    writer.commit();
  }
  const auto sidecar = write_xdmf_sidecar(file);
  ASSERT_EQ(setenv("TFMB_TEST_SIDECAR", sidecar.c_str(), 1), 0);
  // lower_wall: edges (0 1) (1 4) of the mesh points (0 0) (1 0) (2 0.5)
  const std::string parse =
      "/usr/bin/python3 -c \"import os, sys, xml.etree.ElementTree as ET\n"
      "root = ET.parse(os.environ['TFMB_TEST_SIDECAR']).getroot()\n"
      "grids = {g.get('Name'): g for g in root.iter('Grid') if g.get('GridType') == 'Uniform'}\n"
      "wall = grids['lower_wall']\n"
      "topology, geometry = wall.find('Topology'), wall.find('Geometry')\n"
      "node = [a for a in wall.iter('Attribute') if a.get('Name') == 'node'][0]\n"
      "ok = sorted(grids) == ['flowmesh', 'lower_wall']\n"
      "ok = ok and topology.get('TopologyType') == 'Polyline'\n"
      "ok = ok and topology.get('NumberOfElements') == '2'\n"
      "ok = ok and topology.find('DataItem').text.split() == '0 1 1 2'.split()\n"
      "xy = [float(v) for v in geometry.find('DataItem').text.split()]\n"
      "ok = ok and xy == [0, 0, 1, 0, 2, 0.5]\n"
      "ok = ok and node.find('DataItem').text.split() == ['0', '1', '4']\n"
      "ok = ok and grids['flowmesh'].find('Topology').get('TopologyType') == 'Mixed'\n"
      "sys.exit(0 if ok else 1)\"";
  EXPECT_EQ(std::system(parse.c_str()), 0) << test::read_bytes(sidecar);
  ASSERT_TRUE(std::filesystem::exists(meshio_sidecar_path(file)));
  EXPECT_EQ(test::read_bytes(meshio_sidecar_path(file)).find("lower_wall"), std::string::npos);
}

TEST(FormatsMesh, TypedWritesAreByteIdentical) {
  const auto dir = test::scratch_dir();
  for (const char* name : {"a.h5", "b.h5"}) {
    h5::Writer file(dir / name);
    write_header(file, "flowmesh", {"test", "planar", 1.0});
    write_mesh(file, two_cell_mesh());
    write_provenance(file, {"tfmb-test --x", "a = 1", {}});
    file.commit();
  }
  EXPECT_TRUE(test::read_bytes(dir / "a.h5") == test::read_bytes(dir / "b.h5"));
}

// meshio (Debian's python3-meshio) must read every mesh sidecar without project code: the
// sidecar itself, or its .meshio.xdmf variant where the sidecar has more than one grid.
TEST(FormatsMesh, MeshioReadsEverySidecar) {
  if (std::system("/usr/bin/python3 -c 'import meshio' 2>/dev/null") != 0) {
    GTEST_SKIP() << "python3-meshio not installed";
  }
  const auto dir = test::scratch_dir();
  for (const auto& schema : all_schemas()) {
    if (!schema.mesh_bearing) continue;
    const auto file = dir / (schema.kind + ".h5");
    write_document(example_document(schema), file);
    auto sidecar = write_xdmf_sidecar(file);
    if (std::filesystem::exists(meshio_sidecar_path(file)))
      sidecar = meshio_sidecar_path(file);
    const std::string command = "/usr/bin/python3 -c \"import meshio,sys; m = meshio.read('" +
                                sidecar.string() +
                                "'); sys.exit(0 if len(m.points) == 6 and sum(len(c.data) for c "
                                "in m.cells) == 3 else 1)\"";
    EXPECT_EQ(std::system(command.c_str()), 0) << schema.kind;
  }
}

// A file name with XML's special characters (a case directory named "R&D <draft>") must still
// give a well-formed sidecar whose data references name the file exactly: unescaped, `&` and `<`
// made ParaView and meshio refuse it. The field name carries them too, as an external writer may.
TEST(FormatsMesh, SidecarOfAFileNamedWithXmlSpecialCharactersParses) {
  const auto dir = test::scratch_dir();
  const std::string name = "R&D <draft> \"v1\" 'b'";
  const auto file = dir / (name + ".h5");
  {
    h5::Writer writer(file);
    write_header(writer, "flowmesh", {"test", "planar", 1.0});
    write_mesh(writer, two_cell_mesh());
    writer.write("/fields/point/p<&>", std::vector<double>{1, 2, 3, 4, 5}, "Pa");
    writer.commit();
  }
  const auto sidecar = write_xdmf_sidecar(file);
  // The path goes through the environment, so that no shell quoting is involved.
  ASSERT_EQ(setenv("TFMB_TEST_SIDECAR", sidecar.c_str(), 1), 0);
  ASSERT_EQ(setenv("TFMB_TEST_DATA_FILE", file.filename().c_str(), 1), 0);
  const std::string parse =
      "/usr/bin/python3 -c \"import os, sys, xml.etree.ElementTree as ET\n"
      "root = ET.parse(os.environ['TFMB_TEST_SIDECAR']).getroot()\n"
      "data = os.environ['TFMB_TEST_DATA_FILE']\n"
      "items = [e.text for e in root.iter('DataItem') if e.get('Format') == 'HDF']\n"
      "mesh = [g for g in root.iter('Grid') if g.get('GridType') == 'Uniform'][0]\n"
      "names = [e.get('Name') for e in mesh.iter('Attribute')]\n"
      "grid = next(root.iter('Grid')).get('Name')\n"
      "ok = len(items) == 3 and all(t.startswith(data + ':/') for t in items)\n"
      "ok = ok and names == ['p<&>'] and grid == data[:-3]\n"
      "sys.exit(0 if ok else 1)\"";
  EXPECT_EQ(std::system(parse.c_str()), 0) << test::read_bytes(sidecar);
  if (std::system("/usr/bin/python3 -c 'import meshio' 2>/dev/null") == 0) {
    // the mesh with its boundaries is a collection: meshio reads the one-grid variant
    ASSERT_EQ(setenv("TFMB_TEST_SIDECAR", meshio_sidecar_path(file).c_str(), 1), 0);
    const std::string read =
        "/usr/bin/python3 -c \"import meshio, os, sys\n"
        "m = meshio.read(os.environ['TFMB_TEST_SIDECAR'])\n"
        "sys.exit(0 if len(m.points) == 5 else 1)\"";
    EXPECT_EQ(std::system(read.c_str()), 0) << "meshio";
  }
}

// The structure file's sectional strains and forces mix units across their six columns: the
// sidecar shows each column as its own scalar named with its unit, a hyperslab of the same
// dataset (column k of (E,6)); meshio gets the whole datasets from the .meshio.xdmf variant.
TEST(FormatsSidecar, StructureComponentsAreNamedScalarsWithUnits) {
  const auto dir = test::scratch_dir();
  const auto file = dir / "structure.h5";
  write_document(example_document(*find_schema("structure")), file);
  const auto sidecar = write_xdmf_sidecar(file);
  const std::string text = test::read_bytes(sidecar);
  const std::size_t rows = h5::Reader(file).info("/beam/segments").shape.at(0);
  const std::string e = std::to_string(rows);
  EXPECT_NE(text.find("Name=\"bending_moment [N m]\""), std::string::npos) << text;
  EXPECT_NE(text.find("Name=\"axial_strain [1]\""), std::string::npos);
  EXPECT_NE(text.find("Name=\"curvature [1/m]\""), std::string::npos);
  EXPECT_NE(text.find("structure.h5:/fields/cell/sectional_force|0 5:1 1:" + e + " 1:" + e + " 6"),
            std::string::npos)
      << "bending moment (in plane) is column 5";
  EXPECT_EQ(text.find("Name=\"sectional_force\""), std::string::npos) << "shown whole";
  const std::string meshio = test::read_bytes(meshio_sidecar_path(file));
  EXPECT_NE(meshio.find("Name=\"sectional_force\""), std::string::npos);
  EXPECT_EQ(meshio.find('|'), std::string::npos);
}

// Loads (1.2, with positions), strain and walldisp files get a sidecar with a polyline per flap
// or wall; a flow file's wall traces are polylines beside its mesh. Kinds with nothing to draw
// get none.
TEST(FormatsSidecar, LineKindsGetPolylineGrids) {
  const auto dir = test::scratch_dir();
  for (const std::string kind : {"loads", "strain", "walldisp", "flow"}) {
    SCOPED_TRACE(kind);
    const auto file = dir / (kind + ".h5");
    write_document(example_document(*find_schema(kind)), file);
    const auto sidecar = write_xdmf_sidecar(file);
    ASSERT_FALSE(sidecar.empty());
    const std::string text = test::read_bytes(sidecar);
    EXPECT_NE(text.find("TopologyType=\"Polyline\""), std::string::npos) << text;
    EXPECT_NE(text.find("<Grid Name=\"sample\""), std::string::npos);
  }
  EXPECT_NE(test::read_bytes(dir / "flow.xdmf").find("CollectionType=\"Spatial\""),
            std::string::npos);
  EXPECT_TRUE(std::filesystem::exists(dir / "flow.meshio.xdmf"));
  const auto model = dir / "model.h5";
  write_document(example_document(*find_schema("model")), model);
  EXPECT_TRUE(write_xdmf_sidecar(model).empty());
  EXPECT_FALSE(std::filesystem::exists(dir / "model.xdmf"));
}

// A temporal collection over iterates in sub-folders references each file relative to the
// collection, at times 1, 2, ...
TEST(FormatsSidecar, SeriesIsATemporalCollectionOfTheIterates) {
  const auto dir = test::scratch_dir();
  std::vector<std::filesystem::path> files;
  for (const char* iterate : {"iter-001", "iter-002"}) {
    std::filesystem::create_directories(dir / iterate);
    files.push_back(dir / iterate / "structure.h5");
    write_document(example_document(*find_schema("structure")), files.back());
  }
  const auto series = write_xdmf_series(dir / "structure-iterations.xdmf", files);
  const std::string text = test::read_bytes(series);
  EXPECT_NE(text.find("GridType=\"Collection\" CollectionType=\"Temporal\""), std::string::npos);
  EXPECT_NE(text.find("<Time Value=\"1\"/>"), std::string::npos);
  EXPECT_NE(text.find("<Time Value=\"2\"/>"), std::string::npos);
  EXPECT_NE(text.find(">iter-002/structure.h5:/beam/points<"), std::string::npos) << text;
  EXPECT_THROW(write_xdmf_series(dir / "none.xdmf", {}), Error);
}

}  // namespace
}  // namespace tfmb::formats
