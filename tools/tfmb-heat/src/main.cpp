// tfmb-heat: steady 2D finite-element heat conduction in the flap walls.
//
// Sample runs:
//   tfmb-heat solidmesh.h5 flow.h5 model.h5 --db materials-db.h5 -o thermal.h5
//   tfmb-heat solidmesh.h5 flow.h5 model.h5 -o thermal.h5 --environment-temperature 280 -v
// The material database defaults to $TFMB_MATERIAL_DB when --db is not given.
#include "tfmb/common/cli.hpp"
#include "tfmb/common/errors.hpp"
#include "tfmb/heat/run.hpp"

#include <cstdlib>

int main(int argc, char** argv) {
  CLI::App app{"Steady 2D finite-element heat conduction in the flap walls: temperature-dependent "
               "conductivity, wall temperature / convection / radiation from the flow, per beam "
               "element mean temperature and through-thickness difference.",
               "tfmb-heat"};
  tfmb::heat::Options options;
  tfmb::cli::CommonOptions common;
  tfmb::cli::add_common_options(app, common);
  app.add_option("solidmesh", options.solid_mesh, "Solid mesh of the flap walls (tfmb/solidmesh)")->required();
  app.add_option("flow", options.flow, "Flow solution with wall traces (tfmb/flow)")->required();
  app.add_option("model", options.model, "Analysis model (tfmb/model): flap materials, /thermal settings")->required();
  app.add_option("--db", options.material_db, "Material database (tfmb/material-db); default $TFMB_MATERIAL_DB");
  tfmb::cli::add_output_option(app, options.output, "thermal file (tfmb/thermal)");
  app.add_option("--environment-temperature", options.environment_temperature,
                 "Radiation sink temperature of the outer walls [K]")->capture_default_str()->check(CLI::PositiveNumber);
  app.add_option("--joint-conductance", options.joint_conductance,
                 "Gap conductance between flap ends at joints [W/(m^2 K)]; 0: adiabatic ends")->capture_default_str()->check(CLI::NonNegativeNumber);
  app.add_option("--tolerance", options.newton.temperature_tolerance,
                 "Newton stops when the largest temperature update is below this [K]")->capture_default_str()->check(CLI::PositiveNumber);
  app.add_option("--max-iterations", options.newton.max_iterations, "Newton iteration limit")->capture_default_str()->check(CLI::PositiveNumber);
  return tfmb::cli::run_main(app, argc, argv, [&] {
    if (options.material_db.empty()) {
      const char* from_environment = std::getenv("TFMB_MATERIAL_DB");
      if (!from_environment) throw tfmb::UsageError("no material database: give --db FILE or set TFMB_MATERIAL_DB");
      options.material_db = from_environment;
    }
    options.command_line = tfmb::cli::command_line(argc, argv);
    const tfmb::Logger log("tfmb-heat", common.verbosity());
    return tfmb::heat::run(options, log);
  });
}
