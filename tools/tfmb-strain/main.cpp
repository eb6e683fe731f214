// tfmb-strain: mechanical, thermal and total fibre strains and margins of safety.
//
// Sample runs:
//   tfmb-strain structure.h5 materials.h5 -o strain.h5            # + summary.json next to it
//   tfmb-strain structure.h5 materials.h5 --basis force -o strain.h5 --summary s.json
#include <iostream>

#include "run.hpp"
#include "tfmb/common/cli.hpp"
#include "tfmb/common/options.hpp"

int main(int argc, char** argv) {
  CLI::App app{"Fibre strains at the inner and outer surfaces, total strain and margins of safety.",
               "tfmb-strain"};
  tfmb::cli::CommonOptions common;
  tfmb::cli::add_common_options(app, common);
  tfmb::strain::Options options;
  tfmb::cli::OptionTable table(app);
  table
      .add("structure", options.structure_file, "",
           "structure.h5: beam sectional strains and forces")
      ->required();
  table
      .add("materials", options.materials_file, "",
           "materials.h5: allowables, thermal strains, sections")
      ->required();
  table.add_output(options.output, "strain file (tfmb/strain)");
  table.add("--summary", options.summary, "",
            "summary JSON (default: summary.json next to the output)");
  std::string basis = tfmb::strain::basis_name(options.basis);
  table.add("--basis", basis, "",
            "what the structure's sectional strain is: mechanical (kinematic minus the thermal "
            "eigenstrain of materials.h5, as tfmb-beam writes it; also a beam run without "
            "thermal loads), kinematic (including free thermal expansion), or force (use N/EA "
            "and M/EI at temperature instead)",
            CLI::IsMember({"mechanical", "kinematic", "force"}));
  table.add("--worst", options.worst_count, "1", "how many lowest total margins to list");
  options.command_line = tfmb::cli::command_line(argc, argv);
  return tfmb::cli::run_main(app, argc, argv, [&] {
    options.basis = basis == "force"       ? tfmb::strain::MechanicalBasis::force
                    : basis == "kinematic" ? tfmb::strain::MechanicalBasis::kinematic
                                           : tfmb::strain::MechanicalBasis::mechanical;
    options.settings_toml = table.settings_toml();
    tfmb::Logger logger("tfmb-strain", common.verbosity());
    tfmb::strain::run(options, logger, std::cout);
    return 0;
  });
}
