// tfmb-strain: mechanical, thermal and total fibre strains and margins of safety.
//
// Sample runs:
//   tfmb-strain structure.h5 materials.h5 -o strain.h5            # + summary.json next to it
//   tfmb-strain structure.h5 materials.h5 --mechanical force -o strain.h5 --summary s.json
#include <iostream>

#include "run.hpp"
#include "tfmb/common/cli.hpp"

int main(int argc, char** argv) {
  CLI::App app{"Fibre strains at the inner and outer surfaces, total strain and margins of safety.",
               "tfmb-strain"};
  tfmb::cli::CommonOptions common;
  tfmb::cli::add_common_options(app, common);
  tfmb::strain::Options options;
  app.add_option("structure", options.structure_file, "structure.h5: beam sectional strains and forces")->required();
  app.add_option("materials", options.materials_file, "materials.h5: allowables, thermal strains, sections")->required();
  tfmb::cli::add_output_option(app, options.output, "strain file (tfmb/strain)");
  app.add_option("--summary", options.summary, "summary JSON (default: summary.json next to the output)");
  std::string basis = "strain-minus-thermal";
  app.add_option("--mechanical", basis,
                 "how to get the mechanical strain: strain-minus-thermal (the beam's sectional strain "
                 "includes free thermal expansion), strain (it is purely mechanical), force (N/EA and "
                 "M/EI at temperature)")
      ->check(CLI::IsMember({"strain-minus-thermal", "strain", "force"}))->capture_default_str();
  app.add_option("--worst", options.worst_count, "how many lowest total margins to list")->capture_default_str();
  options.command_line = tfmb::cli::command_line(argc, argv);
  return tfmb::cli::run_main(app, argc, argv, [&] {
    options.basis = basis == "force"    ? tfmb::strain::MechanicalBasis::force
                    : basis == "strain" ? tfmb::strain::MechanicalBasis::strain
                                        : tfmb::strain::MechanicalBasis::strain_minus_thermal;
    tfmb::Logger logger("tfmb-strain", common.verbosity());
    tfmb::strain::run(options, logger, std::cout);
    return 0;
  });
}
