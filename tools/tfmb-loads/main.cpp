// tfmb-loads: wall traces -> beam loads (forces), beam motion -> wall displacement (displace).
//
// Sample runs:
//   tfmb-loads forces flow.h5 model.h5 -o loads.h5                      # conservative (default)
//   tfmb-loads forces flow.h5 model.h5 --method linear -o loads.h5      # the seed's interpolation
//   tfmb-loads forces model.h5 --function "p_inner=2e5-1e5*x; p_outer=101325" --diff -o loads.h5
//   tfmb-loads displace structure.h5 model.h5 --mesh flowmesh.h5 -o walldisp.h5
//   tfmb-loads displace model.h5 --function "ux=1e-3; uy=0.01*x; rz=0.01" --diff -o walldisp.h5
#include <iostream>

#include "run.hpp"
#include "tfmb/common/cli.hpp"
#include "tfmb/common/errors.hpp"
#include "tfmb/common/options.hpp"

int main(int argc, char** argv) {
  CLI::App app{"Map flow wall traces to beam loads and beam motion to wall displacements.",
               "tfmb-loads"};
  tfmb::cli::CommonOptions common;
  tfmb::cli::add_common_options(app, common);
  app.require_subcommand(1);

  tfmb::loads::ForcesOptions forces;
  std::vector<std::filesystem::path> forces_inputs;
  std::string method = tfmb::loads::method_name(forces.method);
  auto* f =
      app.add_subcommand("forces", "Wall pressure and shear -> distributed and nodal beam loads");
  tfmb::cli::OptionTable forces_table(*f);
  forces_table.add("inputs", forces_inputs, "", "flow.h5 model.h5 (only model.h5 with --function)")
      ->required();
  forces_table.add_output(forces.output, "loads file (tfmb/loads)");
  forces_table.add("--method", method, "",
                   "linear: the seed's linear interpolation at the beam nodes; conservative: "
                   "consistent nodal loads keeping each flap's total force and moment",
                   CLI::IsMember({"linear", "conservative"}));
  forces_table.add(
      "--function", forces.function, "",
      "analytic traces instead of flow.h5: 'p_inner=EXPR; p_outer=EXPR; tau_inner=EXPR; "
      "tau_outer=EXPR' ([Pa]; p=, tau= set both sides; variables x, y [m]) on the model walls");
  forces_table.add("--samples", forces.function_samples, "1",
                   "with --function: pieces per model wall segment");
  forces_table.add_flag("--diff", forces.diff, "report the mapping error against --function");
  forces_table.add("--coverage-tolerance", forces.coverage_tolerance, "1",
                   "largest uncovered stretch of a flap side, relative to the flap length");
  forces_table.add("--reference-mesh", forces.reference_mesh, "",
                   "undeformed flowmesh.h5 of a two-way run: map the traces of the deformed walls "
                   "from their nodes' reference positions onto the undeformed beam");
  forces_table.add("--missing-side-pressure", forces.missing_side_pressure, "Pa",
                   "uniform pressure on a flap side that has no trace (default: error)");

  tfmb::loads::DisplaceOptions displace;
  std::vector<std::filesystem::path> displace_inputs;
  auto* d =
      app.add_subcommand("displace", "Beam displacement and rotation -> wall point displacement");
  tfmb::cli::OptionTable displace_table(*d);
  displace_table
      .add("inputs", displace_inputs, "", "structure.h5 model.h5 (only model.h5 with --function)")
      ->required();
  displace_table.add_output(displace.output, "wall displacement file (tfmb/walldisp)");
  displace_table.add(
      "--mesh", displace.mesh_file, "",
      "flowmesh.h5 or flow.h5: displace its flap wall nodes (default: the model walls)");
  displace_table.add("--function", displace.function, "",
                     "analytic beam motion instead of structure.h5: 'ux=EXPR; uy=EXPR; rz=EXPR' "
                     "([m], [m], [rad]; variables x, y [m]) at the beam nodes");
  displace_table.add_flag("--diff", displace.diff,
                          "report the difference to (ux, uy) of --function at the wall points");
  displace_table.add("--match-tolerance", displace.match_tolerance, "1",
                     "structure beam nodes must lie this close to the model reference curve, "
                     "relative to the flap length");

  const std::string command = tfmb::cli::command_line(argc, argv);
  return tfmb::cli::run_main(app, argc, argv, [&] {
    tfmb::Logger logger("tfmb-loads", common.verbosity());
    if (f->parsed()) {
      forces.method =
          method == "linear" ? tfmb::loads::Method::linear : tfmb::loads::Method::conservative;
      forces.command_line = command;
      forces.settings_toml = forces_table.settings_toml();
      const std::size_t expected = forces.function.empty() ? 2 : 1;
      if (forces_inputs.size() != expected) {
        throw tfmb::UsageError(forces.function.empty() ? "forces needs flow.h5 model.h5"
                                                       : "forces --function needs only model.h5");
      }
      if (expected == 2)
        forces.flow_file = forces_inputs[0];
      forces.model_file = forces_inputs.back();
      tfmb::loads::run_forces(forces, logger, std::cout);
    } else {
      displace.command_line = command;
      displace.settings_toml = displace_table.settings_toml();
      const std::size_t expected = displace.function.empty() ? 2 : 1;
      if (displace_inputs.size() != expected) {
        throw tfmb::UsageError(displace.function.empty()
                                   ? "displace needs structure.h5 model.h5"
                                   : "displace --function needs only model.h5");
      }
      if (expected == 2)
        displace.structure_file = displace_inputs[0];
      displace.model_file = displace_inputs.back();
      tfmb::loads::run_displace(displace, logger, std::cout);
    }
    return 0;
  });
}
