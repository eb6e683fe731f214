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
  std::size_t piece;  // index within the run
  Polyline line;
  double size = 0.0;  // [m] target spacing inside the part
  int min_segments = 1;
};

// Splits the wall pieces of a run at their corners.
std::vector<Part> split_at_corners(const std::vector<const Polyline*>& lines,
                                   const std::vector<int>& min_segments, double wall_size) {
  std::vector<Part> parts;
  for (std::size_t p = 0; p < lines.size(); ++p) {
    const Polyline& line = *lines[p];
    std::vector<std::size_t> corners{0};
    for (std::size_t i = 1; i + 1 < line.size(); ++i) {
      const Point a = (line[i] - line[i - 1]).normalized(),
                  b = (line[i + 1] - line[i]).normalized();
      if (a.dot(b) < std::cos(10.0 * M_PI / 180.0))
        corners.push_back(i);
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
std::vector<std::array<double, 3>> curvature_spacing(const Polyline& line, int cells_per_circle,
                                                     double scale) {
  std::vector<std::array<double, 3>> out;
  if (cells_per_circle <= 0 || line.size() < 3)
    return out;
  const double total = length(line);
  double s = 0.0;
  for (std::size_t i = 1; i + 1 < line.size(); ++i) {
    const Point back = line[i] - line[i - 1], ahead = line[i + 1] - line[i];
    s += back.norm();
    const double turn =
        std::atan2(std::abs(back.x() * ahead.y() - back.y() * ahead.x()), back.dot(ahead));
    if (turn < 1e-9)
      continue;
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
Polyline sample_part(const Part& part, double a, double b, double g, int cells_per_circle,
                     double scale) {
  const double total = length(part.line);
  const int samples = 2000;
  std::vector<double> cumulative(samples + 1, 0.0);
  const auto curved = curvature_spacing(part.line, cells_per_circle, scale);
  auto spacing = [&](double x) {
    double h = std::min({part.size, a + g * x, b + g * (total - x)});
    for (const auto& [from, to, c] : curved)
      h = std::min(h, c + g * std::max({0.0, from - x, x - to}));
    return h;
  };
  for (int i = 1; i <= samples; ++i) {
    const double x0 = total * (i - 1) / samples, x1 = total * i / samples;
    cumulative[static_cast<std::size_t>(i)] =
        cumulative[static_cast<std::size_t>(i - 1)] +
        (x1 - x0) * 0.5 * (1.0 / spacing(x0) + 1.0 / spacing(x1));
  }
  const int n = std::max(part.min_segments, static_cast<int>(std::lround(cumulative.back())));
  std::vector<double> s{0.0};
  for (int k = 1; k < n; ++k) {
    const double target = cumulative.back() * k / n;
    const auto it = std::lower_bound(cumulative.begin(), cumulative.end(), target);
    const std::size_t i =
        static_cast<std::size_t>(std::max<std::ptrdiff_t>(1, it - cumulative.begin()));
    const double f = (target - cumulative[i - 1]) / (cumulative[i] - cumulative[i - 1]);
    s.push_back(total * (static_cast<double>(i - 1) + f) / samples);
  }
  s.push_back(total);
  Polyline out = points_at(part.line, s);
  out.front() = part.line.front();
  out.back() = part.line.back();
  return out;
}

using Edge = std::array<std::int64_t, 2>;

bool is_wall(const formats::DomainBoundary& piece) {
  return piece.kind == "wall" || piece.kind == "slip_wall";
}

// A maximal sequence of consecutive wall pieces and the strip of quad layers along it.
struct Run {
  std::vector<std::size_t> pieces;       // domain boundary indices, loop order
  std::vector<Point> nodes;              // wall nodes along the run
  std::vector<std::size_t> piece_start;  // first node index of each piece in `nodes`
  std::vector<Point> normals;            // layer directions (mitred)
  int layers = 0;                        // quad layers of the strip
  std::vector<std::int64_t> ids;         // mesh node ids, (layers+1) per wall node, wall first

  std::int64_t id(std::size_t node, int layer) const {
    return ids[node * (layers + 1) + static_cast<std::size_t>(layer)];
  }
  std::int64_t top(std::size_t node) const { return id(node, layers); }
};

// The walls of the domain loop grouped into runs. The loop is cyclic: it is walked from its first
// non-wall piece so that no run wraps around the start.
struct WallRuns {
  std::vector<Run> runs;
  std::vector<int> run_of_piece;   // run index of each domain boundary; -1: not a wall
  std::size_t first_non_wall = 0;  // domain boundary the loop is walked from
};

// Target sizes of a nozzle mesh [m], already multiplied by the mesh scale.
struct NozzleSizes {
  double exit_x = 0.0;         // downstream end of the flaps
  double nozzle_length = 0.0;  // streamwise extent of the flaps
  double wall = 0.0;           // spacing along the walls
  double far = 0.0;            // far-field spacing
  double first_layer = 0.0;    // first wall-layer height
  double growth = 1.0;         // [1] wall-layer height ratio
};

// Nodes and cells of the mesh as they are built: the wall strips first, gmsh's nodes and
// triangles appended.
struct CellArrays {
  std::vector<Point> points;
  std::vector<std::array<std::int64_t, 3>> triangles;
  std::vector<std::array<std::int64_t, 4>> quads;
};

// The edges gmsh put on one of the non-wall lines of the loop.
struct FreeLineEdges {
  std::size_t piece;
  std::vector<Edge> edges;
};

// Sizes from the model's mesh controls; the defaults scale with the flaps' streamwise extent
// (a hundredth of it along the walls, 25 wall sizes in the far field).
NozzleSizes nozzle_sizes(const Model& model, double scale) {
  double x_lo = 1e300, x_hi = -1e300;
  for (const auto& f : model.flaps) {
    for (const auto& p : f.reference_geometry) {
      x_lo = std::min(x_lo, p.x());
      x_hi = std::max(x_hi, p.x());
    }
  }
  NozzleSizes sizes;
  sizes.exit_x = x_hi;
  sizes.nozzle_length = x_hi - x_lo;
  sizes.wall =
      (model.mesh.wall_size > 0 ? model.mesh.wall_size : sizes.nozzle_length / 100.0) * scale;
  sizes.far = (model.mesh.far_size > 0 ? model.mesh.far_size : 25.0 * sizes.wall / scale) * scale;
  sizes.first_layer = model.flow.first_cell_height * scale;
  sizes.growth = model.mesh.growth;
  return sizes;
}

// Groups the walls of the domain loop into runs: each run gets one strip of layers, so the layers
// stay continuous across the joins between consecutive walls.
WallRuns find_wall_runs(const std::vector<formats::DomainBoundary>& pieces) {
  const std::size_t np = pieces.size();
  WallRuns walls;
  while (walls.first_non_wall < np && is_wall(pieces[walls.first_non_wall]))
    ++walls.first_non_wall;
  if (walls.first_non_wall == np)
    throw BadInput("flow domain has walls only: no inflow or far field");
  walls.run_of_piece.assign(np, -1);
  for (std::size_t k = 1; k <= np; ++k) {
    const std::size_t i = (walls.first_non_wall + k) % np;
    if (!is_wall(pieces[i]))
      continue;
    const std::size_t prev = (i + np - 1) % np;
    if (!is_wall(pieces[prev]))
      walls.runs.emplace_back();
    walls.runs.back().pieces.push_back(i);
    walls.run_of_piece[i] = static_cast<int>(walls.runs.size() - 1);
  }
  return walls;
}

// The wall nodes of a run: each wall split at its corners and every part sampled with a spacing
// graded from its neighbours' (sample_part); piece_start records where each wall begins.
void sample_wall_run(Run& run, const std::vector<formats::DomainBoundary>& pieces,
                     const Model& model, const NozzleSizes& sizes, double scale) {
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
  const auto parts = split_at_corners(lines, min_segments, sizes.wall);
  std::size_t current_piece = parts.size();
  for (std::size_t k = 0; k < parts.size(); ++k) {
    const double a = k > 0 ? std::min(parts[k].size, parts[k - 1].size) : parts[k].size;
    const double b =
        k + 1 < parts.size() ? std::min(parts[k].size, parts[k + 1].size) : parts[k].size;
    const Polyline d = sample_part(parts[k], a, b, 0.25, model.mesh.cells_per_circle, scale);
    if (parts[k].piece != current_piece) {
      current_piece = parts[k].piece;
      run.piece_start.push_back(run.nodes.empty() ? 0 : run.nodes.size() - 1);
    }
    run.nodes.insert(run.nodes.end(), run.nodes.empty() ? d.begin() : d.begin() + 1, d.end());
  }
}

// Layer directions of a run: mitred vertex normals along the walls; at the run ends the layers
// follow the adjacent non-wall boundary (the left domain face), stretched so that their height
// normal to the wall is kept (at most 2.5 times, a cosine floor of 0.4).
void set_layer_directions(Run& run, const std::vector<formats::DomainBoundary>& pieces) {
  const std::size_t np = pieces.size();
  run.normals = vertex_normals(run.nodes, 2.5);
  const auto& before = pieces[(run.pieces.front() + np - 1) % np].points;
  const auto& after = pieces[(run.pieces.back() + 1) % np].points;
  const Point d_in = -(before.back() - before[before.size() - 2]).normalized();
  const Point d_out = (after[1] - after[0]).normalized();
  const Point n0 = geometry::left_normal(run.nodes[0], run.nodes[1]);
  const Point n1 = geometry::left_normal(run.nodes[run.nodes.size() - 2], run.nodes.back());
  run.normals.front() = d_in / std::max(d_in.dot(n0), 0.4);
  run.normals.back() = d_out / std::max(d_out.dot(n1), 0.4);
}

// Height of a stack of n geometrically growing layers (sum of h1 growth^k, k < n).
double stack_thickness(const NozzleSizes& sizes, int n) {
  const double h1 = sizes.first_layer, growth = sizes.growth;
  return growth == 1.0 ? n * h1 : h1 * (std::pow(growth, n) - 1.0) / (growth - 1.0);
}

// Layers wanted from the sizes alone: grow until a layer reaches half the wall spacing (then the
// triangles take over at about the wall size), at most mesh.max_layers.
int layers_for_wall_spacing(const Model& model, const NozzleSizes& sizes) {
  int layers = 0;
  if (sizes.first_layer > 0.0 && model.mesh.max_layers > 0) {
    layers = 1;
    while (layers < model.mesh.max_layers &&
           sizes.first_layer * std::pow(sizes.growth, layers - 1) < 0.5 * sizes.wall) {
      ++layers;
    }
  }
  return layers;
}

// Room between the strips: the smallest distance between the nodes of different runs, and
// twice the length of the shortest non-wall face (a strip end must not swallow one).
double strip_clearance(const std::vector<Run>& runs,
                       const std::vector<formats::DomainBoundary>& pieces) {
  double clearance = 1e300;
  for (std::size_t a = 0; a < runs.size(); ++a) {
    for (std::size_t b = a + 1; b < runs.size(); ++b) {
      for (const Point& p : runs[a].nodes)
        clearance = std::min(clearance, distance_to(runs[b].nodes, p));
    }
  }
  for (const auto& piece : pieces) {
    if (!is_wall(piece))
      clearance = std::min(clearance, 2.0 * length(piece.points));
  }
  return clearance;
}

// Where a wall is concave on the flow side the layer directions converge and meet about one
// radius of curvature off the wall (a flap's outer face offset from a tight throat arc, once
// cells_per_circle resolves it): keep the stack below half the height at which the layer
// directions of two neighbouring wall nodes cross, so the strips' top edges keep at least half
// their wall edge's length and direction.
int layers_below_crossings(const std::vector<Run>& runs, const NozzleSizes& sizes, int layers) {
  for (const Run& run : runs) {
    for (std::size_t i = 0; i + 1 < run.nodes.size(); ++i) {
      const Point wall_edge = run.nodes[i + 1] - run.nodes[i];
      // The top edge at height t is wall_edge + t closing.
      const Point closing = run.normals[i + 1] - run.normals[i];
      const double rate = closing.dot(wall_edge);
      if (rate >= 0.0)
        continue;  // the layers fan out here
      const double crossing = -wall_edge.squaredNorm() / rate;
      while (layers > 0 && stack_thickness(sizes, layers) > 0.5 * crossing)
        --layers;
    }
  }
  return layers;
}

// Number of wall layers, the same on every run: as many as the wall spacing asks for, but the
// strips thinner than a quarter of the clearance between runs and free of crossing layer
// directions at concave walls.
int boundary_layer_count(const Model& model, const NozzleSizes& sizes, const WallRuns& walls,
                         const std::vector<formats::DomainBoundary>& pieces, const Logger& log) {
  int layers = layers_for_wall_spacing(model, sizes);
  const double clearance = strip_clearance(walls.runs, pieces);
  while (layers > 0 && stack_thickness(sizes, layers) > 0.25 * clearance)
    --layers;
  const int layers_wanted = layers;
  layers = layers_below_crossings(walls.runs, sizes, layers);
  if (layers_wanted > 0 && layers == 0) {
    throw BadInput(
        "wall layers fold even one layer high where a wall is concave: reduce the first layer "
        "height, or refine mesh.wall_size");
  }
  if (layers < layers_wanted) {
    log.info("wall layers limited to " + std::to_string(layers) + " of " +
             std::to_string(layers_wanted) + " (" +
             text::format_number(stack_thickness(sizes, layers), 4) +
             " m thick): more would fold where a wall is concave");
  }
  return layers;
}

// Heights of the layer tops above the wall, from 0 (the wall) to the stack thickness.
std::vector<double> layer_heights(const NozzleSizes& sizes, int layers) {
  std::vector<double> heights(static_cast<std::size_t>(layers) + 1, 0.0);
  for (int k = 1; k <= layers; ++k)
    heights[static_cast<std::size_t>(k)] = stack_thickness(sizes, k);
  return heights;
}

// Throws if the strip quad (i, k) of a run is inverted: the layer directions of its wall nodes
// crossed below its top.
void check_strip_quad(const Run& run, const std::vector<Point>& points, std::size_t i, int k) {
  const Point& a = points[static_cast<std::size_t>(run.id(i, k))];
  const Point& b = points[static_cast<std::size_t>(run.id(i + 1, k))];
  const Point& c = points[static_cast<std::size_t>(run.id(i + 1, k + 1))];
  const Point& d = points[static_cast<std::size_t>(run.id(i, k + 1))];
  // Signed area of a quadrilateral: half the cross product of its diagonals.
  const double area = 0.5 * ((c - a).x() * (d - b).y() - (c - a).y() * (d - b).x());
  if (area <= 0.0) {
    throw BadInput("boundary layer folds at " + format_point(a) + " (layer " +
                   std::to_string(k + 1) + " of " + std::to_string(run.layers) +
                   "): reduce mesh.max_layers, mesh.growth or the "
                   "first layer height, or refine mesh.wall_size");
  }
}

// The structured strips: the nodes of every run at every layer height along its layer
// directions, and the quads between them.
void build_wall_strips(std::vector<Run>& runs, const std::vector<double>& heights,
                       CellArrays& cells) {
  const int layers = static_cast<int>(heights.size()) - 1;
  for (Run& run : runs) {
    const std::size_t n = run.nodes.size();
    run.layers = layers;
    run.ids.resize(n * (static_cast<std::size_t>(layers) + 1));
    for (std::size_t i = 0; i < n; ++i) {
      for (int k = 0; k <= layers; ++k) {
        run.ids[i * (layers + 1) + static_cast<std::size_t>(k)] =
            static_cast<std::int64_t>(cells.points.size());
        cells.points.push_back(run.nodes[i] +
                               heights[static_cast<std::size_t>(k)] * run.normals[i]);
      }
    }
    for (std::size_t i = 0; i + 1 < n; ++i) {
      for (int k = 0; k < layers; ++k) {
        cells.quads.push_back(
            {run.id(i, k), run.id(i + 1, k), run.id(i + 1, k + 1), run.id(i, k + 1)});
        check_strip_quad(run, cells.points, i, k);
      }
    }
  }
}

// A vertex of the loop handed to gmsh. The line leaving it belongs to `line_piece`; `fixed`
// lines (between strip tops) are one segment, the others gmsh subdivides.
struct LoopVertex {
  Point point;
  double size;
  std::int64_t node;  // our node id, or -1 (gmsh's)
  bool fixed;
  std::size_t line_piece;
};

// Mesh size at a strip-top point: its top edges (longer than the wall edges around convex
// corners, where the layers fan out), at least twice the last layer.
double strip_top_size(const Run& run, std::size_t i, const std::vector<Point>& points,
                      const std::vector<double>& heights) {
  const std::size_t n = run.nodes.size();
  const auto at = [&](std::size_t k) { return points[static_cast<std::size_t>(run.top(k))]; };
  const double back = i > 0 ? (at(i) - at(i - 1)).norm() : 0.0;
  const double ahead = i + 1 < n ? (at(i + 1) - at(i)).norm() : 0.0;
  const double last_layer = run.layers > 0 ? heights.back() - heights[heights.size() - 2] : 0.0;
  return std::max({back, ahead, 2.0 * last_layer});
}

// The boundary of the region gmsh triangulates: the strip tops in place of the walls, and the
// vertices of the non-wall pieces (inflow at up to four wall sizes, the rest at the far size).
std::vector<LoopVertex> triangulated_loop(const std::vector<formats::DomainBoundary>& pieces,
                                          const WallRuns& walls, const NozzleSizes& sizes,
                                          const std::vector<Point>& points,
                                          const std::vector<double>& heights) {
  const std::size_t np = pieces.size();
  std::vector<LoopVertex> vertices;
  for (std::size_t k = 0; k < np; ++k) {
    const std::size_t i = (walls.first_non_wall + k) % np;
    if (is_wall(pieces[i])) {
      const Run& run = walls.runs[static_cast<std::size_t>(walls.run_of_piece[i])];
      if (run.pieces.front() != i)
        continue;  // a run is walked once, at its first piece
      const std::size_t after = (run.pieces.back() + 1) % np;
      for (std::size_t n = 0; n < run.nodes.size(); ++n) {
        const bool last = n + 1 == run.nodes.size();
        vertices.push_back({points[static_cast<std::size_t>(run.top(n))],
                            strip_top_size(run, n, points, heights), run.top(n), !last,
                            last ? after : i});
      }
      continue;
    }
    const Polyline& line = pieces[i].points;
    const bool after_run = is_wall(pieces[(i + np - 1) % np]);
    const double size =
        pieces[i].kind == "inflow" ? std::min(sizes.far, 4.0 * sizes.wall) : sizes.far;
    for (std::size_t v = after_run ? 1 : 0; v + 1 < line.size(); ++v) {
      vertices.push_back({line[v], size, -1, false, i});
    }
  }
  return vertices;
}

// The jet: a box from the nozzle exit over one nozzle length downstream, as high as the exit,
// meshed at three wall sizes (the far-field size elsewhere would smear the shear layers).
void refine_jet(const Model& model, const NozzleSizes& sizes) {
  double exit_half_height = 0.0;
  for (const auto& f : model.flaps) {
    for (const auto& p : f.reference_geometry) {
      if (p.x() >= sizes.exit_x - 1e-9 * sizes.nozzle_length)
        exit_half_height = std::max(exit_half_height, std::abs(p.y()));
    }
  }
  const int box = gmsh::model::mesh::field::add("Box");
  gmsh::model::mesh::field::setNumber(box, "VIn", std::min(sizes.far, 3.0 * sizes.wall));
  gmsh::model::mesh::field::setNumber(box, "VOut", sizes.far);
  gmsh::model::mesh::field::setNumber(box, "XMin", sizes.exit_x);
  gmsh::model::mesh::field::setNumber(box, "XMax", sizes.exit_x + sizes.nozzle_length);
  gmsh::model::mesh::field::setNumber(box, "YMin", -1.3 * exit_half_height);
  gmsh::model::mesh::field::setNumber(box, "YMax", 1.3 * exit_half_height);
  gmsh::model::mesh::field::setNumber(box, "Thickness", 0.5 * sizes.nozzle_length);
  gmsh::model::mesh::field::setAsBackgroundMesh(box);
}

// Meshes the gmsh model in 2D; throws BadInput with gmsh's first error. On an error gmsh stops
// meshing and records it (General.AbortOnError = 1) instead of throwing: its throw from inside
// its own OpenMP region could not be caught and aborted the tool (seen on a boundary loop whose
// wall-layer tops crossed).
void generate_triangles() {
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
    if (gmsh_error.empty() && line.rfind("Error: ", 0) == 0)
      gmsh_error = line.substr(7);
  }
  if (!gmsh_error.empty()) {
    throw BadInput("gmsh failed to mesh the flow domain (" + gmsh_error +
                   "): check the domain outline, the mesh sizes and the wall layers");
  }
}

// gmsh's node tag -> our node id: the loop vertices on strip tops keep ours, every other gmsh
// node is appended to the points.
std::map<std::size_t, std::int64_t> gmsh_nodes(const std::map<int, std::int64_t>& point_node,
                                               std::vector<Point>& points) {
  std::map<std::size_t, std::int64_t> gmsh_node;
  for (const auto& [tag, node] : point_node) {
    std::vector<std::size_t> tags;
    std::vector<double> xyz, param;
    gmsh::model::mesh::getNodes(tags, xyz, param, 0, tag);
    if (tags.size() == 1)
      gmsh_node[tags[0]] = node;
  }
  std::vector<std::size_t> tags;
  std::vector<double> xyz, param;
  gmsh::model::mesh::getNodes(tags, xyz, param, -1, -1, false, false);
  for (std::size_t n = 0; n < tags.size(); ++n) {
    if (gmsh_node.count(tags[n]))
      continue;
    gmsh_node[tags[n]] = static_cast<std::int64_t>(points.size());
    points.emplace_back(xyz[3 * n], xyz[3 * n + 1]);
  }
  return gmsh_node;
}

// gmsh's elements of dimension `dim` on entity `tag`: per element type, the type and the node
// tags of all its elements.
struct GmshElements {
  std::vector<int> types;
  std::vector<std::vector<std::size_t>> node_tags;
};
GmshElements gmsh_elements(int dim, int tag) {
  GmshElements elements;
  std::vector<std::vector<std::size_t>> element_tags;
  gmsh::model::mesh::getElements(elements.types, element_tags, elements.node_tags, dim, tag);
  return elements;
}

// The loop as gmsh lines: a point per vertex (with its mesh size), lines between them, those
// between strip tops transfinite with one segment (the strip's top edges), the others for gmsh
// to subdivide.
struct LoopLines {
  std::vector<int> curves;                              // gmsh line tags, in loop order
  std::map<int, std::int64_t> point_node;               // gmsh point tag -> our node id
  std::vector<std::pair<int, std::size_t>> free_lines;  // lines gmsh subdivides, their piece
};
LoopLines add_loop_lines(const std::vector<LoopVertex>& vertices) {
  LoopLines loop;
  std::vector<int> point_tags;
  for (const LoopVertex& v : vertices) {
    const int tag = gmsh::model::geo::addPoint(v.point.x(), v.point.y(), 0.0, v.size);
    if (v.node >= 0)
      loop.point_node[tag] = v.node;
    point_tags.push_back(tag);
  }
  for (std::size_t j = 0; j < vertices.size(); ++j) {
    const int line =
        gmsh::model::geo::addLine(point_tags[j], point_tags[(j + 1) % vertices.size()]);
    if (vertices[j].fixed)
      gmsh::model::geo::mesh::setTransfiniteCurve(line, 2);
    else
      loop.free_lines.emplace_back(line, vertices[j].line_piece);
    loop.curves.push_back(line);
  }
  return loop;
}

// gmsh's triangles on the surface, in our node ids.
void append_triangles(int surface, const std::map<std::size_t, std::int64_t>& gmsh_node,
                      std::vector<std::array<std::int64_t, 3>>& triangles) {
  const GmshElements cells = gmsh_elements(2, surface);
  for (std::size_t t = 0; t < cells.types.size(); ++t) {
    const int type = cells.types[t];
    if (type != 2)
      throw InternalError("gmsh produced non-triangle elements (type " + std::to_string(type) +
                          ")");
    const auto& nodes = cells.node_tags[t];
    for (std::size_t e = 0; e + 2 < nodes.size(); e += 3) {
      triangles.push_back(
          {gmsh_node.at(nodes[e]), gmsh_node.at(nodes[e + 1]), gmsh_node.at(nodes[e + 2])});
    }
  }
}

// The segments gmsh put on each free line of the loop, in our node ids.
std::vector<FreeLineEdges> free_line_edges(const LoopLines& loop,
                                           const std::map<std::size_t, std::int64_t>& gmsh_node) {
  std::vector<FreeLineEdges> free_edges;
  for (const auto& [tag, piece] : loop.free_lines) {
    const GmshElements segments = gmsh_elements(1, tag);
    FreeLineEdges line{piece, {}};
    for (const auto& nodes : segments.node_tags) {
      for (std::size_t e = 0; e + 1 < nodes.size(); e += 2) {
        line.edges.push_back({gmsh_node.at(nodes[e]), gmsh_node.at(nodes[e + 1])});
      }
    }
    free_edges.push_back(std::move(line));
  }
  return free_edges;
}

// Triangulates the region inside the strip tops with gmsh: appends its nodes and triangles to
// `cells` and returns the edges it put on each non-wall line, in loop order.
std::vector<FreeLineEdges> triangulate_interior(const Model& model, int algorithm,
                                                const std::vector<formats::DomainBoundary>& pieces,
                                                const WallRuns& walls, const NozzleSizes& sizes,
                                                const std::vector<double>& heights,
                                                CellArrays& cells) {
  GmshSession session;
  gmsh::model::add("flow");
  gmsh::option::setNumber("Mesh.Algorithm", algorithm);
  gmsh::option::setNumber("Mesh.MeshSizeExtendFromBoundary", 1);
  gmsh::option::setNumber("Mesh.MeshSizeFromPoints", 1);
  gmsh::option::setNumber("Mesh.MeshSizeFromCurvature", 0);
  gmsh::option::setNumber("General.AbortOnError", 1);  // see generate_triangles
  const LoopLines loop =
      add_loop_lines(triangulated_loop(pieces, walls, sizes, cells.points, heights));
  refine_jet(model, sizes);
  const int curve_loop = gmsh::model::geo::addCurveLoop(loop.curves);
  const int surface = gmsh::model::geo::addPlaneSurface({curve_loop});
  gmsh::model::geo::synchronize();
  generate_triangles();
  const auto gmsh_node = gmsh_nodes(loop.point_node, cells.points);
  append_triangles(surface, gmsh_node, cells.triangles);
  return free_line_edges(loop, gmsh_node);
}

// The mesh edges on every domain boundary (unordered): walls from the runs, the rest from gmsh's
// lines plus the strips' side edges. Before a run they end the previous piece (going down to the
// wall), after it they start the next piece (going up from the wall).
std::vector<std::vector<Edge>> boundary_edges(std::size_t np, const std::vector<Run>& runs,
                                              const std::vector<FreeLineEdges>& free_edges) {
  std::vector<std::vector<Edge>> edges_of_piece(np);
  for (const Run& run : runs) {
    for (std::size_t p = 0; p < run.pieces.size(); ++p) {
      const std::size_t first = run.piece_start[p];
      const std::size_t last =
          p + 1 < run.pieces.size() ? run.piece_start[p + 1] : run.nodes.size() - 1;
      auto& edges = edges_of_piece[run.pieces[p]];
      for (std::size_t n = first; n < last; ++n)
        edges.push_back({run.id(n, 0), run.id(n + 1, 0)});
    }
  }
  for (const Run& run : runs) {
    const std::size_t before = (run.pieces.front() + np - 1) % np;
    for (int k = run.layers; k > 0; --k)
      edges_of_piece[before].push_back({run.id(0, k), run.id(0, k - 1)});
  }
  for (const FreeLineEdges& line : free_edges) {
    auto& edges = edges_of_piece[line.piece];
    edges.insert(edges.end(), line.edges.begin(), line.edges.end());
  }
  for (const Run& run : runs) {
    const std::size_t after = (run.pieces.back() + 1) % np;
    const std::size_t last = run.nodes.size() - 1;
    for (int k = 0; k < run.layers; ++k)
      edges_of_piece[after].push_back({run.id(last, k), run.id(last, k + 1)});
  }
  return edges_of_piece;
}

// A domain boundary of the mesh: its edges oriented along the piece and chained head to tail
// from the end nearest the piece's start.
formats::Boundary chained_boundary(const formats::DomainBoundary& piece,
                                   const std::vector<Edge>& edges,
                                   const std::vector<Point>& points) {
  if (edges.empty())
    throw InternalError("no mesh edges on boundary '" + piece.name + "'");
  const Point start = piece.points.front();
  std::map<std::int64_t, std::vector<std::size_t>> at_node;
  for (std::size_t e = 0; e < edges.size(); ++e) {
    at_node[edges[e][0]].push_back(e);
    at_node[edges[e][1]].push_back(e);
  }
  std::int64_t head = -1;
  double best = 1e300;
  for (const auto& [node, list] : at_node) {
    if (list.size() != 1)
      continue;
    const double d = (points[static_cast<std::size_t>(node)] - start).norm();
    if (d < best) {
      best = d;
      head = node;
    }
  }
  if (head < 0)
    throw InternalError("boundary '" + piece.name + "' edges do not form an open chain");
  formats::Boundary boundary;
  boundary.kind = piece.kind;
  boundary.flap = piece.flap;
  boundary.side = piece.side;
  boundary.edges.resize(static_cast<Eigen::Index>(edges.size()), 2);
  std::vector<bool> used(edges.size(), false);
  for (std::size_t count = 0; count < edges.size(); ++count) {
    std::size_t next = edges.size();
    for (std::size_t e : at_node[head]) {
      if (!used[e])
        next = e;
    }
    if (next == edges.size())
      throw InternalError("boundary '" + piece.name + "' edges are not one chain");
    used[next] = true;
    const std::int64_t tail = edges[next][0] == head ? edges[next][1] : edges[next][0];
    boundary.edges(static_cast<Eigen::Index>(count), 0) = head;
    boundary.edges(static_cast<Eigen::Index>(count), 1) = tail;
    head = tail;
  }
  return boundary;
}

// The mesh from its arrays: cells counter-clockwise, one boundary per domain piece, every cell
// in the region "fluid".
Mesh assemble_mesh(const std::vector<formats::DomainBoundary>& pieces, const CellArrays& cells,
                   const std::vector<std::vector<Edge>>& edges_of_piece) {
  Mesh mesh;
  const auto& points = cells.points;
  mesh.points.resize(static_cast<Eigen::Index>(points.size()), 2);
  for (std::size_t i = 0; i < points.size(); ++i)
    mesh.points.row(static_cast<Eigen::Index>(i)) = points[i].transpose();
  mesh.triangles.resize(static_cast<Eigen::Index>(cells.triangles.size()), 3);
  for (std::size_t i = 0; i < cells.triangles.size(); ++i) {
    for (int k = 0; k < 3; ++k)
      mesh.triangles(static_cast<Eigen::Index>(i), k) =
          cells.triangles[i][static_cast<std::size_t>(k)];
  }
  mesh.quads.resize(static_cast<Eigen::Index>(cells.quads.size()), 4);
  for (std::size_t i = 0; i < cells.quads.size(); ++i) {
    for (int k = 0; k < 4; ++k)
      mesh.quads(static_cast<Eigen::Index>(i), k) = cells.quads[i][static_cast<std::size_t>(k)];
  }
  orient_counter_clockwise(mesh);
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    mesh.boundaries[pieces[i].name] = chained_boundary(pieces[i], edges_of_piece[i], points);
  }
  std::vector<std::int64_t> all(mesh.cell_count());
  for (std::size_t c = 0; c < all.size(); ++c)
    all[c] = static_cast<std::int64_t>(c);
  mesh.regions["fluid"] = all;
  return mesh;
}

// How big the mesh will be, before anything is sampled: wall nodes from the wall lengths and the
// wall spacing, strip quads at the largest layer count, and a lower bound on the triangles (the
// domain's area in equilateral triangles of the far-field size, the largest anywhere). A tiny
// mesh.wall_size or --scale made tfmb-mesh sample and mesh for minutes without a word.
struct SizeEstimate {
  double wall_nodes = 0.0;
  double cells = 0.0;
};

SizeEstimate estimate_size(const Model& model, const std::vector<formats::DomainBoundary>& pieces,
                           const NozzleSizes& sizes) {
  SizeEstimate e;
  double twice_area = 0.0;  // shoelace over the domain loop
  for (const auto& piece : pieces) {
    if (is_wall(piece))
      e.wall_nodes += length(piece.points) / sizes.wall;
    for (std::size_t i = 0; i + 1 < piece.points.size(); ++i) {
      const Point& a = piece.points[i];
      const Point& b = piece.points[i + 1];
      twice_area += a.x() * b.y() - b.x() * a.y();
    }
  }
  const double triangle_area = std::sqrt(3.0) / 4.0 * sizes.far * sizes.far;
  e.cells = e.wall_nodes * std::max(0, model.mesh.max_layers) +
            0.5 * std::abs(twice_area) / triangle_area;
  return e;
}

// Structured quads for the channel and flat-plate domains (structured.cpp).
Mesh build_structured_flow_mesh(const Model& model, double scale, FlowMeshReport& report,
                                const Stopwatch& clock) {
  Mesh mesh = build_structured_mesh(model, scale, report);
  report.quality = mesh_quality(mesh);
  report.seconds = clock.seconds();
  return mesh;
}

}  // namespace

std::optional<double> estimated_yplus(const Model& model, double height) {
  if (!(model.flow.viscous_length > 0.0))
    return std::nullopt;
  return height / model.flow.viscous_length;
}

// The phases: sizes, wall runs (nodes and layer directions), the layer count, the structured
// strips, gmsh's triangles inside the strip tops, the mesh with its boundaries, the report.
Mesh build_flow_mesh(const Model& model, const FlowMeshOptions& options, FlowMeshReport& report,
                     const Logger& log) {
  Stopwatch clock;
  const auto& domain = model.domain;
  if (domain.settings.kind == "none" || domain.boundaries.empty()) {
    throw BadInput("the model has no flow domain (domain.kind = 'none'): nothing to mesh");
  }
  const double scale = options.scale > 0.0 ? options.scale : model.mesh.scale;
  report.estimated_yplus.reset();
  if (domain.settings.kind != "nozzle")
    return build_structured_flow_mesh(model, scale, report, clock);

  const auto& pieces = domain.boundaries;
  const NozzleSizes sizes = nozzle_sizes(model, scale);
  const SizeEstimate size = estimate_size(model, pieces, sizes);
  log.verbose("flow mesh: about " + text::format_number(size.wall_nodes, 3) +
              " wall nodes and at least " + text::format_number(size.cells, 3) + " cells expected");
  if (!(size.cells <= options.max_cells)) {
    throw BadInput("the flow mesh would have at least about " + text::format_number(size.cells, 3) +
                   " cells (" + text::format_number(size.wall_nodes, 3) +
                   " wall nodes at a wall spacing of " + text::format_number(sizes.wall, 3) +
                   " m, far-field spacing " + text::format_number(sizes.far, 3) +
                   " m), more than --max-cells " + text::format_number(options.max_cells, 3) +
                   ": check mesh.wall_size, mesh.far_size and mesh.scale (or --scale), or raise "
                   "--max-cells");
  }
  // Progress by phase: gmsh's triangulation is most of the time (24 of 26 s for config3 at
  // scale 0.5) and one call with no count of its own, so the line shows the phase, the time so
  // far and the expected size, not a rate and a time left.
  Progress progress(log, "flow mesh", 4, {.unit = "phases", .time_left = false});
  progress.update(0);
  WallRuns walls = find_wall_runs(pieces);
  for (Run& run : walls.runs) {
    sample_wall_run(run, pieces, model, sizes, scale);
    set_layer_directions(run, pieces);
  }
  const int layers = boundary_layer_count(model, sizes, walls, pieces, log);
  report.boundary_layers = layers;
  report.first_layer_height = layers > 0 ? sizes.first_layer : 0.0;
  const std::vector<double> heights = layer_heights(sizes, layers);

  CellArrays cells;
  build_wall_strips(walls.runs, heights, cells);
  progress.update(1);
  std::vector<FreeLineEdges> free_edges;
  progress.update_while(1,
                        "gmsh's triangulation (at least about " +
                            text::format_number(size.cells, 3) + " cells expected)",
                        [&] {
                          free_edges = triangulate_interior(model, options.algorithm, pieces, walls,
                                                            sizes, heights, cells);
                        });
  progress.update(2);
  Mesh mesh = assemble_mesh(pieces, cells, boundary_edges(pieces.size(), walls.runs, free_edges));
  progress.update(3);

  report.quality = mesh_quality(mesh);
  progress.update(4);
  progress.finish();
  if (report.first_layer_height > 0.0) {
    report.estimated_yplus = estimated_yplus(model, report.first_layer_height);
  }
  report.seconds = clock.seconds();
  log.verbose("flow mesh: " + std::to_string(walls.runs.size()) + " wall runs, " +
              std::to_string(layers) + " layers, total " + text::format_number(heights.back(), 4) +
              " m");
  return mesh;
}

}  // namespace tfmb::mesh
