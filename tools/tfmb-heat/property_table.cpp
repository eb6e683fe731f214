#include "tfmb-heat/property_table.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace tfmb::heat {

PropertyTable::PropertyTable(std::vector<double> temperatures, std::vector<double> values)
    : temperatures_(std::move(temperatures)), values_(std::move(values)) {
  if (temperatures_.empty()) throw std::invalid_argument("property table: no points");
  if (temperatures_.size() != values_.size()) {
    throw std::invalid_argument("property table: " + std::to_string(temperatures_.size()) +
                                " temperatures but " + std::to_string(values_.size()) + " values");
  }
  for (std::size_t i = 0; i < temperatures_.size(); ++i) {
    if (!std::isfinite(temperatures_[i]) || !std::isfinite(values_[i])) {
      throw std::invalid_argument("property table: non-finite entry at row " + std::to_string(i));
    }
    if (i > 0 && !(temperatures_[i] > temperatures_[i - 1])) {
      throw std::invalid_argument("property table: temperatures not strictly increasing at row " +
                                  std::to_string(i));
    }
  }
}

bool PropertyTable::contains(double temperature) const {
  return is_constant() ||
         (temperature >= temperatures_.front() && temperature <= temperatures_.back());
}

double PropertyTable::min_temperature() const {
  return is_constant() ? -std::numeric_limits<double>::infinity() : temperatures_.front();
}

double PropertyTable::max_temperature() const {
  return is_constant() ? std::numeric_limits<double>::infinity() : temperatures_.back();
}

double PropertyTable::min_value() const { return *std::min_element(values_.begin(), values_.end()); }

std::size_t PropertyTable::segment(double temperature) const {
  // Index i of the segment [T_i, T_{i+1}] holding the temperature (table has >= 2 points).
  const auto it = std::upper_bound(temperatures_.begin(), temperatures_.end(), temperature);
  const auto i = static_cast<std::size_t>(std::max<std::ptrdiff_t>(it - temperatures_.begin() - 1, 0));
  return std::min(i, temperatures_.size() - 2);
}

double PropertyTable::value(double temperature) const {
  if (is_constant()) return values_[0];
  if (temperature <= temperatures_.front()) return values_.front();
  if (temperature >= temperatures_.back()) return values_.back();
  const auto i = segment(temperature);
  const double w = (temperature - temperatures_[i]) / (temperatures_[i + 1] - temperatures_[i]);
  return (1.0 - w) * values_[i] + w * values_[i + 1];
}

double PropertyTable::slope(double temperature) const {
  if (is_constant()) return 0.0;
  if (temperature < temperatures_.front() || temperature > temperatures_.back()) return 0.0;
  const auto i = segment(temperature);
  return (values_[i + 1] - values_[i]) / (temperatures_[i + 1] - temperatures_[i]);
}

namespace {
void require_positive(const PropertyTable& table, const std::string& material,
                      const char* property, const char* units) {
  if (table.empty()) {
    throw std::invalid_argument("material '" + material + "': no " + property + " table");
  }
  // Piecewise-linear between positive points stays positive, so checking the points suffices.
  for (std::size_t i = 0; i < table.values().size(); ++i) {
    if (!(table.values()[i] > 0.0)) {
      throw std::invalid_argument("material '" + material + "': " + property + " " +
                                  std::to_string(table.values()[i]) + " " + units + " at T = " +
                                  std::to_string(table.temperatures()[i]) +
                                  " K is not positive");
    }
  }
}
}  // namespace

void validate_material(const Material& material, bool needs_capacity) {
  require_positive(material.conductivity, material.name, "conductivity", "W/(m K)");
  if (needs_capacity) {
    require_positive(material.density, material.name, "density", "kg/m^3");
    require_positive(material.specific_heat, material.name, "specific heat", "J/(kg K)");
  }
}

double material_min_temperature(const Material& material, bool needs_capacity) {
  double t = material.conductivity.min_temperature();
  if (needs_capacity) {
    t = std::max({t, material.density.min_temperature(), material.specific_heat.min_temperature()});
  }
  return t;
}

double material_max_temperature(const Material& material, bool needs_capacity) {
  double t = material.conductivity.max_temperature();
  if (needs_capacity) {
    t = std::min({t, material.density.max_temperature(), material.specific_heat.max_temperature()});
  }
  return t;
}

}  // namespace tfmb::heat
