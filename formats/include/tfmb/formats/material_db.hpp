// The `material-db` file kind (formats/material-db.md): temperature tables of material properties,
// written by workflows/build-material-db and read by tfmb-matmap and tfmb-heat. read_material_db
// checks the file against the kind's schema (what tfmb-check applies) and that every table's
// temperatures strictly increase; find() is the one rule by which a model's material name
// resolves.
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "tfmb/formats/files.hpp"

namespace tfmb::formats {

struct MaterialProperty {
  std::string units;                // of the values
  std::string exactness;            // least trustworthy point: exact_table ... derived
  std::vector<double> temperature;  // [K] strictly increasing, at least one point
  std::vector<double> value;
};

struct DatabaseMaterial {
  std::string name;
  std::string description;
  std::vector<std::string> aliases;
  double reference_temperature = 0.0;  // [K] of the mean thermal expansion coefficient
  std::string missing;                 // what the sources do not give
  std::map<std::string, MaterialProperty> properties;  // by property name (youngs_modulus, ...)
};

struct MaterialDatabase : ReadFrom {
  std::string default_titanium;  // material of a flap that names none ("" if not set)
  std::vector<DatabaseMaterial> materials;

  // By name or alias, ignoring case and the characters ' ', '-', '_'; nullptr if none.
  const DatabaseMaterial* find(const std::string& name) const;
};

// Whether two material names mean the same material: equal ignoring case and the characters
// ' ', '-', '_' ("Ti-6Al-4V", "ti 6al 4v"). The one rule by which names and aliases resolve.
bool same_material_name(const std::string& a, const std::string& b);

// The database a stage uses when given none: $TFMB_MATERIAL_DB if set; else the installed tree's
// (<prefix>/share/tfmb/data/materials-db.h5, found from the running executable in <prefix>/bin);
// else data/materials-db.h5 of the source tree the executable was built from (a build tree).
std::filesystem::path default_material_db();

// Reads and validates a material database (BadInput naming the file and the object on any problem).
MaterialDatabase read_material_db(const std::filesystem::path& file);

}  // namespace tfmb::formats
