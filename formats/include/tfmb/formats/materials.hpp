// The `materials` file kind (formats/materials.md): material properties, section matrices and
// thermal strains per beam element, written by tfmb-matmap and read by tfmb-beam and
// tfmb-strain. read_materials checks the file against the kind's schema (what tfmb-check
// applies) and what the schema cannot say (one entry per element everywhere, a section that is
// not singular, positive allowable strains).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "tfmb/formats/files.hpp"

namespace tfmb::formats {

// Per beam element of a flap; every vector has one entry per element.
struct MaterialElements {
  std::vector<double> temperature;                        // [K] element mean
  std::vector<double> delta_temperature;                  // [K] outer minus inner surface
  std::vector<double> youngs_modulus, shear_modulus;      // [Pa]
  std::vector<double> poisson_ratio;                      // [1]
  std::vector<double> thermal_expansion;                  // [1/K] mean from reference_temperature
  std::vector<double> density;                            // [kg/m^3]
  std::vector<double> yield_strength, ultimate_strength;  // [Pa]; empty if the database has none
  std::vector<double> allowable_strain;                   // [1]
  std::vector<double> thermal_strain;                     // [1] thickness mean of the free strain
  std::vector<double> thermal_strain_inner, thermal_strain_outer;  // [1] at the surfaces
  std::vector<double> thermal_curvature;                       // [1/m] (outer - inner) / thickness
  std::vector<Eigen::Matrix<double, 6, 6>> section_stiffness;  // [N, N m^2] (model.md order)
  std::vector<Eigen::Matrix<double, 6, 6>> section_mass;       // [kg/m, kg m]
  std::vector<std::int64_t> clamped;  // 1: a temperature was outside a table (end value used)

  std::size_t size() const { return temperature.size(); }
};

struct MaterialsFlap {
  std::string name;
  std::string material;                  // database name
  std::string material_given;            // as the model names it
  double thickness = 0.0, width = 0.0;   // [m]
  double reference_temperature = 0.0;    // [K] of the mean expansion coefficient
  double stress_free_temperature = 0.0;  // [K]
  int outer_normal_sign = 1;             // +1: the outer wall is left of the reference direction
  std::string shear_modulus_basis, allowable_strain_basis;
  bool has_strength = true;  // yield and ultimate strength given
  MaterialElements elements;
};

struct Materials : ReadFrom {
  Header header;
  std::vector<MaterialsFlap> flaps;  // by name

  const MaterialsFlap* find(const std::string& name) const { return find_named(flaps, name); }
};

// Writes materials.h5 atomically (header with `creator`, flaps, provenance).
void write_materials(const std::filesystem::path& file, const Header& header,
                     const std::vector<MaterialsFlap>& flaps, const Provenance& provenance);
// Reads and validates a materials file (BadInput naming the file and the object on any problem).
Materials read_materials(const std::filesystem::path& file);

}  // namespace tfmb::formats
