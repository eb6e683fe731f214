// End-to-end tests of the file stage: model.h5 (+ loads.h5) -> structure.h5, built from the
// formats' example documents with a physically meaningful cantilever put in.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "tfmb/beam/run.hpp"
#include "tfmb/common/errors.hpp"
#include "tfmb/common/h5.hpp"
#include "tfmb/formats/files.hpp"
#include "tfmb/formats/schema.hpp"

namespace fs = std::filesystem;
using namespace tfmb;

namespace {

constexpr double kEI = 100.0, kGA = 1e6, kLength = 1.0;

void set_matrix(formats::DatasetValue& d, const std::vector<std::vector<double>>& rows) {
  d.shape = {rows.size(), rows.empty() ? 0 : rows[0].size()};
  d.floats.clear();
  for (const auto& r : rows) d.floats.insert(d.floats.end(), r.begin(), r.end());
}

void erase_prefix(formats::Document& doc, const std::string& prefix) {
  std::erase_if(doc.datasets, [&](const auto& kv) { return kv.first.rfind(prefix, 0) == 0; });
  std::erase_if(doc.attributes, [&](const auto& kv) { return kv.first.rfind(prefix, 0) == 0; });
  std::erase_if(doc.groups, [&](const std::string& g) { return g.rfind(prefix, 0) == 0; });
}

/// Cantilever of 1 m along +x in 3 two-node model elements, clamped at its start.
fs::path write_cantilever_model(const fs::path& dir, const std::string& joint_kind = "") {
  formats::Document doc = formats::example_document(*formats::find_schema("model"));
  std::vector<std::vector<double>> line, inner;
  for (int i = 0; i < 4; ++i) {
    line.push_back({kLength * i / 3.0, 0.0});
    inner.push_back({kLength * i / 3.0, -0.005});
  }
  set_matrix(doc.datasets["/flaps/sample/reference_curve"], line);
  set_matrix(doc.datasets["/flaps/sample/reference_geometry"], line);
  set_matrix(doc.datasets["/flaps/sample/inner_wall"], inner);
  std::vector<std::vector<double>> k(6, std::vector<double>(6, 0.0)), m(6, std::vector<double>(6, 0.0));
  const double diag_k[6] = {1e7, kGA, kGA, 50.0, kEI, kEI}, diag_m[6] = {1.0, 1.0, 1.0, 2e-4, 1e-4, 1e-4};
  for (int i = 0; i < 6; ++i) {
    k[i][i] = diag_k[i];
    m[i][i] = diag_m[i];
  }
  set_matrix(doc.datasets["/flaps/sample/section_stiffness"], k);
  set_matrix(doc.datasets["/flaps/sample/section_mass"], m);
  if (joint_kind.empty()) {
    erase_prefix(doc, "/joints");
  } else {
    doc.attributes["/joints/sample"]["kind"].text = joint_kind;
  }
  doc.attributes["/supports/sample"]["flap"].text = "sample";
  doc.attributes["/supports/sample"]["end"].text = "start";
  doc.attributes["/supports/sample"]["kind"].text = "clamp";
  doc.attributes["/analysis"]["time"].text = "static";
  doc.attributes["/analysis"]["load_steps"].integer = 2;
  const fs::path file = dir / "model.h5";
  formats::write_document(doc, file);
  return file;
}

/// Uniform transverse load q [N/m] in -y on the cantilever.
fs::path write_loads(const fs::path& dir, double q) {
  formats::Document doc = formats::example_document(*formats::find_schema("loads"));
  std::vector<std::vector<double>> f;
  for (int i = 0; i < 4; ++i) f.push_back({0.0, -q, 0.0});
  set_matrix(doc.datasets["/flaps/sample/distributed_force"], f);
  const std::vector<std::vector<double>> zero(4, std::vector<double>(3, 0.0));
  set_matrix(doc.datasets["/flaps/sample/distributed_moment"], zero);
  set_matrix(doc.datasets["/flaps/sample/nodal_moment"], zero);
  const fs::path file = dir / "loads.h5";
  formats::write_document(doc, file);
  return file;
}

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::path(TFMB_BINARY_DIR) / "test-beam-stage" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

}  // namespace

// Uniform load on a cantilever: tip deflection q L^4 / (8 EI) + q L^2 / (2 GA). The load is
// small (tip rotation ~1e-6), so the geometrically nonlinear answer equals the linear one to ~1e-12;
// three quadratic elements are exact at the nodes for this polynomial solution up to ~1e-6.
TEST(Stage, CantileverUnderUniformLoadWritesValidStructure) {
  const fs::path dir = scratch("uniform");
  beam::Options o;
  o.model = write_cantilever_model(dir);
  const double q = 1e-3;
  o.loads = write_loads(dir, q);
  o.output = dir / "structure.h5";
  o.dead_loads = true;
  const Logger log("tfmb-beam", Verbosity::quiet);
  EXPECT_EQ(beam::run(o, log), 0);
  const h5::Reader r = formats::open_checked(o.output, "structure");  // validates against the schema
  const h5::MatrixXdR u = r.read_matrix("/fields/point/displacement");
  const auto tip_nodes = r.read_index_vector("/flaps/sample/nodes", 7, 0, u.rows());
  const auto tip = static_cast<Eigen::Index>(tip_nodes.back());
  const double exact = q * std::pow(kLength, 4) / (8 * kEI) + q * kLength * kLength / (2 * kGA);
  EXPECT_NEAR(-u(tip, 1), exact, 1e-5 * exact);
  // Follower load (the default): the same at this small rotation.
  o.dead_loads = false;
  EXPECT_EQ(beam::run(o, log), 0);
  const h5::Reader r2 = formats::open_checked(o.output, "structure");
  EXPECT_NEAR(-r2.read_matrix("/fields/point/displacement")(tip, 1), exact, 1e-5 * exact);
  // Clamp reaction balances the load.
  const auto reaction = r2.read_vector("/joints/sample/reaction");
  EXPECT_NEAR(reaction[1], q * kLength, 1e-9);
}

TEST(Stage, DynamicRunWritesHistory) {
  const fs::path dir = scratch("dynamic");
  beam::Options o;
  o.model = write_cantilever_model(dir);
  o.loads = write_loads(dir, 1e-3);
  o.output = dir / "structure.h5";
  o.analysis = "dynamic";
  o.end_time = 0.02;
  o.time_step = 1e-3;
  const Logger log("tfmb-beam", Verbosity::quiet);
  EXPECT_EQ(beam::run(o, log), 0);
  const h5::Reader r = formats::open_checked(o.output, "structure");
  EXPECT_EQ(r.read_vector("/history/time").size(), 20u);
}

TEST(Stage, UnsupportedJointKindIsBadInput) {
  const fs::path dir = scratch("flexible");
  beam::Options o;
  o.model = write_cantilever_model(dir, "flexible");
  o.output = dir / "structure.h5";
  const Logger log("tfmb-beam", Verbosity::quiet);
  try {
    beam::run(o, log);
    FAIL() << "expected BadInput";
  } catch (const BadInput& e) {
    EXPECT_NE(std::string(e.what()).find("flexible"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(o.output));
}

// materials.h5: uniform thermal strain lengthens the free cantilever by eps L; a thermal
// curvature (outer wall hotter, outer wall on the right of +x, i.e. at -y) bends it towards +y
// into an arc of curvature kappa: tip y = (1 - cos(kappa L)) / kappa.
TEST(Stage, ThermalStrainFromMaterials) {
  const fs::path dir = scratch("materials");
  beam::Options o;
  o.model = write_cantilever_model(dir);
  formats::Document doc = formats::example_document(*formats::find_schema("materials"));
  const double eps = 1e-3, kappa = 0.02;
  for (auto& [path, d] : doc.datasets) {
    if (path.rfind("/flaps/sample/", 0) != 0) continue;
    const std::string leaf = path.substr(14);
    if (leaf == "section_stiffness" || leaf == "section_mass") {
      d.shape = {3, 6, 6};
      d.floats.assign(3 * 36, 0.0);
      const double diag_k[6] = {1e7, kGA, kGA, 50.0, kEI, kEI};
      for (int e = 0; e < 3; ++e)
        for (int i = 0; i < 6; ++i) d.floats[36 * e + 7 * i] = leaf == "section_stiffness" ? diag_k[i] : 1.0;
    } else if (d.dtype == h5::DType::int64) {
      d.shape = {3};
      d.integers.assign(3, 0);
    } else {
      d.shape = {3};
      d.floats.assign(3, leaf == "thermal_strain" ? eps : leaf == "thermal_curvature" ? kappa : 1.0);
    }
  }
  doc.attributes["/flaps/sample"]["outer_normal_sign"].integer = -1;
  o.materials = dir / "materials.h5";
  formats::write_document(doc, o.materials);
  o.output = dir / "structure.h5";
  const Logger log("tfmb-beam", Verbosity::quiet);
  EXPECT_EQ(beam::run(o, log), 0);
  const h5::Reader r = formats::open_checked(o.output, "structure");
  const h5::MatrixXdR u = r.read_matrix("/fields/point/displacement");
  const Eigen::Index tip = u.rows() - 1;
  const double x_exact = std::sin(kappa * kLength) / kappa * (1 + eps) - kLength;
  const double y_exact = (1 - std::cos(kappa * kLength)) / kappa * (1 + eps);
  EXPECT_NEAR(u(tip, 0), x_exact, 1e-8);
  EXPECT_NEAR(u(tip, 1), y_exact, 1e-6 * y_exact);
  // The sidecar opens the result as a polyline with its fields.
  std::ifstream x(dir / "structure.xdmf");
  const std::string text((std::istreambuf_iterator<char>(x)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("Polyline"), std::string::npos);
  EXPECT_NE(text.find("structure.h5:/fields/point/displacement"), std::string::npos);
}

// Nodal moments of loads.h5 (wall offsets) and --point-load: a tip moment M gives the tip
// rotation M L / EI; a tip force P adds P L^3 / (3 EI) + P L / GA of deflection.
TEST(Stage, NodalMomentsAndPointLoads) {
  const fs::path dir = scratch("moments");
  beam::Options o;
  o.model = write_cantilever_model(dir);
  formats::Document doc = formats::example_document(*formats::find_schema("loads"));
  std::vector<std::vector<double>> zero(4, std::vector<double>(3, 0.0)), mom = zero;
  const double m_tip = 1e-3, p_tip = 2e-3;
  mom[3][2] = m_tip;
  set_matrix(doc.datasets["/flaps/sample/distributed_force"], zero);
  set_matrix(doc.datasets["/flaps/sample/distributed_moment"], zero);
  set_matrix(doc.datasets["/flaps/sample/nodal_moment"], mom);
  o.loads = dir / "loads.h5";
  formats::write_document(doc, o.loads);
  o.point_loads = {"sample:end:0,-" + std::to_string(p_tip)};
  o.output = dir / "structure.h5";
  o.dead_loads = true;
  const Logger log("tfmb-beam", Verbosity::quiet);
  EXPECT_EQ(beam::run(o, log), 0);
  const h5::Reader r = formats::open_checked(o.output, "structure");
  const h5::MatrixXdR u = r.read_matrix("/fields/point/displacement");
  const Eigen::Index tip = u.rows() - 1;
  const double exact = -m_tip * kLength * kLength / (2 * kEI) + p_tip * std::pow(kLength, 3) / (3 * kEI) + p_tip * kLength / kGA;
  EXPECT_NEAR(-u(tip, 1), exact, 1e-5 * std::abs(exact));
  o.point_loads = {"sample:middle:0,1"};
  EXPECT_THROW(beam::run(o, log), UsageError);
}

// Modal analysis through the stage: first bending frequency of the clamped 1 m cantilever
// (EI = 100 N m^2, 1 kg/m) against Euler-Bernoulli 3.5160 sqrt(EI/m)/(2 pi) = 5.596 Hz; three
// quadratic elements, shear and rotary inertia change it by < 0.2 %.
TEST(Stage, ModalWritesFrequenciesAndShapes) {
  const fs::path dir = scratch("modal");
  beam::Options o;
  o.model = write_cantilever_model(dir);
  o.output = dir / "structure.h5";
  o.analysis = "modal";
  o.modes = 4;
  const Logger log("tfmb-beam", Verbosity::quiet);
  EXPECT_EQ(beam::run(o, log), 0);
  const h5::Reader r = formats::open_checked(o.output, "structure");
  const auto f = r.read_vector("/modes/frequency", 4);
  const double exact = 3.5160152685 * std::sqrt(kEI / 1.0) / (2 * M_PI);
  EXPECT_NEAR(f[0] / exact, 1.0, 2e-3);  // planar model: the first mode is in-plane bending
  std::vector<std::size_t> shape;
  (void)r.read_f64("/modes/displacement", &shape);
  EXPECT_EQ(shape, (std::vector<std::size_t>{4, 7, 3}));
}
