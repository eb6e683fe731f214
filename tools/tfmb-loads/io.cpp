#include "io.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>

#include "tfmb/common/errors.hpp"
#include "tfmb/common/h5.hpp"
#include "tfmb/formats/flow.hpp"
#include "tfmb/formats/flowmesh.hpp"
#include "tfmb/formats/loads.hpp"
#include "tfmb/formats/model.hpp"
#include "tfmb/formats/schema.hpp"
#include "tfmb/formats/structure.hpp"
#include "tfmb/formats/walldisp.hpp"

namespace tfmb::loads {

namespace {

Side parse_side(const formats::Flow& file, const std::string& object, const std::string& side) {
  if (side == "inner") return Side::inner;
  if (side == "outer") return Side::outer;
  if (side == "end") return Side::end;
  file.fail(object, "side '" + side + "' is not inner, outer or end");
}

// Which side of a trace the fluid is on from the flow's mesh, for a file without wall normals
// (they are optional; flow 1.4 added them): +1 where the cells along the trace lie to the left of
// its direction, -1 to the right, by a length-weighted vote of each trace edge's cell (its centre
// against the edge; the cells' orientation is not relied on).
double fluid_side_from_mesh(const formats::Flow& flow, const formats::FlowWall& wall) {
  using Edge = std::pair<std::int64_t, std::int64_t>;
  auto edge = [](std::int64_t a, std::int64_t b) { return a < b ? Edge{a, b} : Edge{b, a}; };
  std::map<Edge, std::size_t> trace_edge;
  for (std::size_t k = 0; k + 1 < wall.node.size(); ++k)
    trace_edge[edge(wall.node[k], wall.node[k + 1])] = k;
  const auto& points = flow.mesh.points;
  auto point = [&](std::int64_t n) { return Vec2(points(n, 0), points(n, 1)); };
  double vote = 0.0;
  auto visit = [&](const h5::MatrixXiR& cells) {
    for (Eigen::Index c = 0; c < cells.rows(); ++c) {
      Vec2 centre = Vec2::Zero();
      for (Eigen::Index i = 0; i < cells.cols(); ++i)
        centre += point(cells(c, i));
      centre /= static_cast<double>(cells.cols());
      for (Eigen::Index i = 0; i < cells.cols(); ++i) {
        const auto it = trace_edge.find(edge(cells(c, i), cells(c, (i + 1) % cells.cols())));
        if (it == trace_edge.end())
          continue;
        const Vec2 a = point(wall.node[it->second]), b = point(wall.node[it->second + 1]);
        const Vec2 e = b - a, r = centre - a;
        const double cross = e.x() * r.y() - e.y() * r.x();
        if (cross != 0.0)
          vote += (cross > 0.0 ? 1.0 : -1.0) * e.norm();
      }
    }
  };
  visit(flow.mesh.triangles);
  visit(flow.mesh.quads);
  if (vote == 0.0) {
    flow.fail("/walls/" + wall.name,
              "no /normal, and no mesh cell along the trace tells on which side the fluid is");
  }
  return vote > 0.0 ? 1.0 : -1.0;
}

// Which side of a trace the fluid is on, from the flow file's wall normals (flow 1.4: unit
// normals leaving the fluid): the sign that turns the segments' left normals out of the solid,
// i.e. against the flow's normals, by a length-weighted vote over the segments; from the mesh's
// cells along the trace where the file has no normals.
double fluid_side(const formats::Flow& flow, const formats::FlowWall& wall,
                  const WallTrace& trace) {
  const std::string group = "/walls/" + wall.name;
  if (wall.normal.empty())
    return fluid_side_from_mesh(flow, wall);
  double vote = 0.0;
  for (std::size_t k = 0; k < trace.segment_count(); ++k) {
    const Vec2 into_wall = wall.normal[k] + wall.normal[k + 1];
    const Vec2 e = trace.points[k + 1] - trace.points[k];
    vote -= Vec2(-e.y(), e.x()).dot(into_wall);  // left normal against the flow's normal
  }
  if (vote == 0.0)
    flow.fail(group + "/normal", "cannot tell on which side of the wall the fluid is");
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
  const formats::Flow flow = formats::read_flow(file);
  h5::MatrixXdR reference_points;
  if (!reference_mesh.empty()) {
    reference_points = formats::read_flowmesh(reference_mesh).mesh.points;
    if (static_cast<std::size_t>(reference_points.rows()) != flow.mesh.node_count()) {
      flow.fail("/mesh/points", std::to_string(flow.mesh.node_count()) +
                                    " nodes, but the reference mesh " + reference_mesh.string() +
                                    " has " + std::to_string(reference_points.rows()) +
                                    " (not the same topology)");
    }
  }
  FlowTraces out;
  out.header = flow.header;
  for (const formats::FlowWall& wall : flow.walls) {
    const std::string g = "/walls/" + wall.name;
    const auto boundary = flow.mesh.boundaries.find(wall.name);
    if (boundary == flow.mesh.boundaries.end() || boundary->second.flap.empty()) {
      out.skipped.push_back(wall.name);
      continue;
    }
    const std::string b = "/mesh/boundaries/" + wall.name;
    WallTrace trace;
    trace.name = wall.name;
    trace.flap = boundary->second.flap;
    if (boundary->second.side.empty())
      flow.fail(b, "a flap wall needs a 'side' attribute (inner, outer or end)");
    trace.side = parse_side(flow, b, boundary->second.side);
    trace.pressure = wall.pressure;
    trace.wall_shear = wall.wall_shear;
    for (std::size_t i = 0; i < wall.x.size(); ++i)
      trace.points.emplace_back(wall.x[i], wall.y[i]);
    try {
      check_trace(trace);
    } catch (const std::invalid_argument& e) {
      flow.fail(g, e.what());
    }
    trace.normal_sign = fluid_side(flow, wall, trace);
    if (reference_points.rows() > 0) {
      for (std::size_t k = 0; k < wall.node.size(); ++k) {
        const auto node = static_cast<Eigen::Index>(wall.node[k]);
        trace.points[k] = Vec2(reference_points(node, 0), reference_points(node, 1));
      }
    }
    out.traces.push_back(std::move(trace));
  }
  return out;
}

std::vector<MeshWall> read_mesh_walls(const std::filesystem::path& file) {
  const std::string kind = formats::schema_of(h5::Reader(file)).kind;
  // (the file is refused by name: opening and checking it a second time only to fail is waste)
  if (kind != "flow" && kind != "flowmesh")
    formats::ReadFrom{file}.fail(
        "/", "format 'tfmb/" + kind + "' has no flow mesh; give a flowmesh or flow file");
  // Either kind carries the mesh block; each is read (and checked) by its own reader.
  formats::ReadFrom source;
  formats::Mesh mesh;
  if (kind == "flow") {
    formats::Flow flow = formats::read_flow(file);
    source = flow;
    mesh = std::move(flow.mesh);
  } else {
    formats::FlowMesh flow_mesh = formats::read_flowmesh(file);
    source = flow_mesh;
    mesh = std::move(flow_mesh.mesh);
  }
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
        source.fail("/mesh/boundaries/" + name + "/edges",
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
    f.position = flap.nodes;
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
  formats::WallDisplacements out;
  out.header = header;
  out.wall_source = wall_source;
  for (const WallDisplacement& wall : walls)
    out.walls.push_back(
        {wall.name, wall.flap, wall.side, wall.nodes, wall.points, wall.displacement});
  formats::write_walldisp(file, out, provenance);
}

}  // namespace tfmb::loads
