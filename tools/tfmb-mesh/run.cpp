#include "mesh_tools.hpp"
#include "tfmb/common/cli.hpp"
#include "tfmb/common/errors.hpp"
#include "tfmb/common/text.hpp"
#include "tfmb/formats/schema.hpp"
#include "tfmb/formats/solidmesh.hpp"
#include "tfmb/formats/walldisp.hpp"

namespace tfmb::mesh {
namespace {

// Four significant digits in the summaries (sizes and qualities, not results).
std::string num(double v, int digits = 4) {
  return text::format_number(v, digits);
}

void write_quality(h5::Writer& w, const Quality& q) {
  w.set_attr("/mesh", "min_angle", q.min_angle);
  w.set_attr("/mesh", "max_aspect_ratio", q.max_aspect_ratio);
  w.set_attr("/mesh", "min_cell_area", q.min_area);
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
    FlowMeshReport report;
    const Mesh mesh = build_flow_mesh(model, fo, report, log);
    if (report.quality.invalid_cells > 0) {
      throw InternalError("flow mesh has " + std::to_string(report.quality.invalid_cells) +
                          " invalid cells");
    }
    {
      h5::Writer w(options.output);
      formats::Header header;
      header.creator = "tfmb-mesh " + cli::version();
      header.depth = model.depth;
      formats::write_header(w, "flowmesh", header);
      formats::write_mesh(w, mesh);
      write_quality(w, report.quality);
      if (report.estimated_yplus)
        w.set_attr("/mesh", "estimated_yplus", *report.estimated_yplus);
      w.set_attr("/mesh", "first_layer_height", report.first_layer_height);
      w.set_attr("/mesh", "boundary_layers", static_cast<std::int64_t>(report.boundary_layers));
      formats::write_provenance(w, provenance(options, {options.input}));
      w.commit();
    }
    formats::write_xdmf_sidecar(options.output);
    log.info("quality: " + quality_text(report.quality) + ", " +
             std::to_string(report.boundary_layers) + " wall layers, first layer " +
             num(report.first_layer_height) + " m, estimated y+ " +
             (report.estimated_yplus ? num(*report.estimated_yplus)
                                     : std::string("not recorded in the model")));
    log.summary("wrote " + options.output.string() + ": " + std::to_string(mesh.node_count()) +
                " nodes, " + std::to_string(mesh.triangles.rows()) + " triangles, " +
                std::to_string(mesh.quads.rows()) + " quads, " +
                std::to_string(mesh.boundaries.size()) + " boundaries (" + num(clock.seconds(), 3) +
                " s)");
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
    const h5::Reader file = formats::open_checked(options.input, "flowmesh");
    const Mesh mesh = formats::read_mesh(file);
    const formats::Header header_in = formats::read_header(file);
    const auto walls = formats::read_walldisp(options.walldisp).walls;
    DeformReport report;
    const Mesh moved = deform_mesh(mesh, walls, report);
    {
      h5::Writer w(options.output);
      formats::Header header;
      header.creator = "tfmb-mesh " + cli::version();
      header.depth = header_in.depth;
      header.geometry = header_in.geometry;
      formats::write_header(w, "flowmesh", header);
      formats::write_mesh(w, moved);
      write_quality(w, report.quality);
      for (const char* name : {"estimated_yplus", "first_layer_height"}) {
        if (file.has_attr("/mesh", name))
          w.set_attr("/mesh", name, file.attr_f64("/mesh", name));
      }
      if (file.has_attr("/mesh", "boundary_layers"))
        w.set_attr("/mesh", "boundary_layers", file.attr_i64("/mesh", "boundary_layers"));
      formats::write_provenance(w, provenance(options, {options.input, options.walldisp}));
      w.commit();
    }
    formats::write_xdmf_sidecar(options.output);
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
