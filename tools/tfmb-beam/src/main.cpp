// tfmb-beam: nonlinear flexible multibody beam solver (static, dynamic, modal).
//
// Sample runs:
//   tfmb-beam model.h5 loads.h5 materials.h5 -o structure.h5
//   tfmb-beam model.h5 loads.h5 -o structure.h5 --analysis dynamic --end-time 1 --time-step 1e-3
//   tfmb-beam model.h5 -o modes.h5 --analysis modal --modes 10
//   tfmb-beam model.h5 -o structure.h5 --point-load beam_a:end:0,-0.01   (cases/beam-revolute)
#include "tfmb/beam/run.hpp"
#include "tfmb/common/cli.hpp"
#include "tfmb/common/errors.hpp"
#include "tfmb/common/h5.hpp"

int main(int argc, char** argv) {
  CLI::App app{"Geometrically exact beams with joints: nonlinear static (load stepping, Newton), dynamic "
               "(generalized-alpha) and modal analysis of the flaps of model.h5 under loads.h5 and materials.h5.",
               "tfmb-beam"};
  tfmb::beam::Options options;
  tfmb::cli::CommonOptions common;
  tfmb::cli::add_common_options(app, common);
  std::vector<std::filesystem::path> inputs;
  app.add_option("inputs", inputs, "model.h5 (tfmb/model), then optionally loads.h5 (tfmb/loads) and materials.h5 (tfmb/materials), recognised by their format")
      ->required();  // a missing input is a bad input (exit 3 from its reader), not a usage error
  tfmb::cli::add_output_option(app, options.output, "structure file (tfmb/structure)");
  app.add_option("--analysis", options.analysis, "static, dynamic or modal (default: the model's /analysis @time)");
  app.add_option("--load-steps", options.load_steps, "static: initial load steps (default: the model's)")->check(CLI::NonNegativeNumber);
  app.add_option("--end-time", options.end_time, "dynamic: end time [s] (default: the model's)")->check(CLI::NonNegativeNumber);
  app.add_option("--time-step", options.time_step, "dynamic: time step [s] (default: the model's)")->check(CLI::NonNegativeNumber);
  app.add_option("--initial-state", options.initial_state,
                 "dynamic: continue from the final positions, rotations and velocities of an earlier dynamic "
                 "structure.h5 of the same model (its /restart group)");
  app.add_option("--rho-inf", options.rho_infinity, "dynamic: spectral radius at infinity of generalized-alpha [0, 1]")
      ->capture_default_str()->check(CLI::Range(0.0, 1.0));
  app.add_option("--modes", options.modes, "modal: number of modes")->capture_default_str()->check(CLI::PositiveNumber);
  app.add_flag("--arc-length", options.arc_length,
               "static: arc-length continuation instead of load stepping (passes limit points; stops at the first load factor >= 1)");
  app.add_flag("--dead-loads", options.dead_loads, "apply loads.h5 forces as dead loads (default: follower, i.e. pressure turning with the wall)");
  app.add_option("--point-load", options.point_loads,
                 "dead point load at a flap end, flap:start|end:fx,fy[,mz] [N, N m]; repeatable");
  return tfmb::cli::run_main(app, argc, argv, [&] {
    options.command_line = tfmb::cli::command_line(argc, argv);
    options.model = inputs.at(0);
    // read only by dynamic runs, but a missing file is refused whatever the analysis
    if (!options.initial_state.empty() && !std::filesystem::exists(options.initial_state))
      throw tfmb::BadInput(options.initial_state.string() + ": no such file");
    for (size_t i = 1; i < inputs.size(); ++i) {
      const tfmb::h5::Reader r(inputs[i]);
      const std::string format = r.attr_string("/", "format");
      if (format == "tfmb/loads") options.loads = inputs[i];
      else if (format == "tfmb/materials") options.materials = inputs[i];
      else throw tfmb::UsageError(inputs[i].string() + ": format '" + format + "' is neither tfmb/loads nor tfmb/materials");
    }
    const tfmb::Logger log("tfmb-beam", common.verbosity());
    return tfmb::beam::run(options, log);
  });
}
