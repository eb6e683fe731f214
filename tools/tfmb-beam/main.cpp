// tfmb-beam: nonlinear flexible multibody beam solver (static, dynamic, modal).
//
// Sample runs:
//   tfmb-beam model.h5 loads.h5 materials.h5 -o structure.h5
//   tfmb-beam model.h5 loads.h5 -o structure.h5 --analysis dynamic --end-time 1 --time-step 1e-3
//   tfmb-beam model.h5 -o modes.h5 --analysis modal --modes 10
//   tfmb-beam model.h5 -o structure.h5 --point-load beam_a:end:0,-0.01   (cases/beam-revolute)
#include "tfmb-beam/run.hpp"
#include "tfmb/common/cli.hpp"
#include "tfmb/common/errors.hpp"
#include "tfmb/common/h5.hpp"
#include "tfmb/common/options.hpp"
#include "tfmb/formats/schema.hpp"

int main(int argc, char** argv) {
  CLI::App app{
      "Geometrically exact beams with joints: nonlinear static (load stepping, Newton), dynamic "
      "(generalized-alpha) and modal analysis of the flaps of model.h5 under loads.h5 and "
      "materials.h5.",
      "tfmb-beam"};
  tfmb::beam::Options options;
  tfmb::cli::CommonOptions common;
  tfmb::cli::add_common_options(app, common);
  std::vector<std::filesystem::path> inputs;
  tfmb::cli::OptionTable table(app);
  table
      .add("inputs", inputs, "",
           "model.h5 (tfmb/model), then optionally loads.h5 (tfmb/loads) and materials.h5 "
           "(tfmb/materials), recognised by their format")
      ->required();  // a missing input is a bad input (exit 3 from its reader), not a usage error
  table.add_output(options.output, "structure file (tfmb/structure)");
  table.add("--analysis", options.analysis, "",
            "static, dynamic or modal (empty: the model's /analysis @time)");
  table.add("--load-steps", options.load_steps, "1", "static: initial load steps (0: the model's)",
            CLI::NonNegativeNumber);
  table.add("--end-time", options.end_time, "s", "dynamic: end time (0: the model's)",
            CLI::NonNegativeNumber);
  table.add("--time-step", options.time_step, "s", "dynamic: time step (0: the model's)",
            CLI::NonNegativeNumber);
  table.add(
      "--initial-state", options.initial_state, "",
      "dynamic: continue from the final positions, rotations and velocities of an earlier dynamic "
      "structure.h5 of the same model (its /restart group)");
  table.add("--rho-inf", options.rho_infinity, "1",
            "dynamic: spectral radius at infinity of generalized-alpha",
            tfmb::cli::range(0.0, 1.0));
  table.add("--modes", options.modes, "1", "modal: number of modes", CLI::PositiveNumber);
  table.add_flag("--arc-length", options.arc_length,
                 "static: arc-length continuation instead of load stepping (passes limit points; "
                 "stops at the first load factor >= 1)");
  table.add_flag("--dead-loads", options.dead_loads,
                 "apply loads.h5 forces as dead loads (default: follower, i.e. pressure turning "
                 "with the wall)");
  table.add("--point-load", options.point_loads, "",
            "dead point load at a flap end, flap:start|end:fx,fy[,mz] [N, N m]; repeatable");
  return tfmb::cli::run_main(app, argc, argv, [&] {
    options.command_line = tfmb::cli::command_line(argc, argv);
    options.settings_toml = table.settings_toml();
    options.model = inputs.at(0);
    // read only by dynamic runs, but a missing file is refused whatever the analysis
    if (!options.initial_state.empty() && !std::filesystem::exists(options.initial_state))
      throw tfmb::BadInput(options.initial_state.string() + ": no such file");
    for (size_t i = 1; i < inputs.size(); ++i) {
      const std::string format = tfmb::formats::schema_of(tfmb::h5::Reader(inputs[i])).format;
      if (format == "tfmb/loads")
        options.loads = inputs[i];
      else if (format == "tfmb/materials")
        options.materials = inputs[i];
      else
        throw tfmb::UsageError(inputs[i].string() + ": format '" + format +
                               "' is neither tfmb/loads nor tfmb/materials");
    }
    const tfmb::Logger log("tfmb-beam", common.verbosity());
    return tfmb::beam::run(options, log);
  });
}
