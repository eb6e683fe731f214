// End-to-end tests of the tfmb-heat stage on small files: a flat flap heated by convection on
// its inner face and radiating from its outer face (1D through the thickness, exact), and the
// bad-input paths (exit code 3 with a clear message).
#include "tfmb/common/errors.hpp"
#include "tfmb/common/h5.hpp"
#include "tfmb/common/log.hpp"
#include "tfmb/formats/files.hpp"
#include "tfmb/formats/schema.hpp"
#include "tfmb-heat/boundary_terms.hpp"
#include "tfmb-heat/run.hpp"
#include "tfmb-heat/strip_mesh.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <sys/wait.h>

namespace fs = std::filesystem;
using namespace tfmb;

namespace {

constexpr double kLength = 0.2, kThickness = 0.004;  // [m]
constexpr int kElements = 4;                          // beam elements of the flap
constexpr double kH = 500.0, kTaw = 900.0;            // inner convection
constexpr double kConductivity = 7.0;                 // [W/(m K)], constant over its table
constexpr double kEmissivity = 0.6, kEnvironment = 300.0;

formats::AttributeValue text(const std::string& value) {
  formats::AttributeValue a;
  a.type = formats::AttrType::string;
  a.text = value;
  return a;
}
formats::AttributeValue number(double value) {
  formats::AttributeValue a;
  a.type = formats::AttrType::float64;
  a.number = value;
  return a;
}
formats::AttributeValue integer(std::int64_t value) {
  formats::AttributeValue a;
  a.type = formats::AttrType::int64;
  a.integer = value;
  return a;
}

void set_floats(formats::Document& doc, const std::string& path, const std::vector<double>& values,
                const std::string& units) {
  auto& d = doc.datasets[path];
  d.dtype = h5::DType::float64;
  d.shape = {values.size()};
  d.floats = values;
  d.integers.clear();
  d.strings.clear();
  doc.attributes[path]["units"] = text(units);
}

// Renames every object under `from` to `to` (groups, datasets, attributes).
void rename_prefix(formats::Document& doc, const std::string& from, const std::string& to) {
  auto renamed = [&](const std::string& key) {
    return key.rfind(from, 0) == 0 && (key.size() == from.size() || key[from.size()] == '/')
               ? to + key.substr(from.size()) : key;
  };
  std::set<std::string> groups;
  for (const auto& g : doc.groups) groups.insert(renamed(g));
  doc.groups = groups;
  std::map<std::string, formats::DatasetValue> datasets;
  for (auto& [k, v] : doc.datasets) datasets[renamed(k)] = v;
  doc.datasets = datasets;
  std::map<std::string, std::map<std::string, formats::AttributeValue>> attributes;
  for (auto& [k, v] : doc.attributes) attributes[renamed(k)] = v;
  doc.attributes = attributes;
}

void copy_prefix(formats::Document& doc, const std::string& from, const std::string& to) {
  formats::Document copy = doc;
  rename_prefix(copy, from, to);
  for (const auto& g : copy.groups) doc.groups.insert(g);
  for (const auto& [k, v] : copy.datasets) doc.datasets[k] = v;
  for (const auto& [k, v] : copy.attributes) doc.attributes[k] = v;
}

formats::Document example(const std::string& kind) {
  return formats::example_document(*formats::find_schema(kind));
}

struct Case {
  fs::path dir, solid, flow, model, db, output;
  double k_value = kConductivity;
  std::vector<double> k_temperatures = {200.0, 2000.0};
  bool with_h_trace = true;
  std::string solid_boundary = "convection_radiation";
  bool two_flaps = false;  // f1 beyond a 0.5 mm gap after f0, joined by a joint in the model
};

constexpr double kGap = 0.0005;  // [m] between the flaps of the two-flap case

void write_solid(const Case& c) {
  heat::StripMeshOptions o;
  o.length = kLength;
  o.thickness = kThickness;
  o.cells_along = 16;
  o.cells_through = 4;
  const auto strip = heat::make_strip_mesh(o);
  const int flaps = c.two_flaps ? 2 : 1;
  const auto n = strip.points.rows();
  const auto& quads = strip.blocks.at(0).nodes;
  const auto nq = static_cast<Eigen::Index>(quads.size() / 4);
  formats::Mesh mesh;
  mesh.points.resize(n * flaps, 2);
  mesh.quads.resize(nq * flaps, 4);
  mesh.triangles.resize(0, 3);
  std::vector<std::int64_t> cell_flap, cell_element;
  for (int f = 0; f < flaps; ++f) {
    const double shift = f * (kLength + kGap);
    for (Eigen::Index i = 0; i < n; ++i) {
      mesh.points(f * n + i, 0) = strip.points(i, 0) + shift;
      mesh.points(f * n + i, 1) = strip.points(i, 1);
    }
    for (Eigen::Index q = 0; q < nq; ++q) {
      double xc = 0;
      for (int a = 0; a < 4; ++a) {
        mesh.quads(f * nq + q, a) = quads[static_cast<std::size_t>(4 * q + a)] + f * n;
        xc += 0.25 * strip.points(quads[static_cast<std::size_t>(4 * q + a)], 0);
      }
      cell_flap.push_back(f);
      cell_element.push_back(static_cast<std::int64_t>(xc / (kLength / kElements)));
    }
    const std::string flap = "f" + std::to_string(f);
    auto boundary = [&](const char* name, const char* kind, const char* side) {
      formats::Boundary b;
      const auto& nodes = strip.boundaries.at(name).nodes;
      b.edges = h5::MatrixXiR::Map(nodes.data(), static_cast<Eigen::Index>(nodes.size() / 2), 2).array() + f * n;
      b.kind = kind;
      b.flap = flap;
      b.side = side;
      return b;
    };
    mesh.boundaries[flap + "_inner"] = boundary("bottom", "solid_inner", "inner");
    mesh.boundaries[flap + "_outer"] = boundary("top", "solid_outer", "outer");
    mesh.boundaries[flap + "_start"] = boundary("left", "solid_end", "end");
    mesh.boundaries[flap + "_end"] = boundary("right", "solid_end", "end");
  }
  h5::Writer w(c.solid);
  formats::write_header(w, "solidmesh", {"test", "planar", 1.0});
  formats::write_mesh(w, mesh);
  w.write_strings("/link/flap_names", c.two_flaps ? std::vector<std::string>{"f0", "f1"} : std::vector<std::string>{"f0"});
  w.write("/link/cell_flap", cell_flap);
  w.write("/link/cell_element", cell_element);
  std::vector<double> z;
  for (Eigen::Index i = 0; i < mesh.points.rows(); ++i) z.push_back(mesh.points(i, 1) - 0.5 * kThickness);
  w.write("/link/point_thickness_coordinate", z, "m");
  w.commit();
}

// One flow wall trace along y = 0 from x0 to x1 (stored running the other way: the mapping must
// not care), with uniform h, T_aw and wall temperature.
void set_wall(formats::Document& doc, const Case& c, const std::string& wall, double x0, double x1,
              double temperature) {
  const int n = 11;
  std::vector<double> s, x, y, h, t, zeros;
  for (int i = 0; i < n; ++i) {
    x.push_back(x1 - (x1 - x0) * i / (n - 1));
    s.push_back((x1 - x0) * i / (n - 1));
    y.push_back(0.0);
    h.push_back(kH);
    t.push_back(temperature);
    zeros.push_back(0.0);
  }
  const std::string w = "/walls/" + wall + "/";
  for (auto it = doc.datasets.begin(); it != doc.datasets.end();) {
    if (it->first.rfind(w, 0) == 0) doc.attributes.erase(it->first), it = doc.datasets.erase(it);
    else ++it;
  }
  set_floats(doc, w + "s", s, "m");
  set_floats(doc, w + "x", x, "m");
  set_floats(doc, w + "y", y, "m");
  set_floats(doc, w + "pressure", std::vector<double>(n, 1e5), "Pa");
  set_floats(doc, w + "temperature", t, "K");
  set_floats(doc, w + "wall_shear", zeros, "Pa");
  set_floats(doc, w + "heat_flux", zeros, "W/m^2");
  set_floats(doc, w + "adiabatic_wall_temperature", t, "K");
  if (c.with_h_trace) set_floats(doc, w + "heat_transfer_coefficient", h, "W/(m^2 K)");
  auto& node = doc.datasets[w + "node"];
  node.dtype = h5::DType::int64;
  node.shape = {static_cast<std::size_t>(n)};
  node.integers.assign(n, 0);
  doc.attributes[w + "node"]["units"] = text("1");
}

void write_flow(const Case& c) {
  auto doc = example("flow");
  if (c.two_flaps) {
    copy_prefix(doc, "/mesh/boundaries/sample", "/mesh/boundaries/sample2");
    copy_prefix(doc, "/walls/sample", "/walls/sample2");
  }
  for (int f = 0; f < (c.two_flaps ? 2 : 1); ++f) {
    const std::string wall = f == 0 ? "sample" : "sample2";
    auto& b = doc.attributes["/mesh/boundaries/" + wall];
    b["kind"] = text("wall");
    b["flap"] = text("f" + std::to_string(f));
    b["side"] = text("inner");
    const double x0 = f * (kLength + kGap);
    set_wall(doc, c, wall, x0, x0 + kLength, f == 0 ? kTaw : 500.0);
  }
  formats::write_document(doc, c.flow);
}

void write_model(const Case& c) {
  auto doc = example("model");
  rename_prefix(doc, "/flaps/sample", "/flaps/f0");
  doc.attributes["/flaps/f0"]["material"] = text("Ti-Test");  // an alias, other case
  doc.attributes["/flaps/f0"]["elements"] = integer(kElements);
  // The model reader wants elements+1 beam nodes (the heat stage takes its geometry from the solid
  // mesh, so a straight line of the flap's length will do) and no references to the example's
  // flap name 'sample'.
  {
    formats::DatasetValue& curve = doc.datasets["/flaps/f0/reference_curve"];
    curve.shape = {static_cast<std::size_t>(kElements) + 1, 2};
    curve.floats.clear();
    for (int i = 0; i <= kElements; ++i)
      curve.floats.insert(curve.floats.end(), {kLength * i / kElements, 0.0});
  }
  std::vector<std::string> unused = {"/supports/", "/domain/boundaries/"};
  if (!c.two_flaps)
    unused.push_back("/joints/");  // the two-flap case re-points the joint below
  for (const std::string& prefix : unused) {
    std::erase_if(doc.groups, [&](const std::string& g) { return g.rfind(prefix, 0) == 0; });
    std::erase_if(doc.datasets, [&](const auto& kv) { return kv.first.rfind(prefix, 0) == 0; });
    std::erase_if(doc.attributes, [&](const auto& kv) { return kv.first.rfind(prefix, 0) == 0; });
  }
  doc.attributes["/thermal"]["solid_boundary"] = text(c.solid_boundary);
  doc.attributes["/thermal"]["emissivity"] = number(kEmissivity);
  if (c.two_flaps) {
    copy_prefix(doc, "/flaps/f0", "/flaps/f1");
    doc.attributes["/flaps/f1"]["order"] = integer(1);
    auto& joint = doc.attributes["/joints/sample"];
    joint["flap_a"] = text("f0");
    joint["end_a"] = text("end");
    joint["flap_b"] = text("f1");
    joint["end_b"] = text("start");
  }
  formats::write_document(doc, c.model);
}

void write_db(const Case& c) {
  auto doc = example("material-db");
  rename_prefix(doc, "/materials/sample", "/materials/alloy");
  doc.attributes["/materials/alloy"]["aliases"] = text("other,ti-test");
  const std::string p = "/materials/alloy/sample";
  const std::size_t n = c.k_temperatures.size();
  for (const char* ds : {"/point_exactness", "/point_source"}) {
    if (doc.datasets.count(p + ds)) {
      auto& d = doc.datasets[p + ds];
      d.strings.assign(n, d.strings.empty() ? "x" : d.strings.front());
      d.shape = {n};
    }
  }
  set_floats(doc, p + "/temperature", c.k_temperatures, "K");
  copy_prefix(doc, p, "/materials/alloy/density");
  set_floats(doc, "/materials/alloy/density/value", std::vector<double>(n, 4430.0), "kg/m^3");
  copy_prefix(doc, p, "/materials/alloy/specific_heat");
  set_floats(doc, "/materials/alloy/specific_heat/value", std::vector<double>(n, 526.0), "J/(kg K)");
  rename_prefix(doc, p, "/materials/alloy/conductivity");
  set_floats(doc, "/materials/alloy/conductivity/value", std::vector<double>(n, c.k_value), "W/(m K)");
  formats::write_document(doc, c.db);
}

Case make_case(const std::string& name) {
  Case c;
  c.dir = fs::path(TFMB_BINARY_DIR) / "test-heat-stage" / name;
  fs::remove_all(c.dir);
  fs::create_directories(c.dir);
  c.solid = c.dir / "solidmesh.h5";
  c.flow = c.dir / "flow.h5";
  c.model = c.dir / "model.h5";
  c.db = c.dir / "materials-db.h5";
  c.output = c.dir / "thermal.h5";
  return c;
}

void write_inputs(const Case& c) {
  write_solid(c);
  write_flow(c);
  write_model(c);
  write_db(c);
}

heat::Options options_of(const Case& c) {
  heat::Options o;
  o.solid_mesh = c.solid;
  o.flow = c.flow;
  o.model = c.model;
  o.material_db = c.db;
  o.output = c.output;
  o.environment_temperature = kEnvironment;
  o.newton.temperature_tolerance = 1e-10;
  return o;
}

std::string bad_input_message(const Case& c) {
  std::ostringstream sink;
  const Logger log("tfmb-heat", Verbosity::quiet, sink);
  try {
    heat::run(options_of(c), log);
  } catch (const BadInput& error) {
    return error.what();
  }
  return "no BadInput";
}

}  // namespace

TEST(HeatStage, FlatFlapConvectionRadiationMatchesOneDimensionalBalance) {
  auto c = make_case("flat");
  write_inputs(c);
  std::ostringstream sink;
  const Logger log("tfmb-heat", Verbosity::quiet, sink);
  ASSERT_EQ(heat::run(options_of(c), log), 0);

  // 1D through the thickness: q = h (T_aw - T_in) = k (T_in - T_out) / t = eps sigma (T_out^4 - T_env^4).
  auto radiated = [](double t) { return kEmissivity * heat::kStefanBoltzmann * (std::pow(t, 4) - std::pow(kEnvironment, 4)); };
  auto outer_of = [&](double t_in) {  // T_out from the conduction balance, by bisection
    double lo = kEnvironment, hi = t_in;
    for (int i = 0; i < 200; ++i) {
      const double mid = 0.5 * (lo + hi);
      (kConductivity * (t_in - mid) / kThickness > radiated(mid) ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
  };
  double lo = kEnvironment, hi = kTaw;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (kH * (kTaw - mid) > radiated(outer_of(mid)) ? lo : hi) = mid;
  }
  const double t_in = 0.5 * (lo + hi), t_out = outer_of(t_in);

  const auto file = formats::open_checked(c.output, "thermal");  // passes the thermal schema
  const auto mean = file.read_vector("/beam/f0/mean_temperature", kElements);
  const auto delta = file.read_vector("/beam/f0/delta_temperature", kElements);
  std::printf("flat flap: T_in %.6f K, T_out %.6f K; beam 0 mean %.6f K, delta %.6f K\n", t_in, t_out, mean[0], delta[0]);
  for (int e = 0; e < kElements; ++e) {
    // Linear elements reproduce the linear 1D profile: tolerance from the Newton tolerance.
    EXPECT_NEAR(mean[e], 0.5 * (t_in + t_out), 1e-7);
    EXPECT_NEAR(delta[e], t_out - t_in, 1e-7);
  }
  const auto t = file.read_vector("/fields/point/temperature");
  EXPECT_NEAR(*std::max_element(t.begin(), t.end()), t_in, 1e-7);
  const auto flux = file.read_matrix("/fields/point/heat_flux", t.size(), 3);
  EXPECT_NEAR(flux(0, 1), kH * (kTaw - t_in), 1e-6 * kH * kTaw);  // towards +y (outer)
  EXPECT_TRUE(fs::exists(c.dir / "thermal.xdmf"));
}

TEST(HeatStage, JointConductanceCouplesFlapEnds) {
  // Two flaps with imposed inner wall temperatures 900 K and 500 K, adiabatic elsewhere: without
  // joint conductance each flap is uniform; with it, heat crosses the gap between f0's end and
  // f1's start, cooling f0's last beam element and heating f1's first.
  for (double conductance : {0.0, 2000.0}) {
    auto c = make_case(conductance > 0 ? "joint_on" : "joint_off");
    c.two_flaps = true;
    c.solid_boundary = "wall_temperature";
    write_inputs(c);
    auto options = options_of(c);
    options.joint_conductance = conductance;
    std::ostringstream sink;
    const Logger log("tfmb-heat", Verbosity::quiet, sink);
    ASSERT_EQ(heat::run(options, log), 0);
    const auto file = formats::open_checked(c.output, "thermal");
    const auto f0 = file.read_vector("/beam/f0/mean_temperature", kElements);
    const auto f1 = file.read_vector("/beam/f1/mean_temperature", kElements);
    std::printf("joint conductance %.0f: f0 last element %.4f K, f1 first element %.4f K\n",
                conductance, f0.back(), f1.front());
    EXPECT_NEAR(f0.front(), kTaw, 1e-6);
    EXPECT_NEAR(f1.back(), 500.0, 1e-6);
    if (conductance > 0) {
      EXPECT_LT(f0.back(), kTaw - 0.1);
      EXPECT_GT(f1.front(), 500.0 + 0.1);
    } else {
      EXPECT_NEAR(f0.back(), kTaw, 1e-6);
      EXPECT_NEAR(f1.front(), 500.0, 1e-6);
    }
  }
}

TEST(HeatStage, BadInputsExitThreeWithClearMessages) {
  {
    auto c = make_case("zero_k");
    c.k_value = 0.0;
    write_inputs(c);
    const auto message = bad_input_message(c);
    // The database reader refuses it (formats/material_db: one check for every stage).
    EXPECT_NE(message.find("/materials/alloy/conductivity/value: row 0"), std::string::npos)
        << message;
    EXPECT_NE(message.find("must be positive"), std::string::npos) << message;
  }
  {
    auto c = make_case("narrow_table");
    c.k_temperatures = {200.0, 500.0};  // the inner face reaches ~800 K
    write_inputs(c);
    const auto message = bad_input_message(c);
    EXPECT_NE(message.find("outside the property table of material 'alloy'"), std::string::npos) << message;
  }
  {
    auto c = make_case("missing_h");
    c.with_h_trace = false;
    write_inputs(c);
    const auto message = bad_input_message(c);
    EXPECT_NE(message.find("/walls/sample/heat_transfer_coefficient: missing, needed by"), std::string::npos) << message;
    // The executable maps it to exit code 3.
    const std::string command = std::string(TFMB_BIN_DIR) + "/tfmb-heat " + c.solid.string() + " " +
                                c.flow.string() + " " + c.model.string() + " --db " + c.db.string() +
                                " -o " + c.output.string() + " -q 2> " + (c.dir / "stderr.txt").string();
    const int status = std::system(command.c_str());
    ASSERT_TRUE(WIFEXITED(status));
    EXPECT_EQ(WEXITSTATUS(status), 3);
    EXPECT_FALSE(fs::exists(c.output));
  }
}
