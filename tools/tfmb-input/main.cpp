// tfmb-input: case.toml + geometry (CSV polyline, STEP/IGES, gmsh .geo) -> model.h5
// (formats/model.md; the case file is documented in formats/case-toml.md).
//
// Sample runs:
//   tfmb-input cases/simple-nozzle/case.toml -o model.h5
//   tfmb-input cases/realistic-nozzle/case.toml -o model.h5 --set flow.nozzle_pressure_ratio=5.423
//     --set flap.upper_divergent.thickness=0.004
//   tfmb-input case.toml -o model.h5 --curves-csv curves.csv   # also dumps the curves it read
#include "model_build.hpp"
#include "tfmb/common/cli.hpp"
#include "tfmb/common/options.hpp"

int main(int argc, char** argv) {
  CLI::App app{"Build the analysis model (model.h5) from a case file and its geometry.",
               "tfmb-input"};
  tfmb::input::Options options;
  tfmb::cli::CommonOptions common;
  tfmb::cli::add_common_options(app, common);
  // model.h5:/provenance@settings holds the resolved case file, which the --set overrides are
  // part of, so this table only declares the options.
  tfmb::cli::OptionTable table(app);
  table.add("case", options.case_file, "", "case.toml (see formats/case-toml.md)")->required();
  table.add_output(options.output, "model file to write (model.h5)");
  table.add_set(options.overrides);
  table.add("--curves-csv", options.curves_csv, "",
            "Also write the curves read from the geometry file as CSV (curve,x,y) [m]");
  return tfmb::cli::run_main(app, argc, argv, [&] {
    options.command_line = tfmb::cli::command_line(argc, argv);
    const tfmb::Logger log("tfmb-input", common.verbosity());
    tfmb::input::run(options, log);
    return 0;
  });
}
