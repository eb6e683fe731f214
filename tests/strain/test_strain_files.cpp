// tfmb-strain against analytic fibre strains on test structure/materials files: pure tension,
// pure bending, a free uniform temperature rise; worst locations; bad inputs exit 3.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <sstream>

#include "tfmb-strain/run.hpp"
#include "test_files.hpp"
#include "tfmb/common/errors.hpp"
#include "tfmb/formats/schema.hpp"

using namespace tfmb;
using namespace tfmb::strain;
namespace tf = tfmb::testfiles;
using tf::Vec2;

namespace {

const Logger quiet("test", Verbosity::quiet);
constexpr double kThickness = 0.004, kWidth = 0.5, kE = 1.1e11, kAllowable = 6e-3;
constexpr int kElements = 6;

std::vector<std::string> problems(const std::filesystem::path& file, const std::string& kind) {
  const h5::Reader reader(file);
  std::vector<std::string> out;
  for (const auto& p : formats::validate(reader, *formats::find_schema(kind))) out.push_back(p.object_path + ": " + p.message);
  return out;
}

// materials.h5 of one flap with uniform properties and the given free thermal strains.
void write_materials(const std::filesystem::path& file, double thermal_inner, double thermal_outer,
                     int outer_sign = 1, double thickness_attribute = kThickness) {
  formats::Document doc = tf::example_with("materials", "/flaps", {"upper"});
  const std::string g = "/flaps/upper";
  const std::size_t n = kElements;
  auto fill = [&](const std::string& name, double v, const std::string& units) {
    tf::set_f64(doc, g + "/" + name, {n}, std::vector<double>(n, v), units);
  };
  for (const auto& [name, value, units] : std::vector<std::tuple<std::string, double, std::string>>{
           {"temperature", 600.0, "K"}, {"delta_temperature", 0.0, "K"}, {"youngs_modulus", kE, "Pa"},
           {"shear_modulus", 4e10, "Pa"}, {"poisson_ratio", 0.31, "1"}, {"thermal_expansion", 9e-6, "1/K"},
           {"density", 4420.0, "kg/m^3"}, {"yield_strength", kAllowable * kE, "Pa"},
           {"ultimate_strength", 8e8, "Pa"}, {"allowable_strain", kAllowable, "1"},
           {"thermal_strain", 0.5 * (thermal_inner + thermal_outer), "1"},
           {"thermal_strain_inner", thermal_inner, "1"}, {"thermal_strain_outer", thermal_outer, "1"},
           {"thermal_curvature", (thermal_outer - thermal_inner) / kThickness, "1/m"}}) {
    fill(name, value, units);
  }
  std::vector<double> k(n * 36, 0.0), m(n * 36, 0.0);
  for (std::size_t e = 0; e < n; ++e) {
    k[e * 36] = kE * kThickness * kWidth;
    k[e * 36 + 35] = kE * kWidth * kThickness * kThickness * kThickness / 12.0;
    // Shear, torsion and out-of-plane bending: not used by the strain stage, but a section
    // matrix must not be singular (the materials reader refuses that).
    for (std::size_t d : {7u, 14u, 21u, 28u})
      k[e * 36 + d] = 1e3;
    m[e * 36] = 1.0;
  }
  tf::set_f64(doc, g + "/section_stiffness", {n, 6, 6}, k, "N, N m^2");
  tf::set_f64(doc, g + "/section_mass", {n, 6, 6}, m, "kg/m, kg m");
  formats::DatasetValue clamped;
  clamped.dtype = h5::DType::int64;
  clamped.shape = {n};
  clamped.integers.assign(n, 0);
  doc.datasets[g + "/clamped"] = clamped;
  tf::set_attr(doc, g, "thickness", thickness_attribute);
  tf::set_attr(doc, g, "width", kWidth);
  tf::set_attr(doc, g, "outer_normal_sign", static_cast<double>(outer_sign));
  formats::write_document(doc, file);
}

// structure.h5: a straight flap along x with kElements segments carrying the given sectional
// strain (gamma11, kappa3) and force (N, M3).
void write_structure(const std::filesystem::path& file, const std::vector<double>& gamma, const std::vector<double>& kappa,
                     const std::vector<double>& force, const std::vector<double>& moment, int segments = kElements,
                     const std::string& name = "upper") {
  tf::TestStructureFlap f;
  f.name = name;
  for (int i = 0; i <= segments; ++i) f.points.emplace_back(0.05 * i, 0.1);
  for (int e = 0; e < segments; ++e) {
    const auto k = static_cast<std::size_t>(e) % gamma.size();
    f.sectional_strain.push_back({gamma[k], 0, 0, 0, 0, kappa[k]});
    f.sectional_force.push_back({force[k], 0, 0, 0, 0, moment[k]});
  }
  tf::write_structure(file, {f});
}

struct Files {
  std::filesystem::path dir, structure, materials, output;
  explicit Files(const std::string& name) {
    dir = tf::temp_dir(name);
    structure = dir / "structure.h5";
    materials = dir / "materials.h5";
    output = dir / "strain.h5";
  }
  StrainResult run(MechanicalBasis basis) const {
    Options o;
    o.structure_file = structure;
    o.materials_file = materials;
    o.output = output;
    o.basis = basis;
    std::ostringstream out;
    return tfmb::strain::run(o, quiet, out);
  }
};

const double EA = kE * kThickness * kWidth;
const double EI = kE * kWidth * kThickness * kThickness * kThickness / 12.0;

}  // namespace

TEST(StrainVerification, PureTension) {
  const Files f("tension");
  const double n = 2.2e5;  // N: strain n / EA = 1e-3
  write_materials(f.materials, 0.0, 0.0);
  write_structure(f.structure, {n / EA}, {0.0}, {n}, {0.0});
  for (MechanicalBasis basis : {MechanicalBasis::mechanical, MechanicalBasis::kinematic, MechanicalBasis::force}) {
    const StrainResult r = f.run(basis);
    const auto& flap = r.flaps.at(0);
    for (std::size_t k = 0; k < flap.s.size(); ++k) {
      EXPECT_NEAR(flap.strains[k].mechanical_inner, 1e-3, 1e-15);
      EXPECT_NEAR(flap.strains[k].mechanical_outer, 1e-3, 1e-15);
      EXPECT_NEAR(flap.margin_total[k], kAllowable / 1e-3 - 1.0, 1e-12);
    }
  }
  EXPECT_TRUE(problems(f.output, "strain").empty()) << problems(f.output, "strain").front();
  EXPECT_TRUE(std::filesystem::exists(f.dir / "summary.json"));
}

TEST(StrainVerification, PureBending) {
  // Pure bending M3: kappa3 = M / EI; with the outer surface on the left (y2 = +t/2) the outer
  // fibre strain is -t/2 kappa3 and the inner +t/2 kappa3 (eps = gamma11 - y2 kappa3).
  const double m = 150.0;
  const double kappa = m / EI;
  for (int sign : {1, -1}) {
    const Files f("bending" + std::to_string(sign));
    write_materials(f.materials, 0.0, 0.0, sign);
    write_structure(f.structure, {0.0}, {kappa}, {0.0}, {m});
    for (MechanicalBasis basis : {MechanicalBasis::mechanical, MechanicalBasis::kinematic, MechanicalBasis::force}) {
      const StrainResult r = f.run(basis);
      for (const auto& s : r.flaps.at(0).strains) {
        EXPECT_NEAR(s.mechanical_outer, -sign * 0.5 * kThickness * kappa, 1e-15);
        EXPECT_NEAR(s.mechanical_inner, sign * 0.5 * kThickness * kappa, 1e-15);
      }
      // Analytic surface stress M c / I over E.
      EXPECT_NEAR(std::abs(r.worst_total.strain), m * 0.5 * kThickness / (kWidth * std::pow(kThickness, 3) / 12.0) / kE, 1e-15);
    }
  }
}

TEST(StrainVerification, FreeUniformTemperatureRiseHasNoMechanicalStrain) {
  // A free beam heated uniformly expands by the thermal strain and carries no force or moment:
  // its kinematic strain is the thermal strain, its mechanical strain (what tfmb-beam writes)
  // zero.
  const double eps_th = 9.0e-6 * (600.0 - 293.15);
  for (MechanicalBasis basis : {MechanicalBasis::mechanical, MechanicalBasis::kinematic, MechanicalBasis::force}) {
    const Files f(std::string("thermal-") + basis_name(basis));
    write_materials(f.materials, eps_th, eps_th);
    const double sectional = basis == MechanicalBasis::kinematic ? eps_th : 0.0;
    write_structure(f.structure, {sectional}, {0.0}, {0.0}, {0.0});
    const StrainResult r = f.run(basis);
    const auto& flap = r.flaps.at(0);
    for (std::size_t k = 0; k < flap.s.size(); ++k) {
      EXPECT_EQ(flap.strains[k].mechanical_inner, 0.0) << basis_name(basis);
      EXPECT_EQ(flap.strains[k].mechanical_outer, 0.0) << basis_name(basis);
      EXPECT_DOUBLE_EQ(flap.strains[k].thermal_outer, eps_th);
      EXPECT_DOUBLE_EQ(flap.strains[k].total_inner, eps_th);
      EXPECT_EQ(flap.margin_mechanical[k], kMarginCap);
      EXPECT_NEAR(flap.margin_thermal[k], kAllowable / eps_th - 1.0, 1e-12);
    }
  }
}

TEST(StrainFiles, WorstLocationAndThreeSegmentsPerElement) {
  const Files f("worst");
  write_materials(f.materials, 0.0, 0.0);
  // 3 segments per material element (a 4-node element writes 3); segment 7 carries the most.
  std::vector<double> gamma(18, 1e-4);
  gamma[7] = 2e-3;
  std::vector<double> zero(18, 0.0);
  write_structure(f.structure, gamma, zero, zero, zero, 18);
  const StrainResult r = f.run(MechanicalBasis::mechanical);
  EXPECT_EQ(r.worst_total.segment, 7u);
  EXPECT_EQ(r.worst_total.element, 2);
  EXPECT_NEAR(r.worst_total.position.x(), 0.05 * 7.5, 1e-15);
  EXPECT_NEAR(r.worst_total.margin, kAllowable / 2e-3 - 1.0, 1e-12);
  const h5::Reader file(f.output);
  EXPECT_EQ(file.attr_i64("/", "worst_segment"), 7);
  std::ifstream json(f.dir / "summary.json");
  std::stringstream text;
  text << json.rdbuf();
  EXPECT_NE(text.str().find("\"segment\": 7"), std::string::npos) << text.str();
}

TEST(StrainFiles, MismatchedStructureAndMaterialsExit3) {
  const Files f("mismatch");
  write_materials(f.materials, 0.0, 0.0);
  write_structure(f.structure, {1e-4}, {0.0}, {0.0}, {0.0}, 7);
  const std::string err = (f.dir / "err.txt").string();
  const std::string cli = std::string(TFMB_BIN_DIR) + "/tfmb-strain " + f.structure.string() + " " + f.materials.string() +
                          " -o " + f.output.string() + " 2>" + err + " >/dev/null";
  EXPECT_EQ(WEXITSTATUS(std::system(cli.c_str())), 3);
  std::ifstream in(err);
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_NE(text.str().find("/flaps/upper/segments"), std::string::npos) << text.str();
  EXPECT_NE(text.str().find("mismatched structure and materials"), std::string::npos) << text.str();
  write_structure(f.structure, {1e-4}, {0.0}, {0.0}, {0.0}, kElements, "lower");
  EXPECT_EQ(WEXITSTATUS(std::system(cli.c_str())), 3);
  EXPECT_FALSE(std::filesystem::exists(f.output));
}

// The surfaces sit at +-thickness/2 of a section whose EA and EI are the rectangle's: a thickness
// that is not sqrt(12 EI / EA) (the mutation suite's 1e300 m turned a failing margin into a
// passing one) is refused with exit 3, naming the attribute.
TEST(StrainFiles, ThicknessThatIsNotTheSectionsIsRefused) {
  const Files f("thickness");
  write_structure(f.structure, {1e-4}, {0.0}, {0.0}, {0.0});
  write_materials(f.materials, 0.0, 0.0, 1, kThickness);
  EXPECT_NO_THROW(f.run(MechanicalBasis::mechanical));
  for (const double wrong : {1.01 * kThickness, 1e300}) {
    write_materials(f.materials, 0.0, 0.0, 1, wrong);
    try {
      f.run(MechanicalBasis::mechanical);
      ADD_FAILURE() << "thickness " << wrong << " m taken";
    } catch (const BadInput& e) {
      EXPECT_NE(std::string(e.what()).find("/flaps/upper@thickness: "), std::string::npos)
          << e.what();
      EXPECT_NE(std::string(e.what()).find("that of a 0.004 m thick rectangle"), std::string::npos)
          << e.what();
    }
  }
}
