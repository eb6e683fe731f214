// tfmb-strain: fibre strains at the inner and outer surfaces, thermal and total strains and
// margins of safety of every beam segment; the worst locations.
#pragma once

#include <filesystem>
#include <ostream>
#include <string>

#include "io.hpp"
#include "tfmb/common/log.hpp"

namespace tfmb::strain {

struct Options {
  std::filesystem::path structure_file;
  std::filesystem::path materials_file;
  std::filesystem::path output;
  std::filesystem::path summary;  // summary.json; empty: next to the output
  MechanicalBasis basis = MechanicalBasis::mechanical;
  int worst_count = 5;
  std::string command_line;
  std::string settings_toml;  // the command line's options (cli::OptionTable) for /provenance
};

// Throws BadInput for mismatched structure and materials files.
StrainResult run(const Options& options, const Logger& logger, std::ostream& out);

}  // namespace tfmb::strain
