// Layout of the "materials" file kind; prose spec in formats/materials.md.
#include "schema_rules.hpp"

namespace tfmb::formats::detail {

Schema materials_schema() {
  Schema s{"materials", "tfmb/materials", 1, 1,
           "per beam element properties at its temperature, section stiffness, thermal strains",
           false, {}, {}};
  add_root(s, true);
  s.attributes.push_back(sattr("/flaps/*", "material", "material name in the database"));
  s.attributes.push_back(sattr("/flaps/*", "material_given", "material name as the model gives it"));
  s.attributes.push_back(nattr("/flaps/*", "thickness", "m", "section thickness t (in the plane)", 0.0));
  s.attributes.push_back(nattr("/flaps/*", "width", "m", "section width w (depth direction)", 0.0));
  s.attributes.push_back(nattr("/flaps/*", "reference_temperature", "K",
                               "reference of the mean thermal expansion coefficient", 0.0));
  s.attributes.push_back(nattr("/flaps/*", "stress_free_temperature", "K",
                               "temperature of zero thermal strain", 0.0));
  s.attributes.push_back(nattr("/flaps/*", "outer_normal_sign", "1",
                               "+1 if the outer wall lies to the left of the reference direction "
                               "(start to end), -1 if to the right",
                               -1.0, 1.0, true, AttrType::int64));
  s.attributes.push_back(sattr("/flaps/*", "shear_modulus_basis", "database, or derived from E and a given nu"));
  s.attributes.push_back(sattr("/flaps/*", "allowable_strain_basis", "how the allowable strain was obtained"));
  s.attributes.push_back(nattr("/flaps/*", "clamped_elements", "1",
                               "elements with a temperature outside a table (--clamp)", 0.0,
                               std::nullopt, true, AttrType::int64));
  const std::vector<std::tuple<std::string, std::string, std::string, bool>> per_element = {
      {"temperature", "K", "mean temperature of the element", true},
      {"delta_temperature", "K", "outer minus inner surface temperature", true},
      {"youngs_modulus", "Pa", "at the element temperature", true},
      {"shear_modulus", "Pa", "at the element temperature", true},
      {"poisson_ratio", "1", "at the element temperature", true},
      {"thermal_expansion", "1/K", "mean coefficient from reference_temperature to the element temperature", true},
      {"density", "kg/m^3", "at the element temperature", true},
      {"yield_strength", "Pa", "at the element temperature (absent if the database has none)", false},
      {"ultimate_strength", "Pa", "at the element temperature (absent if the database has none)", false},
      {"allowable_strain", "1", "see allowable_strain_basis", true},
      {"thermal_strain", "1", "axial thermal strain of the section: thickness mean of the free thermal strain", true},
      {"thermal_strain_inner", "1", "free thermal strain at the inner surface temperature", true},
      {"thermal_strain_outer", "1", "free thermal strain at the outer surface temperature", true},
      {"thermal_curvature", "1/m",
       "(thermal_strain_outer - thermal_strain_inner) / thickness; positive: the outer surface expands more", true}};
  for (const auto& [name, units, meaning, required] : per_element) {
    s.datasets.push_back(f64("/flaps/*/" + name, {"ne"}, units, meaning, required));
  }
  s.datasets.push_back(f64("/flaps/*/section_stiffness", {"ne", "6", "6"}, "*",
                           "rectangle thickness x width: N, N m^2 (order of model.md)"));
  s.datasets.push_back(f64("/flaps/*/section_mass", {"ne", "6", "6"}, "*", "kg/m, kg m"));
  s.datasets.push_back(i64("/flaps/*/clamped", {"ne"}, "2",
                           "1 if a temperature of the element was outside a table and clamped"));
  add_provenance(s);
  return s;
}

}  // namespace tfmb::formats::detail
