// tfmb-mesh: meshes of a model (formats/flowmesh.md, formats/solidmesh.md) and deformation of a
// flow mesh by a wall displacement (formats/walldisp.md).
//
// Sample runs:
//   tfmb-mesh flow model.h5 -o flowmesh.h5             # + flowmesh.xdmf; quality on stderr
//   tfmb-mesh flow model.h5 -o flowmesh.h5 --scale 4   # 4x coarser (every size times 4)
//   tfmb-mesh solid model.h5 -o solidmesh.h5
//   tfmb-mesh deform flowmesh.h5 walldisp.h5 -o flowmesh2.h5   # exit 3 + fraction if cells fold
#include "tfmb-mesh/mesh_tools.hpp"
#include "tfmb/common/cli.hpp"
#include "tfmb/common/options.hpp"

int main(int argc, char** argv) {
  CLI::App app{"Build the flow and solid meshes of a model, or deform a flow mesh.", "tfmb-mesh"};
  app.require_subcommand(1);
  tfmb::mesh::Options options;
  tfmb::cli::CommonOptions common;
  tfmb::cli::add_common_options(app, common);
  auto* flow =
      app.add_subcommand("flow", "Fluid mesh: quad layers on walls, triangles elsewhere (gmsh)");
  tfmb::cli::OptionTable flow_table(*flow);
  flow_table.add("model", options.input, "", "model.h5 from tfmb-input")->required();
  flow_table.add_output(options.output, "flow mesh file (flowmesh.h5)");
  // Options::scale 0 stands for "the case's"; on the command line it is simply not given.
  std::optional<double> scale;
  flow_table.add(
      "--scale", scale, "1",
      "Multiply every mesh size (wall size, far size, first layer height; structured cell "
      "counts are divided) by this factor (default: the case's mesh.scale)",
      tfmb::cli::range(0.01, 100.0));
  flow_table.add("--algorithm", options.algorithm, "",
                 "gmsh 2D algorithm: 1 MeshAdapt, 2 Automatic, 5 Delaunay, 6 Frontal-Delaunay",
                 CLI::IsMember({1, 2, 5, 6}));
  flow_table.add("--max-cells", options.max_cells, "1",
                 "refuse a nozzle mesh estimated (from the wall and far-field spacings, before "
                 "meshing) above this many cells",
                 tfmb::cli::range(1.0, 1e9));
  auto* solid =
      app.add_subcommand("solid", "Solid mesh of the flap walls, linked to the beam elements");
  tfmb::cli::OptionTable solid_table(*solid);
  solid_table.add("model", options.input, "", "model.h5 from tfmb-input")->required();
  solid_table.add_output(options.output, "solid mesh file (solidmesh.h5)");
  auto* deform =
      app.add_subcommand("deform", "Move a flow mesh by a wall displacement (same topology)");
  tfmb::cli::OptionTable deform_table(*deform);
  deform_table.add("flowmesh", options.input, "", "flowmesh.h5 to deform")->required();
  deform_table.add("walldisp", options.walldisp, "", "walldisp.h5 (formats/walldisp.md)")
      ->required();
  deform_table.add_flag("--rotations,!--no-rotations", options.deform.rotations,
                        "interpolate the walls' rotations as well as their displacements, so that "
                        "cells near a turning wall turn with it (Luke, Collins & Blades 2012)");
  deform_table.add_output(options.output, "deformed flow mesh file");
  return tfmb::cli::run_main(app, argc, argv, [&] {
    options.command = app.get_subcommands().front()->get_name();
    options.command_line = tfmb::cli::command_line(argc, argv);
    options.scale = scale.value_or(0.0);
    const tfmb::cli::OptionTable& table = flow->parsed()    ? flow_table
                                          : solid->parsed() ? solid_table
                                                            : deform_table;
    options.settings_toml = table.settings_toml();
    const tfmb::Logger log("tfmb-mesh", common.verbosity());
    return tfmb::mesh::run(options, log);
  });
}
