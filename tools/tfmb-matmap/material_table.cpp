#include "material_table.hpp"

#include <algorithm>
#include <sstream>

#include "tfmb/common/text.hpp"
#include "tfmb/formats/material_db.hpp"

namespace tfmb::matmap {

OutsideTable::OutsideTable(const PropertyTable& table, double t)
    : std::runtime_error(text::format_number(t) + " K is outside the " + table.name + " table [" +
                         text::format_number(table.lowest()) + ", " +
                         text::format_number(table.highest()) + "] K"),
      temperature(t),
      lowest(table.lowest()),
      highest(table.highest()),
      property(table.name) {}

Evaluation evaluate(const PropertyTable& table, double t, bool clamp) {
  const auto& x = table.temperature;
  const auto& y = table.value;
  if (!table.contains(t)) {
    if (!clamp) throw OutsideTable(table, t);
    return {t < x.front() ? y.front() : y.back(), true};
  }
  // First point with x > t; t lies in [x[i-1], x[i]].
  const auto upper = std::upper_bound(x.begin(), x.end(), t);
  if (upper == x.end()) return {y.back(), false};  // t == last point
  const auto i = static_cast<std::size_t>(upper - x.begin());
  if (i == 0) return {y.front(), false};
  const double u = (t - x[i - 1]) / (x[i] - x[i - 1]);
  // Written so that u = 0 and u = 1 return the table values exactly.
  return {u == 0.0 ? y[i - 1] : (1.0 - u) * y[i - 1] + u * y[i], false};
}

const PropertyTable* Material::find(const std::string& property) const {
  auto it = properties.find(property);
  return it == properties.end() ? nullptr : &it->second;
}

const PropertyTable& Material::require(const std::string& property) const {
  if (const PropertyTable* table = find(property)) return *table;
  throw std::invalid_argument("material " + name + " has no " + property + " in the database (missing: " +
                              missing + ")");
}

const Material* MaterialDatabase::find(const std::string& name) const {
  // The database's one name rule (formats::same_material_name), as tfmb-heat resolves names.
  for (const Material& m : materials) {
    if (formats::same_material_name(m.name, name))
      return &m;
  }
  for (const Material& m : materials) {
    for (const auto& alias : m.aliases) {
      if (formats::same_material_name(alias, name))
        return &m;
    }
  }
  return nullptr;
}

}  // namespace tfmb::matmap
