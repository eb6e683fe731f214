// Layout of the "materials" file kind; prose spec in formats/materials.md.
#include "schema_rules.hpp"

namespace tfmb::formats::detail {

Schema materials_schema() {
  Schema s{"materials", "tfmb/materials", 1, 0,
           "per beam element properties at its temperature, section stiffness, thermal strains",
           false, {}, {}};
  add_root(s, true);
  s.attributes.push_back(sattr("/flaps/*", "material", "material name"));
  const std::vector<std::pair<std::string, std::string>> per_element = {
      {"temperature", "K"},       {"youngs_modulus", "Pa"},   {"shear_modulus", "Pa"},
      {"poisson_ratio", "1"},     {"thermal_expansion", "1/K"}, {"yield_strength", "Pa"},
      {"ultimate_strength", "Pa"}, {"allowable_strain", "1"},  {"thermal_strain", "1"},
      {"thermal_curvature", "1/m"}};
  for (const auto& [name, units] : per_element) {
    s.datasets.push_back(f64("/flaps/*/" + name, {"ne"}, units, "per beam element"));
  }
  s.datasets.push_back(f64("/flaps/*/section_stiffness", {"ne", "6", "6"}, "*", "N, N m^2"));
  s.datasets.push_back(f64("/flaps/*/section_mass", {"ne", "6", "6"}, "*", "kg/m, kg m"));
  s.datasets.push_back(i64("/flaps/*/clamped", {"ne"}, "2",
                           "1 if the temperature was outside the table and clamped"));
  add_provenance(s);
  return s;
}

}  // namespace tfmb::formats::detail
