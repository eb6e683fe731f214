// The material-db kind's one reader: formats/material-db.md (schema in schema_material_db.cpp;
// the writer is workflows/build-material-db).
#include "tfmb/formats/material_db.hpp"

#include <cctype>
#include <cstdlib>
#include <sstream>

#include "tfmb/common/h5.hpp"
#include "tfmb/common/paths.hpp"
#include "tfmb/formats/schema.hpp"

namespace tfmb::formats {
namespace {

// Case and the separators people write differently ("Ti-6Al-4V", "ti 6al 4v") do not matter.
std::string normalise(const std::string& name) {
  std::string out;
  for (char c : name) {
    if (c == ' ' || c == '-' || c == '_')
      continue;
    out.push_back(static_cast<char>(std::tolower(static_cast<unsigned char>(c))));
  }
  return out;
}

// The physical range of a property's values (material-db.md): every property but the thermal
// expansion coefficient is positive, the Poisson ratio below 1/2. A negative conductivity or
// modulus would pass every later stage and give a result with the wrong sign.
void check_values(const h5::Reader& r, const std::string& path, const std::string& property,
                  const std::vector<double>& values) {
  for (std::size_t i = 0; i < values.size(); ++i) {
    const double v = values[i];
    const bool ok = property == "thermal_expansion" ? true
                    : property == "poisson_ratio"   ? (v > 0.0 && v < 0.5)
                                                    : v > 0.0;
    if (!ok)
      r.fail(path, "row " + std::to_string(i) + ": " + std::to_string(v) + " is not a physical " +
                       property +
                       (property == "poisson_ratio" ? " (0 < nu < 0.5)" : " (must be positive)"));
  }
}

}  // namespace

bool same_material_name(const std::string& a, const std::string& b) {
  return normalise(a) == normalise(b);
}

const DatabaseMaterial* MaterialDatabase::find(const std::string& name) const {
  for (const DatabaseMaterial& m : materials)
    if (same_material_name(m.name, name))
      return &m;
  for (const DatabaseMaterial& m : materials)
    for (const auto& alias : m.aliases)
      if (same_material_name(alias, name))
        return &m;
  return nullptr;
}

MaterialDatabase read_material_db(const std::filesystem::path& file) {
  const h5::Reader r = open_checked(file, "material-db");
  MaterialDatabase db;
  db.source = file;
  if (r.has_attr("/", "default_titanium"))
    db.default_titanium = r.attr_string("/", "default_titanium");
  for (const std::string& name : r.children("/materials")) {
    const std::string g = "/materials/" + name;
    DatabaseMaterial m;
    m.name = name;
    m.description = r.attr_string(g, "description");
    m.reference_temperature = r.attr_f64(g, "reference_temperature");
    m.missing = r.attr_string(g, "missing");
    std::stringstream aliases(r.attr_string(g, "aliases"));
    for (std::string alias; std::getline(aliases, alias, ',');)
      if (!alias.empty())
        m.aliases.push_back(alias);
    for (const std::string& property : r.children(g)) {
      const std::string p = g + "/" + property;
      MaterialProperty t;
      t.temperature = r.read_vector(p + "/temperature");
      t.value = r.read_vector(p + "/value", t.temperature.size());
      t.units = r.attr_string(p + "/value", "units");
      t.exactness = r.attr_string(p, "exactness");
      if (t.temperature.empty())
        r.fail(p + "/temperature", "empty table");
      for (std::size_t i = 1; i < t.temperature.size(); ++i)
        if (!(t.temperature[i] > t.temperature[i - 1]))
          r.fail(p + "/temperature", "not strictly increasing at row " + std::to_string(i));
      check_values(r, p + "/value", property, t.value);
      m.properties[property] = std::move(t);
    }
    db.materials.push_back(std::move(m));
  }
  return db;
}

std::filesystem::path default_material_db() {
  if (const char* from_environment = std::getenv("TFMB_MATERIAL_DB");
      from_environment && *from_environment)
    return from_environment;
  // The installed database first: an installed executable must not reach back into the source
  // tree it was built from (which may have moved on, or be gone).
  if (auto installed = beside_executable(TFMB_INSTALLED_MATERIAL_DB); !installed.empty())
    return installed;
  return TFMB_SOURCE_MATERIAL_DB;
}

}  // namespace tfmb::formats
