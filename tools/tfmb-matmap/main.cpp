// tfmb-matmap: beam element temperatures -> material properties, section stiffness and mass,
// thermal strain and curvature.
//
// Sample runs:
//   tfmb-matmap thermal.h5 model.h5 --db materials-db.h5 -o materials.h5
//   tfmb-matmap thermal.h5 model.h5 --db materials-db.h5 --clamp -o materials.h5  # flag, exit 0
#include <iostream>

#include "run.hpp"
#include "tfmb/common/cli.hpp"
#include "tfmb/common/options.hpp"
#include "tfmb/formats/material_db.hpp"

int main(int argc, char** argv) {
  CLI::App app{"Material properties of every beam element at its temperature (tfmb/materials).",
               "tfmb-matmap"};
  tfmb::cli::CommonOptions common;
  tfmb::cli::add_common_options(app, common);
  tfmb::matmap::Options options;
  // Looked up before declaring --db so that --help shows it.
  options.database_file = tfmb::formats::default_material_db();
  tfmb::cli::OptionTable table(app);
  table.add("thermal", options.thermal_file, "", "thermal.h5: per beam element temperatures")
      ->required();
  table.add("model", options.model_file, "", "model.h5: flap materials and sections")->required();
  table.add("--db", options.database_file, "",
            "material database (tfmb/material-db); default $TFMB_MATERIAL_DB, else the installed "
            "share/tfmb/data/materials-db.h5, else the source tree's data/materials-db.h5");
  table.add_output(options.output, "materials file (tfmb/materials)");
  table.add_flag(
      "--clamp", options.clamp,
      "outside a property table use its end value and flag the element (default: exit 3)");
  table.add("--stress-free-temperature", options.stress_free_temperature, "K",
            "temperature of zero thermal strain (default: the model's /thermal reference "
            "temperature, else the material's CTE reference temperature)");
  table.add("--poisson-ratio", options.poisson_ratio, "1",
            "for materials the database has no Poisson ratio or shear modulus for");
  table.add("--allowable-strain", options.allowable_strain, "1",
            "for materials the database has no yield strength for");
  options.command_line = tfmb::cli::command_line(argc, argv);
  return tfmb::cli::run_main(app, argc, argv, [&] {
    options.settings_toml = table.settings_toml();
    tfmb::Logger logger("tfmb-matmap", common.verbosity());
    tfmb::matmap::run(options, logger, std::cout);
    return 0;
  });
}
