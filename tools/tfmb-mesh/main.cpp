// tfmb-mesh: meshes of a model (formats/flowmesh.md, formats/solidmesh.md) and deformation of a
// flow mesh by a wall displacement (formats/walldisp.md).
//
// Sample runs:
//   tfmb-mesh flow model.h5 -o flowmesh.h5               # + flowmesh.xdmf; quality report on stderr
//   tfmb-mesh flow model.h5 -o flowmesh.h5 --scale 4     # 4x coarser (every size times 4)
//   tfmb-mesh solid model.h5 -o solidmesh.h5
//   tfmb-mesh deform flowmesh.h5 walldisp.h5 -o flowmesh2.h5   # exit 3 + admissible fraction if cells fold
#include "tfmb-mesh/mesh_tools.hpp"
#include "tfmb/common/cli.hpp"

int main(int argc, char** argv) {
  CLI::App app{"Build the flow and solid meshes of a model, or deform a flow mesh.", "tfmb-mesh"};
  app.require_subcommand(1);
  tfmb::mesh::Options options;
  tfmb::cli::CommonOptions common;
  tfmb::cli::add_common_options(app, common);
  auto* flow = app.add_subcommand("flow", "Fluid mesh: quad layers on walls, triangles elsewhere (gmsh)");
  flow->add_option("model", options.input, "model.h5 from tfmb-input")->required();
  tfmb::cli::add_output_option(*flow, options.output, "flow mesh file (flowmesh.h5)");
  flow->add_option("--scale", options.scale,
                   "Multiply every mesh size (wall size, far size, first layer height; structured cell "
                   "counts are divided) by this factor [1]; default: the case's mesh.scale")
      ->check(CLI::Range(0.01, 100.0));
  flow->add_option("--algorithm", options.algorithm, "gmsh 2D algorithm: 5 Delaunay, 6 Frontal-Delaunay")
      ->check(CLI::IsMember({1, 2, 5, 6}));
  auto* solid = app.add_subcommand("solid", "Solid mesh of the flap walls, linked to the beam elements");
  solid->add_option("model", options.input, "model.h5 from tfmb-input")->required();
  tfmb::cli::add_output_option(*solid, options.output, "solid mesh file (solidmesh.h5)");
  auto* deform = app.add_subcommand("deform", "Move a flow mesh by a wall displacement (same topology)");
  deform->add_option("flowmesh", options.input, "flowmesh.h5 to deform")->required();
  deform->add_option("walldisp", options.walldisp, "walldisp.h5 (formats/walldisp.md)")->required();
  tfmb::cli::add_output_option(*deform, options.output, "deformed flow mesh file");
  return tfmb::cli::run_main(app, argc, argv, [&] {
    options.command = app.get_subcommands().front()->get_name();
    options.command_line = tfmb::cli::command_line(argc, argv);
    const tfmb::Logger log("tfmb-mesh", common.verbosity());
    return tfmb::mesh::run(options, log);
  });
}
