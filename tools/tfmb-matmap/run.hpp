// tfmb-matmap: per beam element material properties at the element temperature, section
// stiffness and mass from the section geometry, thermal strains and curvature.
#pragma once

#include <filesystem>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "io.hpp"
#include "tfmb/common/log.hpp"

namespace tfmb::matmap {

struct Options {
  std::filesystem::path thermal_file;
  std::filesystem::path model_file;
  std::filesystem::path database_file;
  std::filesystem::path output;
  bool clamp = false;  // use table end values outside a table (flagged) instead of refusing
  // Stress-free temperature [K]; default: the model's /thermal@reference_temperature, else each
  // material's reference temperature (so the strain is alpha_mean (T - T_ref)).
  std::optional<double> stress_free_temperature;
  // For materials the database gives no Poisson ratio or shear modulus for: nu, and
  // G = E / (2 (1 + nu)).
  std::optional<double> poisson_ratio;
  // For materials without a yield strength in the database: a temperature-independent
  // allowable strain [1].
  std::optional<double> allowable_strain;
  std::string command_line;
  std::string settings_toml;  // the command line's options (cli::OptionTable) for /provenance
};

struct Result {
  std::vector<MaterialsFlap> flaps;
  std::size_t clamped_elements = 0;
};

// Throws BadInput for unknown materials, mismatched files, NaN or out-of-table temperatures.
Result run(const Options& options, const Logger& logger, std::ostream& out);

}  // namespace tfmb::matmap
