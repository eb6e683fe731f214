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
#include "tfmb/formats/materials.hpp"
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

// The materials file kind's types and writer (formats/materials.hpp).
using ElementProperties = formats::MaterialElements;
using formats::MaterialsFlap;
using formats::write_materials;

}  // namespace tfmb::matmap
