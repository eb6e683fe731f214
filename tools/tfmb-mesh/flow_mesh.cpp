// Fluid mesh of a nozzle domain: every run of consecutive walls gets a strip of structured quad
// layers (first height from the case, geometric growth, the same number of layers along the
// whole run: exact and repeatable, like a transfinite strip with recombination), and gmsh fills
// the rest of the domain with triangles whose boundary nodes on the strip tops are ours.
#include <gmsh.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

#include "mesh_tools.hpp"
#include "tfmb/common/errors.hpp"
#include "tfmb/common/gmsh_session.hpp"
#include "tfmb/common/polyline.hpp"
#include "tfmb/common/text.hpp"

namespace tfmb::mesh {

using namespace geometry;  // polyline helpers (libcommon)

Mesh build_structured_mesh(const Model& model, double scale, FlowMeshReport& report);

namespace {

// A part of a wall between two corners (turns above 10 degrees), to be sampled as one.
struct Part {
  std::size_t piece;     // index within the run
  Polyline line;
  double size = 0.0;     // [m] target spacing inside the part
  int min_segments = 1;
};

// Splits the wall pieces of a run at their corners.
std::vector<Part> split_at_corners(const std::vector<const Polyline*>& lines, const std::vector<int>& min_segments,
                                   double wall_size) {
  std::vector<Part> parts;
  for (std::size_t p = 0; p < lines.size(); ++p) {
    const Polyline& line = *lines[p];
    std::vector<std::size_t> corners{0};
    for (std::size_t i = 1; i + 1 < line.size(); ++i) {
      const Point a = (line[i] - line[i - 1]).normalized(), b = (line[i + 1] - line[i]).normalized();
      if (a.dot(b) < std::cos(10.0 * M_PI / 180.0)) corners.push_back(i);
    }
    corners.push_back(line.size() - 1);
    const std::size_t count = corners.size() - 1;
    for (std::size_t k = 0; k < count; ++k) {
      Part part;
      part.piece = p;
      part.line.assign(line.begin() + static_cast<std::ptrdiff_t>(corners[k]),
                       line.begin() + static_cast<std::ptrdiff_t>(corners[k + 1]) + 1);
      part.min_segments = count == 1 ? min_segments[p] : 1;
      part.size = std::min(wall_size, length(part.line) / part.min_segments);
      parts.push_back(std::move(part));
    }
  }
  return parts;
}

// Spacing wanted around the interior vertices of a part from the wall's curvature: 2 pi R / N
// (times the mesh scale), with R = (length around the vertex) / (turn angle at the vertex), the
// radius of the circle through the polyline there. It holds from half-way to the previous vertex
// to half-way to the next; the first and last interior vertices hold it out to the part's ends
// (a part ends at a corner or a joint, where the curve's own curvature is not measured). Returns
// (from, to, spacing) in arc length; empty when cells_per_circle is 0.
std::vector<std::array<double, 3>> curvature_spacing(const Polyline& line, int cells_per_circle, double scale) {
  std::vector<std::array<double, 3>> out;
  if (cells_per_circle <= 0 || line.size() < 3) return out;
  const double total = length(line);
  double s = 0.0;
  for (std::size_t i = 1; i + 1 < line.size(); ++i) {
    const Point back = line[i] - line[i - 1], ahead = line[i + 1] - line[i];
    s += back.norm();
    const double turn = std::atan2(std::abs(back.x() * ahead.y() - back.y() * ahead.x()), back.dot(ahead));
    if (turn < 1e-9) continue;
    const double radius = 0.5 * (back.norm() + ahead.norm()) / turn;
    const double from = i == 1 ? 0.0 : s - 0.5 * back.norm();
    const double to = i + 2 == line.size() ? total : s + 0.5 * ahead.norm();
    out.push_back({from, to, scale * 2.0 * M_PI * radius / cells_per_circle});
  }
  return out;
}

// Samples a part with spacing s(x) = min(size, a + g x, b + g (L - x), c_j + g d_j(x)): the
// spacing grows linearly (rate g, about a geometric ratio 1 + g) away from short neighbours at
// either end and from the curvature-limited spacings c_j (d_j: distance to the stretch where c_j
// holds).
Polyline sample_part(const Part& part, double a, double b, double g, int cells_per_circle, double scale) {
  const double total = length(part.line);
  const int samples = 2000;
  std::vector<double> cumulative(samples + 1, 0.0);
  const auto curved = curvature_spacing(part.line, cells_per_circle, scale);
  auto spacing = [&](double x) {
    double h = std::min({part.size, a + g * x, b + g * (total - x)});
    for (const auto& [from, to, c] : curved) h = std::min(h, c + g * std::max({0.0, from - x, x - to}));
    return h;
  };
  for (int i = 1; i <= samples; ++i) {
    const double x0 = total * (i - 1) / samples, x1 = total * i / samples;
    cumulative[static_cast<std::size_t>(i)] =
        cumulative[static_cast<std::size_t>(i - 1)] + (x1 - x0) * 0.5 * (1.0 / spacing(x0) + 1.0 / spacing(x1));
  }
  const int n = std::max(part.min_segments, static_cast<int>(std::lround(cumulative.back())));
  std::vector<double> s{0.0};
  for (int k = 1; k < n; ++k) {
    const double target = cumulative.back() * k / n;
    const auto it = std::lower_bound(cumulative.begin(), cumulative.end(), target);
    const std::size_t i = static_cast<std::size_t>(std::max<std::ptrdiff_t>(1, it - cumulative.begin()));
    const double f = (target - cumulative[i - 1]) / (cumulative[i] - cumulative[i - 1]);
    s.push_back(total * (static_cast<double>(i - 1) + f) / samples);
  }
  s.push_back(total);
  Polyline out = points_at(part.line, s);
  out.front() = part.line.front();
  out.back() = part.line.back();
  return out;
}

struct Run {
  std::vector<std::size_t> pieces;       // domain boundary indices, loop order
  std::vector<Point> nodes;              // wall nodes along the run
  std::vector<std::size_t> piece_start;  // first node index of each piece in `nodes`
  std::vector<Point> normals;            // layer directions (mitred)
  std::vector<std::int64_t> ids;         // mesh node ids, (layers+1) per wall node, wall first
};

}  // namespace

std::optional<double> estimated_yplus(const Model& model, double height) {
  if (!(model.flow.viscous_length > 0.0))
    return std::nullopt;
  return height / model.flow.viscous_length;
}

Mesh build_flow_mesh(const Model& model, const FlowMeshOptions& options, FlowMeshReport& report,
                     const Logger& log) {
  Stopwatch clock;
  const auto& domain = model.domain;
  if (domain.settings.kind == "none" || domain.boundaries.empty()) {
    throw BadInput("the model has no flow domain (domain.kind = 'none'): nothing to mesh");
  }
  const double scale = options.scale > 0.0 ? options.scale : model.mesh.scale;
  report.estimated_yplus.reset();
  if (domain.settings.kind != "nozzle") {
    Mesh mesh = build_structured_mesh(model, scale, report);
    report.quality = mesh_quality(mesh);
    report.seconds = clock.seconds();
    return mesh;
  }
  const auto& pieces = domain.boundaries;
  const std::size_t np = pieces.size();
  // Sizes.
  double x_lo = 1e300, x_hi = -1e300;
  for (const auto& f : model.flaps) {
    for (const auto& p : f.reference_geometry) {
      x_lo = std::min(x_lo, p.x());
      x_hi = std::max(x_hi, p.x());
    }
  }
  const double nozzle_length = x_hi - x_lo;
  const double wall_size = (model.mesh.wall_size > 0 ? model.mesh.wall_size : nozzle_length / 100.0) * scale;
  const double far_size = (model.mesh.far_size > 0 ? model.mesh.far_size : 25.0 * wall_size / scale) * scale;
  const double h1 = model.flow.first_cell_height * scale;
  const double growth = model.mesh.growth;

  // Wall runs: maximal sequences of consecutive wall pieces (the loop is cyclic).
  auto is_wall = [&](std::size_t i) { return pieces[i].kind == "wall" || pieces[i].kind == "slip_wall"; };
  std::size_t first_non_wall = 0;
  while (first_non_wall < np && is_wall(first_non_wall)) ++first_non_wall;
  if (first_non_wall == np) throw BadInput("flow domain has walls only: no inflow or far field");
  std::vector<Run> runs;
  std::vector<int> run_of_piece(np, -1);
  for (std::size_t k = 1; k <= np; ++k) {
    const std::size_t i = (first_non_wall + k) % np;
    if (!is_wall(i)) continue;
    const std::size_t prev = (i + np - 1) % np;
    if (!is_wall(prev)) runs.emplace_back();
    runs.back().pieces.push_back(i);
    run_of_piece[i] = static_cast<int>(runs.size() - 1);
  }
  for (Run& run : runs) {
    std::vector<const Polyline*> lines;
    std::vector<int> min_segments;
    // The end faces' cell count coarsens with --scale like every other size (rounded down, at
    // least 2): ten cells across the 3 mm end faces of the simple nozzle among the 20 mm wall
    // cells of a scale-4 mesh made slivers (smallest angle 1.4 deg; three: 8.8 deg).
    const int end_cells = std::max(2, static_cast<int>(model.mesh.end_cells / scale));
    for (std::size_t i : run.pieces) {
      lines.push_back(&pieces[i].points);
      min_segments.push_back(pieces[i].side == "end" ? end_cells : 1);
    }
    const auto parts = split_at_corners(lines, min_segments, wall_size);
    std::size_t current_piece = parts.size();
    for (std::size_t k = 0; k < parts.size(); ++k) {
      const double a = k > 0 ? std::min(parts[k].size, parts[k - 1].size) : parts[k].size;
      const double b = k + 1 < parts.size() ? std::min(parts[k].size, parts[k + 1].size) : parts[k].size;
      const Polyline d = sample_part(parts[k], a, b, 0.25, model.mesh.cells_per_circle, scale);
      if (parts[k].piece != current_piece) {
        current_piece = parts[k].piece;
        run.piece_start.push_back(run.nodes.empty() ? 0 : run.nodes.size() - 1);
      }
      run.nodes.insert(run.nodes.end(), run.nodes.empty() ? d.begin() : d.begin() + 1, d.end());
    }
    run.normals = vertex_normals(run.nodes, 2.5);
    // At the run ends the layers follow the adjacent non-wall boundary (the left domain face).
    const auto& before = pieces[(run.pieces.front() + np - 1) % np].points;
    const auto& after = pieces[(run.pieces.back() + 1) % np].points;
    const Point d_in = -(before.back() - before[before.size() - 2]).normalized();
    const Point d_out = (after[1] - after[0]).normalized();
    const Point n0 = geometry::left_normal(run.nodes[0], run.nodes[1]);
    const Point n1 = geometry::left_normal(run.nodes[run.nodes.size() - 2], run.nodes.back());
    run.normals.front() = d_in / std::max(d_in.dot(n0), 0.4);
    run.normals.back() = d_out / std::max(d_out.dot(n1), 0.4);
  }
  // Number of layers: grow until a layer reaches half the wall spacing, but keep the strips
  // thinner than a quarter of the clearance between different runs and of the adjacent
  // non-wall faces.
  int layers = 0;
  if (h1 > 0.0 && model.mesh.max_layers > 0) {
    layers = 1;
    while (layers < model.mesh.max_layers && h1 * std::pow(growth, layers - 1) < 0.5 * wall_size) ++layers;
  }
  auto thickness = [&](int n) {
    return growth == 1.0 ? n * h1 : h1 * (std::pow(growth, n) - 1.0) / (growth - 1.0);
  };
  double clearance = 1e300;
  for (std::size_t a = 0; a < runs.size(); ++a) {
    for (std::size_t b = a + 1; b < runs.size(); ++b) {
      for (const Point& p : runs[a].nodes)
        clearance = std::min(clearance, distance_to(runs[b].nodes, p));
    }
  }
  for (std::size_t i = 0; i < np; ++i) {
    if (!is_wall(i))
      clearance = std::min(clearance, 2.0 * length(pieces[i].points));
  }
  while (layers > 0 && thickness(layers) > 0.25 * clearance) --layers;
  // Where a wall is concave on the flow side the layer directions converge and meet about one
  // radius of curvature off the wall (a flap's outer face offset from a tight throat arc, once
  // cells_per_circle resolves it): keep the stack below half the height at which the layer
  // directions of two neighbouring wall nodes cross, so the strips' top edges keep at least half
  // their wall edge's length and direction.
  const int layers_wanted = layers;
  for (const Run& run : runs) {
    for (std::size_t i = 0; i + 1 < run.nodes.size(); ++i) {
      const Point wall_edge = run.nodes[i + 1] - run.nodes[i];
      const Point closing = run.normals[i + 1] - run.normals[i];  // top edge = wall_edge + t closing
      const double rate = closing.dot(wall_edge);
      if (rate >= 0.0) continue;  // the layers fan out here
      const double crossing = -wall_edge.squaredNorm() / rate;
      while (layers > 0 && thickness(layers) > 0.5 * crossing) --layers;
    }
  }
  if (layers_wanted > 0 && layers == 0) {
    throw BadInput("wall layers fold even one layer high where a wall is concave: reduce the first layer height, or "
                   "refine mesh.wall_size");
  }
  if (layers < layers_wanted) {
    log.info("wall layers limited to " + std::to_string(layers) + " of " +
             std::to_string(layers_wanted) + " (" + text::format_number(thickness(layers), 4) +
             " m thick): more would fold where a wall is concave");
  }
  report.boundary_layers = layers;
  report.first_layer_height = layers > 0 ? h1 : 0.0;
  std::vector<double> heights(static_cast<std::size_t>(layers) + 1, 0.0);
  for (int k = 1; k <= layers; ++k) heights[static_cast<std::size_t>(k)] = thickness(k);

  Mesh mesh;
  std::vector<Point> points;
  std::vector<std::array<std::int64_t, 4>> quads;
  for (Run& run : runs) {
    const std::size_t n = run.nodes.size();
    run.ids.resize(n * (static_cast<std::size_t>(layers) + 1));
    for (std::size_t i = 0; i < n; ++i) {
      for (int k = 0; k <= layers; ++k) {
        run.ids[i * (layers + 1) + static_cast<std::size_t>(k)] = static_cast<std::int64_t>(points.size());
        points.push_back(run.nodes[i] + heights[static_cast<std::size_t>(k)] * run.normals[i]);
      }
    }
    for (std::size_t i = 0; i + 1 < n; ++i) {
      for (int k = 0; k < layers; ++k) {
        const auto id = [&](std::size_t node, int layer) { return run.ids[node * (layers + 1) + static_cast<std::size_t>(layer)]; };
        quads.push_back({id(i, k), id(i + 1, k), id(i + 1, k + 1), id(i, k + 1)});
        const Point& a = points[static_cast<std::size_t>(id(i, k))];
        const Point& b = points[static_cast<std::size_t>(id(i + 1, k))];
        const Point& c = points[static_cast<std::size_t>(id(i + 1, k + 1))];
        const Point& d = points[static_cast<std::size_t>(id(i, k + 1))];
        const double area = 0.5 * ((c - a).x() * (d - b).y() - (c - a).y() * (d - b).x());
        if (area <= 0.0) {
          throw BadInput("boundary layer folds at " + format_point(a) + " (layer " +
                         std::to_string(k + 1) + " of " + std::to_string(layers) +
                         "): reduce mesh.max_layers, mesh.growth or the "
                         "first layer height, or refine mesh.wall_size");
        }
      }
    }
  }
  const auto top = [&](const Run& run, std::size_t node) { return run.ids[node * (layers + 1) + static_cast<std::size_t>(layers)]; };

  // gmsh: the loop made of strip tops and non-wall pieces; triangles inside.
  GmshSession session;
  gmsh::model::add("flow");
  gmsh::option::setNumber("Mesh.Algorithm", options.algorithm);
  gmsh::option::setNumber("Mesh.MeshSizeExtendFromBoundary", 1);
  gmsh::option::setNumber("Mesh.MeshSizeFromPoints", 1);
  gmsh::option::setNumber("Mesh.MeshSizeFromCurvature", 0);
  // On an error gmsh stops meshing and records it (read below) instead of throwing: its throw
  // from inside its own OpenMP region could not be caught and aborted the tool (seen on a boundary
  // loop whose wall-layer tops crossed).
  gmsh::option::setNumber("General.AbortOnError", 1);
  // The loop as gmsh vertices: strip tops (lines between them fixed to one segment) and the
  // vertices of the non-wall pieces. The line leaving a vertex belongs to `line_piece`.
  struct Vertex {
    Point point;
    double size;
    std::int64_t node;  // our node id, or -1 (gmsh's)
    bool fixed;
    std::size_t line_piece;
  };
  // Mesh size at a strip-top point: its top edges (longer than the wall edges around convex
  // corners, where the layers fan out), at least twice the last layer.
  auto edge_size = [&](const Run& run, std::size_t i) {
    const std::size_t n = run.nodes.size();
    const auto at = [&](std::size_t k) { return points[static_cast<std::size_t>(top(run, k))]; };
    const double back = i > 0 ? (at(i) - at(i - 1)).norm() : 0.0;
    const double ahead = i + 1 < n ? (at(i + 1) - at(i)).norm() : 0.0;
    const double last_layer = layers > 0 ? heights.back() - heights[heights.size() - 2] : 0.0;
    return std::max({back, ahead, 2.0 * last_layer});
  };
  std::vector<Vertex> vertices;
  for (std::size_t k = 0; k < np; ++k) {
    const std::size_t i = (first_non_wall + k) % np;
    if (is_wall(i)) {
      const Run& run = runs[static_cast<std::size_t>(run_of_piece[i])];
      if (run.pieces.front() != i) continue;  // a run is walked once, at its first piece
      const std::size_t after = (run.pieces.back() + 1) % np;
      for (std::size_t n = 0; n < run.nodes.size(); ++n) {
        const bool last = n + 1 == run.nodes.size();
        vertices.push_back({points[static_cast<std::size_t>(top(run, n))], edge_size(run, n), top(run, n),
                            !last, last ? after : i});
      }
      continue;
    }
    const Polyline& line = pieces[i].points;
    const bool after_run = is_wall((i + np - 1) % np);
    const double size = pieces[i].kind == "inflow" ? std::min(far_size, 4.0 * wall_size) : far_size;
    for (std::size_t v = after_run ? 1 : 0; v + 1 < line.size(); ++v) {
      vertices.push_back({line[v], size, -1, false, i});
    }
  }
  std::map<int, std::int64_t> point_node;  // gmsh point tag -> our node id
  std::vector<int> point_tags, loop_curves;
  struct GmshLine { int tag; std::size_t piece; };
  std::vector<GmshLine> free_lines;  // non-wall lines meshed by gmsh, with their piece
  for (const Vertex& v : vertices) {
    const int tag = gmsh::model::geo::addPoint(v.point.x(), v.point.y(), 0.0, v.size);
    if (v.node >= 0) point_node[tag] = v.node;
    point_tags.push_back(tag);
  }
  for (std::size_t j = 0; j < vertices.size(); ++j) {
    const int line = gmsh::model::geo::addLine(point_tags[j], point_tags[(j + 1) % vertices.size()]);
    if (vertices[j].fixed) gmsh::model::geo::mesh::setTransfiniteCurve(line, 2);
    else free_lines.push_back({line, vertices[j].line_piece});
    loop_curves.push_back(line);
  }
  // The jet: a box from the nozzle exit over one nozzle length downstream, as high as the exit,
  // meshed at three wall sizes (the far-field size elsewhere would smear the shear layers).
  {
    double exit_half_height = 0.0;
    for (const auto& f : model.flaps) {
      for (const auto& p : f.reference_geometry) {
        if (p.x() >= x_hi - 1e-9 * nozzle_length) exit_half_height = std::max(exit_half_height, std::abs(p.y()));
      }
    }
    const int box = gmsh::model::mesh::field::add("Box");
    gmsh::model::mesh::field::setNumber(box, "VIn", std::min(far_size, 3.0 * wall_size));
    gmsh::model::mesh::field::setNumber(box, "VOut", far_size);
    gmsh::model::mesh::field::setNumber(box, "XMin", x_hi);
    gmsh::model::mesh::field::setNumber(box, "XMax", x_hi + nozzle_length);
    gmsh::model::mesh::field::setNumber(box, "YMin", -1.3 * exit_half_height);
    gmsh::model::mesh::field::setNumber(box, "YMax", 1.3 * exit_half_height);
    gmsh::model::mesh::field::setNumber(box, "Thickness", 0.5 * nozzle_length);
    gmsh::model::mesh::field::setAsBackgroundMesh(box);
  }
  const int loop = gmsh::model::geo::addCurveLoop(loop_curves);
  const int surface = gmsh::model::geo::addPlaneSurface({loop});
  gmsh::model::geo::synchronize();
  // The messages of this generate() only (the last-error slot would outlive a session).
  std::string gmsh_error;
  gmsh::option::setNumber("General.Verbosity", 1);  // errors only, for the logger
  gmsh::logger::start();
  try {
    gmsh::model::mesh::generate(2);
  } catch (...) {
    gmsh_error = "exception";
  }
  std::vector<std::string> gmsh_log;
  gmsh::logger::get(gmsh_log);
  gmsh::logger::stop();
  for (const auto& line : gmsh_log) {
    if (gmsh_error.empty() && line.rfind("Error: ", 0) == 0) gmsh_error = line.substr(7);
  }
  if (!gmsh_error.empty()) {
    throw BadInput("gmsh failed to mesh the flow domain (" + gmsh_error +
                   "): check the domain outline, the mesh sizes and the wall layers");
  }
  // Nodes.
  std::map<std::size_t, std::int64_t> gmsh_node;
  for (const auto& [tag, node] : point_node) {
    std::vector<std::size_t> tags;
    std::vector<double> xyz, param;
    gmsh::model::mesh::getNodes(tags, xyz, param, 0, tag);
    if (tags.size() == 1) gmsh_node[tags[0]] = node;
  }
  {
    std::vector<std::size_t> tags;
    std::vector<double> xyz, param;
    gmsh::model::mesh::getNodes(tags, xyz, param, -1, -1, false, false);
    for (std::size_t n = 0; n < tags.size(); ++n) {
      if (gmsh_node.count(tags[n])) continue;
      gmsh_node[tags[n]] = static_cast<std::int64_t>(points.size());
      points.emplace_back(xyz[3 * n], xyz[3 * n + 1]);
    }
  }
  std::vector<std::array<std::int64_t, 3>> triangles;
  {
    std::vector<int> types;
    std::vector<std::vector<std::size_t>> element_tags, node_tags;
    gmsh::model::mesh::getElements(types, element_tags, node_tags, 2, surface);
    for (std::size_t t = 0; t < types.size(); ++t) {
      if (types[t] != 2) throw InternalError("gmsh produced non-triangle elements (type " + std::to_string(types[t]) + ")");
      for (std::size_t e = 0; e + 2 < node_tags[t].size(); e += 3) {
        triangles.push_back({gmsh_node.at(node_tags[t][e]), gmsh_node.at(node_tags[t][e + 1]), gmsh_node.at(node_tags[t][e + 2])});
      }
    }
  }
  // Boundary edges: walls from the runs, the rest from gmsh lines plus the strip side edges.
  std::map<std::size_t, std::vector<std::array<std::int64_t, 2>>> edges_of_piece;
  for (const Run& run : runs) {
    for (std::size_t p = 0; p < run.pieces.size(); ++p) {
      const std::size_t first = run.piece_start[p];
      const std::size_t last = p + 1 < run.pieces.size() ? run.piece_start[p + 1] : run.nodes.size() - 1;
      auto& edges = edges_of_piece[run.pieces[p]];
      for (std::size_t n = first; n < last; ++n) edges.push_back({run.ids[n * (layers + 1)], run.ids[(n + 1) * (layers + 1)]});
    }
  }
  for (const Run& run : runs) {
    // Side edges: before the run they end the previous piece (going down to the wall), after
    // the run they start the next piece (going up from the wall).
    const std::size_t before = (run.pieces.front() + np - 1) % np;
    for (int k = layers; k > 0; --k) {
      edges_of_piece[before].push_back({run.ids[static_cast<std::size_t>(k)], run.ids[static_cast<std::size_t>(k - 1)]});
    }
  }
  for (const GmshLine& line : free_lines) {
    std::vector<int> types;
    std::vector<std::vector<std::size_t>> element_tags, node_tags;
    gmsh::model::mesh::getElements(types, element_tags, node_tags, 1, line.tag);
    auto& edges = edges_of_piece[line.piece];
    for (std::size_t t = 0; t < types.size(); ++t) {
      for (std::size_t e = 0; e + 1 < node_tags[t].size(); e += 2) {
        edges.push_back({gmsh_node.at(node_tags[t][e]), gmsh_node.at(node_tags[t][e + 1])});
      }
    }
  }
  for (const Run& run : runs) {
    const std::size_t after = (run.pieces.back() + 1) % np;
    const std::size_t last = run.nodes.size() - 1;
    for (int k = 0; k < layers; ++k) {
      edges_of_piece[after].push_back({run.ids[last * (layers + 1) + static_cast<std::size_t>(k)],
                                       run.ids[last * (layers + 1) + static_cast<std::size_t>(k) + 1]});
    }
  }
  // Fill the mesh; order every boundary's edges head to tail along the loop direction.
  mesh.points.resize(static_cast<Eigen::Index>(points.size()), 2);
  for (std::size_t i = 0; i < points.size(); ++i) mesh.points.row(static_cast<Eigen::Index>(i)) = points[i].transpose();
  mesh.triangles.resize(static_cast<Eigen::Index>(triangles.size()), 3);
  for (std::size_t i = 0; i < triangles.size(); ++i) {
    for (int k = 0; k < 3; ++k) mesh.triangles(static_cast<Eigen::Index>(i), k) = triangles[i][static_cast<std::size_t>(k)];
  }
  mesh.quads.resize(static_cast<Eigen::Index>(quads.size()), 4);
  for (std::size_t i = 0; i < quads.size(); ++i) {
    for (int k = 0; k < 4; ++k) mesh.quads(static_cast<Eigen::Index>(i), k) = quads[i][static_cast<std::size_t>(k)];
  }
  orient_counter_clockwise(mesh);
  for (std::size_t i = 0; i < np; ++i) {
    auto edges = edges_of_piece[i];
    if (edges.empty()) throw InternalError("no mesh edges on boundary '" + pieces[i].name + "'");
    // Orient each edge along the piece direction and chain them from the piece's start.
    const Point start = pieces[i].points.front();
    std::map<std::int64_t, std::vector<std::size_t>> at_node;
    for (std::size_t e = 0; e < edges.size(); ++e) {
      at_node[edges[e][0]].push_back(e);
      at_node[edges[e][1]].push_back(e);
    }
    std::int64_t head = -1;
    double best = 1e300;
    for (const auto& [node, list] : at_node) {
      if (list.size() != 1) continue;
      const double d = (points[static_cast<std::size_t>(node)] - start).norm();
      if (d < best) {
        best = d;
        head = node;
      }
    }
    if (head < 0) throw InternalError("boundary '" + pieces[i].name + "' edges do not form an open chain");
    formats::Boundary boundary;
    boundary.kind = pieces[i].kind;
    boundary.flap = pieces[i].flap;
    boundary.side = pieces[i].side;
    boundary.edges.resize(static_cast<Eigen::Index>(edges.size()), 2);
    std::vector<bool> used(edges.size(), false);
    for (std::size_t count = 0; count < edges.size(); ++count) {
      std::size_t next = edges.size();
      for (std::size_t e : at_node[head]) {
        if (!used[e]) next = e;
      }
      if (next == edges.size()) throw InternalError("boundary '" + pieces[i].name + "' edges are not one chain");
      used[next] = true;
      const std::int64_t tail = edges[next][0] == head ? edges[next][1] : edges[next][0];
      boundary.edges(static_cast<Eigen::Index>(count), 0) = head;
      boundary.edges(static_cast<Eigen::Index>(count), 1) = tail;
      head = tail;
    }
    mesh.boundaries[pieces[i].name] = std::move(boundary);
  }
  std::vector<std::int64_t> all(mesh.cell_count());
  for (std::size_t c = 0; c < all.size(); ++c) all[c] = static_cast<std::int64_t>(c);
  mesh.regions["fluid"] = all;
  report.quality = mesh_quality(mesh);
  if (report.first_layer_height > 0.0) {
    report.estimated_yplus = estimated_yplus(model, report.first_layer_height);
  }
  report.seconds = clock.seconds();
  log.verbose("flow mesh: " + std::to_string(runs.size()) + " wall runs, " +
              std::to_string(layers) + " layers, total " + text::format_number(heights.back(), 4) +
              " m");
  return mesh;
}

}  // namespace tfmb::mesh
