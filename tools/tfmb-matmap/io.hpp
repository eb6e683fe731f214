// Every file tfmb-matmap reads or writes goes through here (formats/material-db.md,
// thermal.md, model.md, materials.md), so a layout change is adapted in one place.
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "material_table.hpp"
#include "section.hpp"
#include "tfmb/formats/files.hpp"
#include "tfmb/formats/model.hpp"

namespace tfmb::matmap {

MaterialDatabase read_material_db(const std::filesystem::path& file);

// A flap of the model (formats' type) and which side its outer wall is on.
struct ModelFlap : formats::Flap {
  // +1 if the outer wall lies to the left of the reference direction (start to end), -1 if
  // to the right (from the model's walls).
  int outer_normal_sign = 1;
};
struct Model {
  formats::Header header;
  std::vector<ModelFlap> flaps;
  std::optional<double> stress_free_temperature;  // /thermal@reference_temperature if present
};
Model read_model(const std::filesystem::path& file);

struct ThermalFlap {
  std::vector<double> mean_temperature;   // [K] per beam element
  std::vector<double> delta_temperature;  // [K] outer minus inner
};
std::map<std::string, ThermalFlap> read_thermal(const std::filesystem::path& file);

struct ElementProperties {
  std::vector<double> temperature, delta_temperature, youngs_modulus, shear_modulus, poisson_ratio,
      thermal_expansion, density, yield_strength, ultimate_strength, allowable_strain, thermal_strain,
      thermal_strain_inner, thermal_strain_outer, thermal_curvature;
  std::vector<Matrix6> section_stiffness, section_mass;
  std::vector<std::int64_t> clamped;
};

struct MaterialsFlap {
  std::string name;
  std::string material;        // database name
  std::string material_given;  // as the model names it
  double thickness = 0.0, width = 0.0;
  double reference_temperature = 0.0;    // of alpha_mean [K]
  double stress_free_temperature = 0.0;  // [K]
  int outer_normal_sign = 1;             // see ModelFlap
  std::string shear_modulus_basis, allowable_strain_basis;
  bool has_strength = true;
  ElementProperties elements;
};

void write_materials(const std::filesystem::path& file, const formats::Header& header,
                     const std::vector<MaterialsFlap>& flaps, const formats::Provenance& provenance);

}  // namespace tfmb::matmap
