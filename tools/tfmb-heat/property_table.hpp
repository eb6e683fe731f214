#pragma once
// Temperature-dependent material properties as tabulated piecewise-linear functions.
#include <string>
#include <vector>

namespace tfmb::heat {

/// value(T) interpolated linearly between table points. A one-point table is a constant valid at
/// every temperature; otherwise temperatures outside [T_front, T_back] are outside the table.
class PropertyTable {
 public:
  PropertyTable() = default;
  /// Throws std::invalid_argument if sizes differ, the table is empty, temperatures are not
  /// strictly increasing or a value is not finite.
  PropertyTable(std::vector<double> temperatures, std::vector<double> values);
  static PropertyTable constant(double value) { return PropertyTable({0.0}, {value}); }

  bool empty() const { return temperatures_.empty(); }
  bool is_constant() const { return temperatures_.size() == 1; }
  bool contains(double temperature) const;
  double min_temperature() const;  // [K]; -inf for a constant
  double max_temperature() const;  // [K]; +inf for a constant
  double min_value() const;

  /// Value at T, clamped to the end values outside the table (used inside Newton iterations,
  /// where an intermediate iterate may overshoot; the converged field is checked separately).
  double value(double temperature) const;
  /// d value / dT at T (zero outside the table, consistent with the clamping).
  double slope(double temperature) const;

  const std::vector<double>& temperatures() const { return temperatures_; }
  const std::vector<double>& values() const { return values_; }

 private:
  std::size_t segment(double temperature) const;
  std::vector<double> temperatures_;  // [K]
  std::vector<double> values_;
};

struct Material {
  std::string name;
  PropertyTable conductivity;   // k [W/(m K)]
  PropertyTable density;        // rho [kg/m^3]
  PropertyTable specific_heat;  // cp [J/(kg K)]
};

/// Throws std::invalid_argument when a property is missing or not strictly positive.
/// Density and specific heat are only required when `needs_capacity` (transient runs).
void validate_material(const Material& material, bool needs_capacity);

/// Temperature range over which every property of the material is tabulated.
double material_min_temperature(const Material& material, bool needs_capacity);
double material_max_temperature(const Material& material, bool needs_capacity);

}  // namespace tfmb::heat
