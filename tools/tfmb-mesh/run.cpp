#include "mesh_tools.hpp"
#include "tfmb/common/cli.hpp"
#include "tfmb/common/errors.hpp"
#include "tfmb/common/text.hpp"
#include "tfmb/formats/flowmesh.hpp"
#include "tfmb/formats/solidmesh.hpp"
#include "tfmb/formats/walldisp.hpp"

namespace tfmb::mesh {
namespace {

// Four significant digits in the summaries (sizes and qualities, not results).
std::string num(double v, int digits = 4) {
  return text::format_number(v, digits);
}

void set_quality(formats::MeshQualityReport& report, const Quality& q) {
  report.min_angle = q.min_angle;
  report.max_aspect_ratio = q.max_aspect_ratio;
  report.min_cell_area = q.min_area;
}

std::string quality_text(const Quality& q) {
  return "min angle " + num(q.min_angle) + " deg, max aspect ratio " + num(q.max_aspect_ratio) +
         ", min cell area " + num(q.min_area) + " m^2";
}

formats::Provenance provenance(const Options& options, std::vector<std::filesystem::path> inputs) {
  formats::Provenance p;
  p.command_line = options.command_line;
  p.inputs = std::move(inputs);
  p.settings = options.settings_toml;
  return p;
}

}  // namespace

int run(const Options& options, const Logger& log) {
  Stopwatch clock;
  if (options.command == "flow") {
    const Model model = formats::read_model(options.input);
    FlowMeshOptions fo;
    fo.scale = options.scale;
    fo.algorithm = options.algorithm;
    fo.max_cells = options.max_cells;
    FlowMeshReport report;
    formats::FlowMesh out;
    out.mesh = build_flow_mesh(model, fo, report, log);
    if (report.quality.invalid_cells > 0) {
      throw InternalError("flow mesh has " + std::to_string(report.quality.invalid_cells) +
                          " invalid cells");
    }
    out.header.creator = "tfmb-mesh " + cli::version();
    out.header.depth = model.depth;
    out.header.geometry = model.geometry;
    set_quality(out.quality, report.quality);
    out.quality.estimated_yplus = report.estimated_yplus;
    out.quality.first_layer_height = report.first_layer_height;
    out.quality.boundary_layers = static_cast<std::int64_t>(report.boundary_layers);
    formats::write_flowmesh(options.output, out, provenance(options, {options.input}));
    log.info("quality: " + quality_text(report.quality) + ", " +
             std::to_string(report.boundary_layers) + " wall layers, first layer " +
             num(report.first_layer_height) + " m, estimated y+ " +
             (report.estimated_yplus ? num(*report.estimated_yplus)
                                     : std::string("not recorded in the model")));
    log.summary("wrote " + options.output.string() + ": " + std::to_string(out.mesh.node_count()) +
                " nodes, " + std::to_string(out.mesh.triangles.rows()) + " triangles, " +
                std::to_string(out.mesh.quads.rows()) + " quads, " +
                std::to_string(out.mesh.boundaries.size()) + " boundaries (" +
                num(clock.seconds(), 3) + " s)");
    return 0;
  }
  if (options.command == "solid") {
    const Model model = formats::read_model(options.input);
    SolidLink link;
    const Mesh mesh = build_solid_mesh(model, link);
    const Quality q = mesh_quality(mesh);
    formats::SolidMesh out;
    out.header.creator = "tfmb-mesh " + cli::version();
    out.header.depth = model.depth;
    out.mesh = mesh;
    out.flap_names = link.flap_names;
    out.cell_flap = link.cell_flap;
    out.cell_element = link.cell_element;
    out.point_thickness_coordinate = link.point_thickness_coordinate;
    formats::write_solidmesh(options.output, out, provenance(options, {options.input}));
    log.info("quality: " + quality_text(q));
    log.summary("wrote " + options.output.string() + ": " + std::to_string(mesh.node_count()) +
                " nodes, " + std::to_string(mesh.quads.rows()) + " quads in " +
                std::to_string(link.flap_names.size()) + " flaps");
    return 0;
  }
  if (options.command == "deform") {
    const formats::FlowMesh in = formats::read_flowmesh(options.input);
    const auto walls = formats::read_walldisp(options.walldisp).walls;
    DeformReport report;
    formats::FlowMesh out;
    out.header.creator = "tfmb-mesh " + cli::version();
    out.header.depth = in.header.depth;
    out.header.geometry = in.header.geometry;
    try {
      out.mesh = deform_mesh(in.mesh, walls, options.deform, report);
    } catch (const BadInput& e) {
      // deform_mesh speaks of "walldisp: ..." and "deform: ...": a walldisp that does not fit the
      // mesh (points away from their nodes, unknown walls, a displacement that would invert
      // cells). The line names the walldisp file and the mesh it was held against.
      const std::string what = e.what();
      for (const std::string prefix : {"walldisp: ", "deform: "}) {
        if (what.rfind(prefix, 0) == 0)
          throw BadInput(options.walldisp.string() + ": " + what.substr(prefix.size()) +
                         " (flow mesh " + options.input.string() + ")");
      }
      throw;
    }
    // The wall layers and their y+ estimate are the input's: deformation keeps the topology.
    out.quality = in.quality;
    set_quality(out.quality, report.quality);
    formats::write_flowmesh(options.output, out,
                            provenance(options, {options.input, options.walldisp}));
    if (report.projected_nodes > 0) {
      log.info(std::to_string(report.projected_nodes) +
               " wall nodes off the walldisp curves (joins, lips, end "
               "faces) took the displacement of the nearest curve point (at most " +
               num(report.largest_projection) + " m away)");
    }
    log.info("quality after deformation: " + quality_text(report.quality));
    log.summary("wrote " + options.output.string() + ": " +
                std::to_string(report.moved_wall_nodes) +
                " boundary nodes displaced, every cell valid (" + num(clock.seconds(), 3) + " s)");
    return 0;
  }
  throw UsageError("unknown command '" + options.command + "' (flow, solid or deform)");
}

}  // namespace tfmb::mesh
