// tfmb-heat: steady 2D finite-element heat conduction in the flap walls.
//
// Sample runs:
//   tfmb-heat solidmesh.h5 flow.h5 model.h5 --db materials-db.h5 -o thermal.h5
//   tfmb-heat solidmesh.h5 flow.h5 model.h5 -o thermal.h5 --environment-temperature 280 -v
// The material database defaults to $TFMB_MATERIAL_DB when --db is not given, else to the
// installed tree's or the source tree's data/materials-db.h5 (as tfmb-matmap).
#include "tfmb-heat/run.hpp"
#include "tfmb/common/cli.hpp"
#include "tfmb/common/errors.hpp"
#include "tfmb/common/options.hpp"
#include "tfmb/formats/material_db.hpp"

int main(int argc, char** argv) {
  CLI::App app{
      "Steady 2D finite-element heat conduction in the flap walls: temperature-dependent "
      "conductivity, wall temperature / convection / radiation from the flow, per beam "
      "element mean temperature and through-thickness difference.",
      "tfmb-heat"};
  tfmb::heat::Options options;
  tfmb::cli::CommonOptions common;
  tfmb::cli::add_common_options(app, common);
  // Looked up before declaring --db so that --help shows it.
  options.material_db = tfmb::formats::default_material_db();
  tfmb::cli::OptionTable table(app);
  table.add("solidmesh", options.solid_mesh, "", "Solid mesh of the flap walls (tfmb/solidmesh)")
      ->required();
  table.add("flow", options.flow, "", "Flow solution with wall traces (tfmb/flow)")->required();
  table
      .add("model", options.model, "",
           "Analysis model (tfmb/model): flap materials, /thermal settings")
      ->required();
  table.add("--db", options.material_db, "",
            "Material database (tfmb/material-db); default $TFMB_MATERIAL_DB, else the "
            "installed or the source tree's data/materials-db.h5");
  table.add_output(options.output, "thermal file (tfmb/thermal)");
  table.add("--environment-temperature", options.environment_temperature, "K",
            "Radiation sink temperature of the outer walls", CLI::PositiveNumber);
  table.add("--joint-conductance", options.joint_conductance, "W/(m^2 K)",
            "Gap conductance between flap ends at joints; 0: adiabatic ends",
            CLI::NonNegativeNumber);
  table.add("--tolerance", options.newton.temperature_tolerance, "K",
            "Newton stops when the largest temperature update is below this", CLI::PositiveNumber);
  table.add("--max-iterations", options.newton.max_iterations, "1", "Newton iteration limit",
            CLI::PositiveNumber);
  return tfmb::cli::run_main(app, argc, argv, [&] {
    if (options.material_db.empty())
      throw tfmb::UsageError("no material database: give --db FILE or set TFMB_MATERIAL_DB");
    options.command_line = tfmb::cli::command_line(argc, argv);
    options.settings_toml = table.settings_toml();
    const tfmb::Logger log("tfmb-heat", common.verbosity());
    return tfmb::heat::run(options, log);
  });
}
