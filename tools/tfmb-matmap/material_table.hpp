// Material properties tabulated against temperature (one material of the material database,
// formats/material-db.md) and their linear interpolation.
//
// Between table points a property is interpolated linearly in temperature (the database's
// tables are what the sources print; no smoothing). A temperature outside a table is refused
// (OutsideTable) unless the caller clamps, which evaluates at the nearer end and reports it.
#pragma once

#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace tfmb::matmap {

struct PropertyTable {
  std::string name;                  // e.g. "youngs_modulus"
  std::string units;                 // e.g. "Pa"
  std::vector<double> temperature;   // [K], strictly increasing, at least one point
  std::vector<double> value;
  std::string exactness;             // least trustworthy point: exact_table ... derived
  double lowest() const { return temperature.front(); }
  double highest() const { return temperature.back(); }
  bool contains(double t) const { return t >= lowest() && t <= highest(); }
};

// Thrown by evaluate() without clamping.
class OutsideTable : public std::runtime_error {
 public:
  OutsideTable(const PropertyTable& table, double t);
  double temperature;
  double lowest, highest;
  std::string property;
};

struct Evaluation {
  double value = 0.0;
  bool clamped = false;  // the temperature was outside the table and the end value was used
};

// Linear interpolation in the table; exact at table points.
Evaluation evaluate(const PropertyTable& table, double temperature, bool clamp);

struct Material {
  std::string name;
  std::string description;
  std::vector<std::string> aliases;    // lower case
  double reference_temperature = 0.0;  // [K] of the mean thermal expansion coefficient
  std::string missing;                 // what the sources do not give
  std::map<std::string, PropertyTable> properties;

  const PropertyTable* find(const std::string& property) const;
  // Throws std::invalid_argument "material <name> has no <property> in the database (<missing>)".
  const PropertyTable& require(const std::string& property) const;
};

struct MaterialDatabase {
  std::vector<Material> materials;
  std::string default_titanium;
  // By name or alias, ignoring case and the characters ' ', '-', '_'; nullptr if none.
  const Material* find(const std::string& name) const;
};

}  // namespace tfmb::matmap
