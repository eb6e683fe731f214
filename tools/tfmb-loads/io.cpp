#include "io.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>

#include "tfmb/common/errors.hpp"
#include "tfmb/common/h5.hpp"
#include "tfmb/formats/loads.hpp"
#include "tfmb/formats/model.hpp"
#include "tfmb/formats/schema.hpp"
#include "tfmb/formats/structure.hpp"

namespace tfmb::loads {

namespace {

Side parse_side(const h5::Reader& file, const std::string& object, const std::string& side) {
  if (side == "inner") return Side::inner;
  if (side == "outer") return Side::outer;
  if (side == "end") return Side::end;
  file.fail(object, "side '" + side + "' is not inner, outer or end");
}

h5::MatrixXdR rows3(const std::vector<Vec2>& v, bool as_3d = true) {
  h5::MatrixXdR m = h5::MatrixXdR::Zero(static_cast<Eigen::Index>(v.size()), as_3d ? 3 : 2);
  for (std::size_t i = 0; i < v.size(); ++i) {
    m(static_cast<Eigen::Index>(i), 0) = v[i].x();
    m(static_cast<Eigen::Index>(i), 1) = v[i].y();
  }
  return m;
}

// Which side of a trace the fluid is on, from the flow file's wall normals (flow 1.4: unit
// normals leaving the fluid): the sign that turns the segments' left normals out of the solid,
// i.e. against the flow's normals, by a length-weighted vote over the segments.
double fluid_side(const h5::Reader& file, const std::string& group, const WallTrace& trace) {
  if (!file.exists(group + "/normal")) {
    file.fail(group,
              "no /normal: tfmb-loads needs each flap wall's normal (flow 1.4) to know which side "
              "the fluid is on; re-run tfmb-flow, or have the external flow code write it");
  }
  const h5::MatrixXdR normal =
      file.read_matrix(group + "/normal", static_cast<Eigen::Index>(trace.points.size()), 2);
  for (Eigen::Index k = 0; k < normal.rows(); ++k) {
    if (std::abs(normal.row(k).norm() - 1.0) > 1e-6)
      file.fail(group + "/normal", "row " + std::to_string(k) + " is not a unit vector");
  }
  double vote = 0.0;
  for (std::size_t k = 0; k < trace.segment_count(); ++k) {
    const Vec2 into_wall =
        (normal.row(static_cast<Eigen::Index>(k)) + normal.row(static_cast<Eigen::Index>(k + 1)))
            .transpose();
    const Vec2 e = trace.points[k + 1] - trace.points[k];
    vote -= Vec2(-e.y(), e.x()).dot(into_wall);  // left normal against the flow's normal
  }
  if (vote == 0.0)
    file.fail(group + "/normal", "cannot tell on which side of the wall the fluid is");
  return vote > 0.0 ? 1.0 : -1.0;
}

}  // namespace

Model read_model(const std::filesystem::path& file) {
  const formats::Model in = formats::read_model(file);
  Model model;
  model.file = file;
  model.header.geometry = in.geometry;
  model.header.depth = in.depth;
  model.flaps = in.flaps;
  if (model.flaps.empty())
    in.fail("/flaps", "no flaps: nothing to load");
  std::sort(model.flaps.begin(), model.flaps.end(),
            [](const ModelFlap& a, const ModelFlap& b) { return a.name < b.name; });
  return model;
}

FlowTraces read_flow_traces(const std::filesystem::path& file,
                            const std::filesystem::path& reference_mesh) {
  const h5::Reader reader = formats::open_checked(file, "flow");
  h5::MatrixXdR reference_points;
  if (!reference_mesh.empty()) {
    const formats::Mesh reference =
        formats::read_mesh(formats::open_checked(reference_mesh, "flowmesh"));
    reference_points = reference.points;
  }
  FlowTraces out;
  out.header = formats::read_header(reader);
  const auto node_count =
      static_cast<std::int64_t>(reader.read_matrix("/mesh/points", std::nullopt, 2).rows());
  const std::vector<std::string> names =
      reader.is_group("/walls") ? reader.children("/walls") : std::vector<std::string>{};
  for (const std::string& name : names) {
    const std::string g = "/walls/" + name;
    const std::string b = "/mesh/boundaries/" + name;
    if (!reader.exists(b) || !reader.has_attr(b, "flap") || reader.attr_string(b, "flap").empty()) {
      out.skipped.push_back(name);
      continue;
    }
    WallTrace trace;
    trace.name = name;
    trace.flap = reader.attr_string(b, "flap");
    if (!reader.has_attr(b, "side")) reader.fail(b, "a flap wall needs a 'side' attribute (inner, outer or end)");
    trace.side = parse_side(reader, b, reader.attr_string(b, "side"));
    const std::vector<double> x = reader.read_vector(g + "/x");
    const std::vector<double> y = reader.read_vector(g + "/y", x.size());
    trace.pressure = reader.read_vector(g + "/pressure", x.size());
    trace.wall_shear = reader.read_vector(g + "/wall_shear", x.size());
    for (std::size_t i = 0; i < x.size(); ++i) trace.points.emplace_back(x[i], y[i]);
    try {
      check_trace(trace);
    } catch (const std::invalid_argument& e) {
      reader.fail(g, e.what());
    }
    const std::vector<std::int64_t> nodes =
        reader.read_index_vector(g + "/node", x.size(), 0, node_count);
    trace.normal_sign = fluid_side(reader, g, trace);
    if (reference_points.rows() > 0) {
      if (reference_points.rows() != node_count) {
        reader.fail("/mesh/points", std::to_string(node_count) + " nodes, but the reference mesh " +
                                        reference_mesh.string() + " has " +
                                        std::to_string(reference_points.rows()) + " (not the same topology)");
      }
      for (std::size_t k = 0; k < nodes.size(); ++k) {
        trace.points[k] = Vec2(reference_points(nodes[k], 0), reference_points(nodes[k], 1));
      }
    }
    out.traces.push_back(std::move(trace));
  }
  return out;
}

std::vector<MeshWall> read_mesh_walls(const std::filesystem::path& file) {
  std::string kind;
  {
    const h5::Reader probe(file);
    if (!probe.has_attr("/", "format")) probe.fail("/", "no 'format' attribute: not a tfmb file");
    kind = probe.attr_string("/", "format");
    if (kind.rfind("tfmb/", 0) == 0) kind = kind.substr(5);
  }
  if (kind != "flow" && kind != "flowmesh") {
    const h5::Reader probe(file);
    probe.fail("/", "format 'tfmb/" + kind + "' has no flow mesh; give a flowmesh or flow file");
  }
  const h5::Reader reader = formats::open_checked(file, kind);
  const formats::Mesh mesh = formats::read_mesh(reader);
  std::vector<MeshWall> walls;
  for (const auto& [name, boundary] : mesh.boundaries) {
    if (boundary.flap.empty()) continue;
    MeshWall wall;
    wall.name = name;
    wall.flap = boundary.flap;
    wall.side = boundary.side;
    const auto& e = boundary.edges;
    if (e.rows() == 0) continue;
    wall.nodes.push_back(e(0, 0));
    for (Eigen::Index k = 0; k < e.rows(); ++k) {
      if (e(k, 0) != wall.nodes.back()) {
        reader.fail("/mesh/boundaries/" + name + "/edges",
                    "edge " + std::to_string(k) + " does not continue the previous one");
      }
      wall.nodes.push_back(e(k, 1));
    }
    for (std::int64_t n : wall.nodes) wall.points.emplace_back(mesh.points(n, 0), mesh.points(n, 1));
    walls.push_back(std::move(wall));
  }
  return walls;
}

Structure read_structure(const std::filesystem::path& file) {
  const formats::Structure in = formats::read_structure(file);
  Structure out;
  out.header = in.header;
  for (const formats::StructureFlap& f : in.flaps) {
    StructureFlap flap;
    for (std::int64_t node : f.nodes) {
      const auto i = static_cast<std::size_t>(node);
      flap.points.emplace_back(in.points[i].x(), in.points[i].y());
      flap.motion.displacement.emplace_back(in.displacement[i].x(), in.displacement[i].y());
      flap.motion.rotation.push_back(wiener_milenkovic_angle(in.rotation[i].z()));
    }
    out.flaps[f.name] = std::move(flap);
  }
  return out;
}

void write_loads(const std::filesystem::path& file, const LoadsFile& loads,
                 const formats::Provenance& provenance) {
  auto in_3d = [](const Vec2& v) { return Eigen::Vector3d(v.x(), v.y(), 0.0); };
  auto about_z = [](double m) { return Eigen::Vector3d(0.0, 0.0, m); };
  formats::Loads out;
  out.header = loads.header;
  out.method = method_name(loads.method);
  out.load_basis = loads.load_basis;
  for (const auto& flap : loads.flaps) {
    const FlapLoads& l = flap.loads;
    formats::LoadsFlap f;
    f.name = flap.name;
    f.width = flap.width;
    f.traces = flap.traces;
    f.s = l.arc_length;
    for (const Vec2& q : l.distributed_force)
      f.distributed_force.push_back(in_3d(q));
    for (double m : l.distributed_moment)
      f.distributed_moment.push_back(about_z(m));
    for (const Vec2& p : l.nodal_force)
      f.nodal_force.push_back(in_3d(p));
    for (double m : l.nodal_moment)
      f.nodal_moment.push_back(about_z(m));
    f.total_force = in_3d(l.traces.force);
    f.total_moment = about_z(l.traces.moment);
    f.mapped_force = in_3d(l.mapped.force);
    f.mapped_moment = about_z(l.mapped.moment);
    out.flaps.push_back(std::move(f));
  }
  formats::write_loads(file, out, provenance);
}

void write_walldisp(const std::filesystem::path& file, const formats::Header& header,
                    const std::string& wall_source, const std::vector<WallDisplacement>& walls,
                    const formats::Provenance& provenance) {
  h5::Writer writer(file);
  formats::write_header(writer, "walldisp", header);
  writer.set_attr("/", "wall_source", wall_source);
  for (const auto& wall : walls) {
    const std::string g = "/walls/" + wall.name;
    writer.write(g + "/x0", rows3(wall.points, false), "m", "undeformed wall point");
    writer.write(g + "/displacement", rows3(wall.displacement, false), "m", "displacement");
    if (!wall.nodes.empty()) writer.write(g + "/node", wall.nodes, "1", "flow mesh node of each point");
    writer.set_attr(g, "flap", wall.flap);
    writer.set_attr(g, "side", wall.side);
  }
  formats::write_provenance(writer, provenance);
  writer.commit();
}

}  // namespace tfmb::loads
