// tfmb-matmap on the committed material database and on test thermal/model files: exact at
// table points, linear between, clamped and refused cases, bad inputs exit 3.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <sstream>

#include "tfmb-matmap/io.hpp"
#include "tfmb-matmap/run.hpp"
#include "test_files.hpp"
#include "tfmb/common/errors.hpp"
#include "tfmb/formats/schema.hpp"

using namespace tfmb;
using namespace tfmb::matmap;
namespace tf = tfmb::testfiles;

namespace {

const std::filesystem::path database = std::filesystem::path(TFMB_SOURCE_DIR) / "data" / "materials-db.h5";

std::vector<std::string> problems(const std::filesystem::path& file, const std::string& kind) {
  const h5::Reader reader(file);
  std::vector<std::string> out;
  for (const auto& p : formats::validate(reader, *formats::find_schema(kind))) out.push_back(p.object_path + ": " + p.message);
  return out;
}

int run_cli(const std::string& arguments, std::string* stderr_text) {
  const std::string err = (tf::process_temp_root() / "matmap-stderr.txt").string();
  const int status = std::system((std::string(TFMB_BIN_DIR) + "/tfmb-matmap " + arguments + " 2>" + err + " >/dev/null").c_str());
  std::ifstream in(err);
  std::stringstream s;
  s << in.rdbuf();
  *stderr_text = s.str();
  return WEXITSTATUS(status);
}

// One straight Ti-6Al-4V flap with the given element temperatures.
struct Case {
  std::filesystem::path dir, model, thermal, output;
  Case(const std::string& name, const std::vector<double>& temperature, const std::vector<double>& delta,
       const std::string& material = "Ti-6Al-4V") {
    dir = tf::temp_dir(name);
    model = dir / "model.h5";
    thermal = dir / "thermal.h5";
    output = dir / "materials.h5";
    auto flap = tf::straight_flap("upper", {0.0, 0.1}, 0.1, 0.3, static_cast<int>(temperature.size()) + 1, 7);
    flap.material = material;
    tf::write_model(model, {flap});
    tf::write_thermal(thermal, {{"upper", {temperature, delta}}});
  }
  Options options() const {
    Options o;
    o.thermal_file = thermal;
    o.model_file = model;
    o.database_file = database;
    o.output = output;
    return o;
  }
};

}  // namespace

TEST(MaterialDb, CommittedDatabaseIsValidAndComplete) {
  const auto p = problems(database, "material-db");
  ASSERT_TRUE(p.empty()) << p.front();
  const MaterialDatabase db = read_material_db(database);
  const Material* ti = db.find("titanium");
  ASSERT_NE(ti, nullptr);
  EXPECT_EQ(ti->name, "Ti-6Al-4V");
  for (const char* property : {"youngs_modulus", "shear_modulus", "poisson_ratio", "thermal_expansion",
                               "conductivity", "specific_heat", "density", "yield_strength",
                               "ultimate_strength", "allowable_strain"}) {
    EXPECT_NE(ti->find(property), nullptr) << property;
  }
  ASSERT_NE(db.find("Inconel 718"), nullptr);
  ASSERT_NE(db.find("Ti-6Al-2Nb-1Ta-1Mo"), nullptr);
  // Every table keeps its source and exactness.
  const h5::Reader reader(database);
  for (const auto& m : db.materials) {
    for (const auto& [name, table] : m.properties) {
      const std::string g = "/materials/" + m.name + "/" + name;
      EXPECT_FALSE(reader.attr_string(g, "source").empty()) << g;
      EXPECT_EQ(reader.read_strings(g + "/point_source").size(), table.temperature.size()) << g;
    }
  }
}

// The committed database is what the builder makes from the reference CSVs today.
TEST(MaterialDb, CommittedDatabaseMatchesARebuild) {
  const std::filesystem::path refdata = std::filesystem::path(TFMB_SOURCE_DIR) / "refdata" / "materials";
  if (!std::filesystem::exists(refdata)) GTEST_SKIP() << "refdata not on this machine";
  const auto dir = tf::temp_dir("rebuild");
  const auto rebuilt = dir / "materials-db.h5";
  const std::string command = std::string(TFMB_SOURCE_DIR) + "/workflows/build-material-db --refdata " +
                              refdata.string() + " -o " + rebuilt.string() + " 2>/dev/null";
  ASSERT_EQ(std::system(command.c_str()), 0);
  std::ifstream a(database, std::ios::binary), b(rebuilt, std::ios::binary);
  const std::string bytes_a((std::istreambuf_iterator<char>(a)), {}), bytes_b((std::istreambuf_iterator<char>(b)), {});
  EXPECT_TRUE(bytes_a == bytes_b) << "data/materials-db.h5 is stale: run workflows/build-material-db -o data/materials-db.h5";
}

TEST(Matmap, ExactAtTablePointsAndLinearBetween) {
  const MaterialDatabase db = read_material_db(database);
  const Material& ti = *db.find("Ti-6Al-4V");
  const PropertyTable& yield = ti.require("yield_strength");
  const PropertyTable& E = ti.require("youngs_modulus");
  const PropertyTable& alpha = ti.require("thermal_expansion");
  // Element temperatures: yield table points and midpoints between them.
  std::vector<double> temperature;
  for (std::size_t i = 1; i < yield.temperature.size(); ++i) {
    temperature.push_back(yield.temperature[i]);
    temperature.push_back(0.5 * (yield.temperature[i - 1] + yield.temperature[i]));
  }
  const Case c("table", temperature, std::vector<double>(temperature.size(), 0.0));
  Options o = c.options();
  o.stress_free_temperature = ti.reference_temperature;
  std::ostringstream out;
  const Logger quiet("test", Verbosity::quiet);
  const Result r = run(o, quiet, out);
  ASSERT_TRUE(problems(c.output, "materials").empty()) << problems(c.output, "materials").front();
  const ElementProperties& e = r.flaps.at(0).elements;
  for (std::size_t k = 0; k < temperature.size(); ++k) {
    const double t = temperature[k];
    if (k % 2 == 0) {
      EXPECT_EQ(e.yield_strength[k], yield.value[k / 2 + 1]) << t;  // exact at a table point
    } else {
      EXPECT_NEAR(e.yield_strength[k], 0.5 * (yield.value[k / 2] + yield.value[k / 2 + 1]), 1e-6) << t;
    }
    // Linear interpolation in E's own table, and the thermal strain alpha_mean (T - Tref).
    const auto upper = std::upper_bound(E.temperature.begin(), E.temperature.end(), t);
    const std::size_t i = static_cast<std::size_t>(upper - E.temperature.begin());
    const double u = (t - E.temperature[i - 1]) / (E.temperature[i] - E.temperature[i - 1]);
    EXPECT_NEAR(e.youngs_modulus[k], (1 - u) * E.value[i - 1] + u * E.value[i], 1e-4 * E.value[0] * 1e-6) << t;
    const auto ua = std::upper_bound(alpha.temperature.begin(), alpha.temperature.end(), t);
    const std::size_t j = static_cast<std::size_t>(ua - alpha.temperature.begin());
    const double v = (t - alpha.temperature[j - 1]) / (alpha.temperature[j] - alpha.temperature[j - 1]);
    const double a = (1 - v) * alpha.value[j - 1] + v * alpha.value[j];
    EXPECT_NEAR(e.thermal_strain[k], a * (t - ti.reference_temperature), 1e-15) << t;
    EXPECT_NEAR(e.allowable_strain[k] * 0 + e.section_stiffness[k](5, 5),
                e.youngs_modulus[k] * 0.5 * std::pow(0.004, 3) / 12.0, 1e-9 * e.section_stiffness[k](5, 5));
    EXPECT_EQ(e.clamped[k], 0);
    EXPECT_EQ(e.thermal_curvature[k], 0.0);  // no through-thickness difference
  }
  EXPECT_NE(out.str().find("Ti-6Al-4V"), std::string::npos);
  EXPECT_EQ(r.flaps.at(0).outer_normal_sign, 1);  // the test flap has its outer wall on the left
}

TEST(Matmap, ThermalCurvatureFromTheSurfaceStrains) {
  const Case c("curvature", {500.0, 600.0}, {40.0, -20.0});
  Options o = c.options();
  const Logger quiet("test", Verbosity::quiet);
  std::ostringstream out;
  const Result r = run(o, quiet, out);
  const MaterialDatabase db = read_material_db(database);
  const PropertyTable& alpha = db.find("Ti-6Al-4V")->require("thermal_expansion");
  const double tref = db.find("Ti-6Al-4V")->reference_temperature;
  const auto& e = r.flaps[0].elements;
  for (std::size_t k = 0; k < 2; ++k) {
    // Free strain from the model's stress-free temperature (293.15 K, test_files.hpp).
    const double t0 = r.flaps[0].stress_free_temperature;
    EXPECT_EQ(t0, 293.15);
    auto eps = [&](double t) {
      return evaluate(alpha, t, false).value * (t - tref) - evaluate(alpha, t0, false).value * (t0 - tref);
    };
    const double t = e.temperature[k], dt = e.delta_temperature[k];
    EXPECT_NEAR(e.thermal_curvature[k], (eps(t + dt / 2) - eps(t - dt / 2)) / 0.004, 1e-12);
    // Both surfaces lie in one table segment, where alpha_mean is linear and the strain
    // quadratic in T: the secant equals alpha_inst dT / t with the instantaneous coefficient
    // alpha_inst = d(alpha_mean (T - Tref))/dT = alpha_mean + (T - Tref) alpha_mean'.
    const auto upper = std::upper_bound(alpha.temperature.begin(), alpha.temperature.end(), t);
    const auto i = static_cast<std::size_t>(upper - alpha.temperature.begin());
    const double slope = (alpha.value[i] - alpha.value[i - 1]) / (alpha.temperature[i] - alpha.temperature[i - 1]);
    const double alpha_inst = evaluate(alpha, t, false).value + (t - tref) * slope;
    EXPECT_NEAR(e.thermal_curvature[k], alpha_inst * dt / 0.004, 1e-12);
    // The section's axial thermal strain is the thickness mean of the free strain (midpoint
    // rule with 2000 layers as the reference; its error is O(1e-7) of the quadratic term).
    double mean = 0.0;
    for (int layer = 0; layer < 2000; ++layer) mean += eps(t - dt / 2 + dt * (layer + 0.5) / 2000.0) / 2000.0;
    EXPECT_NEAR(e.thermal_strain[k], mean, 1e-13);
    EXPECT_GT(std::abs(e.thermal_strain[k] - eps(t)), 1e-9);  // the quadratic term is seen
  }
}

TEST(Matmap, OutsideTheTableIsRefusedOrClampedAndFlagged) {
  // Ti-6Al-4V strengths end at 810.9 K (1000 F).
  const Case c("clamp", {400.0, 900.0, 500.0}, {0.0, 0.0, 0.0});
  Options o = c.options();
  const Logger quiet("test", Verbosity::quiet);
  std::ostringstream out;
  try {
    run(o, quiet, out);
    FAIL() << "expected BadInput";
  } catch (const BadInput& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find(c.thermal.string() + ": /beam/upper/mean_temperature[1]"), std::string::npos) << m;
    EXPECT_NE(m.find("900 K is outside the yield_strength table"), std::string::npos) << m;
    EXPECT_NE(m.find("--clamp"), std::string::npos) << m;
  }
  EXPECT_FALSE(std::filesystem::exists(c.output));
  std::string err;
  EXPECT_EQ(run_cli(c.thermal.string() + " " + c.model.string() + " --db " + database.string() + " -o " +
                    c.output.string(), &err), 3);
  // Clamped: the end value, the element flagged in the file and on stderr.
  o.clamp = true;
  std::ostringstream log;
  const Logger logger("test", Verbosity::normal, log);
  const Result r = run(o, logger, out);
  const auto& e = r.flaps[0].elements;
  EXPECT_EQ(e.clamped, (std::vector<std::int64_t>{0, 1, 0}));
  const MaterialDatabase db = read_material_db(database);
  const PropertyTable& yield = db.find("Ti-6Al-4V")->require("yield_strength");
  EXPECT_EQ(e.yield_strength[1], yield.value.back());
  EXPECT_NE(log.str().find("flap upper element 1: clamped"), std::string::npos) << log.str();
  EXPECT_EQ(r.clamped_elements, 1u);
  const h5::Reader file(c.output);
  EXPECT_EQ(file.attr_i64("/flaps/upper", "clamped_elements"), 1);
  EXPECT_EQ(run_cli(c.thermal.string() + " " + c.model.string() + " --db " + database.string() + " --clamp -o " +
                    c.output.string(), &err), 0);
  EXPECT_NE(err.find("clamped"), std::string::npos) << err;
}

TEST(Matmap, BadInputsExit3WithALocatedMessage) {
  std::string err;
  // NaN temperature.
  const Case nan("nan", {400.0, std::nan(""), 500.0}, {0.0, 0.0, 0.0});
  EXPECT_EQ(run_cli(nan.thermal.string() + " " + nan.model.string() + " --db " + database.string() + " -o " +
                    nan.output.string(), &err), 3);
  EXPECT_NE(err.find("/beam/upper/mean_temperature"), std::string::npos) << err;
  // Element count differs from the model's beam.
  Case mismatch("mismatch", {400.0, 450.0}, {0.0, 0.0});
  tf::write_thermal(mismatch.thermal, {{"upper", {{400.0, 450.0, 470.0}, {0.0, 0.0, 0.0}}}});
  EXPECT_EQ(run_cli(mismatch.thermal.string() + " " + mismatch.model.string() + " --db " + database.string() +
                    " -o " + mismatch.output.string(), &err), 3);
  EXPECT_NE(err.find("mismatched model and thermal"), std::string::npos) << err;
  // A material the database does not have, and one without strengths.
  const Case steel("steel", {400.0}, {0.0}, "steel");
  EXPECT_EQ(run_cli(steel.thermal.string() + " " + steel.model.string() + " --db " + database.string() + " -o " +
                    steel.output.string(), &err), 3);
  EXPECT_NE(err.find("material 'steel'"), std::string::npos) << err;
  const Case in718("in718", {400.0}, {0.0}, "Inconel 718");
  EXPECT_EQ(run_cli(in718.thermal.string() + " " + in718.model.string() + " --db " + database.string() + " -o " +
                    in718.output.string(), &err), 3);
  EXPECT_NE(err.find("--poisson-ratio"), std::string::npos) << err;
  EXPECT_EQ(run_cli(in718.thermal.string() + " " + in718.model.string() + " --db " + database.string() +
                    " --poisson-ratio 0.29 --allowable-strain 0.005 --stress-free-temperature 300 -o " +
                    in718.output.string(), &err), 0) << err;
  // A stress-free temperature below its CTE table (0 F = 255.37 K) is refused, naming the option.
  EXPECT_EQ(run_cli(in718.thermal.string() + " " + in718.model.string() + " --db " + database.string() +
                    " --poisson-ratio 0.29 --allowable-strain 0.005 --stress-free-temperature 250 -o " +
                    in718.output.string(), &err), 3);
  EXPECT_NE(err.find("--stress-free-temperature: stress-free temperature 250 K"), std::string::npos) << err;
}
