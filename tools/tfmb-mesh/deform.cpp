// Mesh deformation for two-way coupling: wall nodes take the wall displacement exactly (linear
// interpolation along the walldisp curve), every other node the inverse-distance-weighted
// motion of all boundary nodes (Luke, Collins & Blades, J. Comput. Phys. 231 (2012) 586-601,
// eq. 2-3: w_i = A_i ((L/d_i)^a + (alpha L/d_i)^b), a = 3, b = 5, alpha = 0.1); other
// boundaries are held fixed. With rotations, each boundary node carries the
// rotation of its wall as well as its displacement, so that the cells near a turning wall turn
// with it instead of being sheared. Same topology, so the flow solver can restart.
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <sstream>

#include "mesh_tools.hpp"
#include "tfmb/common/errors.hpp"
#include "tfmb/common/polyline.hpp"
#include "tfmb/common/text.hpp"
#include "tfmb/formats/schema.hpp"
#include "tfmb/formats/walldisp.hpp"

namespace tfmb::mesh {
namespace {

using Vector = Eigen::Vector2d;

bool all_valid(const Mesh& mesh, const h5::MatrixXdR& points, std::int64_t* first_bad) {
  const auto cells = static_cast<std::int64_t>(mesh.cell_count());
  for (std::int64_t c = 0; c < cells; ++c) {
    if (cell_min_corner_area(points, mesh, c) <= 0.0) {
      if (first_bad)
        *first_bad = c;
      return false;
    }
  }
  return true;
}

bool is_wall(const formats::Boundary& boundary) {
  return boundary.kind == "wall" || boundary.kind == "slip_wall";
}

// The boundary nodes whose displacement is given, with the rotation of the wall there and the
// boundary length each stands for (the area A_i of the weights); every node not listed moves by
// interpolation.
struct BoundarySources {
  std::map<std::int64_t, Vector> prescribed;   // [m] displacement of a boundary node
  std::map<std::int64_t, double> rotation;     // [rad] counter-clockwise turn of its wall
  std::map<std::int64_t, double> node_length;  // [m] half the length of its boundary edges
};

// The motion of a node that two or more walls give (the shared node of two flaps at a joint,
// whose sections move differently at a clearance joint or a hinge): their mean, so the result
// does not depend on which wall is read first.
class NodeMotions {
 public:
  void add(std::int64_t node, const Vector& u, double rotation) {
    Sum& sum = sums_[node];
    sum.u += u;
    sum.rotation += rotation;
    ++sum.count;
  }
  void put_into(BoundarySources& sources) const {
    for (const auto& [node, sum] : sums_) {
      sources.prescribed[node] = sum.u / sum.count;
      sources.rotation[node] = sum.rotation / sum.count;
    }
  }

 private:
  struct Sum {
    Vector u = Vector::Zero();
    double rotation = 0.0;
    int count = 0;
  };
  std::map<std::int64_t, Sum> sums_;
};

// [rad] counter-clockwise angle from a to b
double turn_angle(const Vector& a, const Vector& b) {
  return std::atan2(a.x() * b.y() - a.y() * b.x(), a.dot(b));
}

// [rad] the turn of the chord from point a to point b of a walldisp curve
double chord_turn(const WallDisplacement& w, std::size_t a, std::size_t b) {
  return turn_angle(w.x0[b] - w.x0[a], w.x0[b] + w.displacement[b] - w.x0[a] - w.displacement[a]);
}

// The turn of a walldisp curve at its point k: of the chord through its neighbours (one-sided at
// the ends); 0 for a single point.
double curve_rotation_at(const WallDisplacement& w, std::size_t k) {
  const std::size_t n = w.x0.size();
  if (n < 2)
    return 0.0;
  return chord_turn(w, k > 0 ? k - 1 : 0, std::min(k + 1, n - 1));
}

// The mesh nodes before the deformation and the diagonal of their bounding box (the length
// scale L of the weights and of every tolerance).
struct NodePositions {
  std::vector<Vector> x;  // [m]
  double extent = 0.0;    // [m]
  double tight = 0.0;     // [m] a node this close to a walldisp curve lies on it
};

NodePositions node_positions(const Mesh& mesh) {
  NodePositions nodes;
  const auto n = static_cast<std::size_t>(mesh.points.rows());
  nodes.x.resize(n);
  for (std::size_t i = 0; i < n; ++i)
    nodes.x[i] = mesh.points.row(static_cast<Eigen::Index>(i)).transpose();
  Vector lo = nodes.x[0], hi = nodes.x[0];
  for (const auto& p : nodes.x) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  nodes.extent = (hi - lo).norm();
  nodes.tight = 1e-9 * nodes.extent + 1e-12;
  return nodes;
}

// Walldisp points that name their flow-mesh node (tfmb-loads writes them for the mesh it read)
// prescribe that node; a point away from its node means the file belongs to another mesh.
void prescribe_named_nodes(const std::vector<WallDisplacement>& walls, const NodePositions& nodes,
                           NodeMotions& motions) {
  const std::size_t n = nodes.x.size();
  for (const auto& w : walls) {
    for (std::size_t k = 0; k < w.nodes.size(); ++k) {
      const auto node = w.nodes[k];
      if (node >= static_cast<std::int64_t>(n)) {
        throw BadInput("walldisp: /walls/" + w.name + "/node: node " + std::to_string(node) +
                       " is not in the flow mesh (" + std::to_string(n) + " nodes)");
      }
      const double d = (nodes.x[static_cast<std::size_t>(node)] - w.x0[k]).norm();
      if (d > nodes.tight + 1e-6 * nodes.extent) {
        throw BadInput("walldisp: /walls/" + w.name + "/x0 row " + std::to_string(k) + " is " +
                       text::format_number(d) + " m from flow-mesh node " + std::to_string(node) +
                       ": computed for another mesh");
      }
      motions.add(node, w.displacement[k], curve_rotation_at(w, k));
    }
  }
}

// Every walldisp wall must name a wall of the mesh, unless it is a curve of a flap the mesh
// walls are matched to by flap (model walls such as <flap>_<side>).
void check_wall_names(const Mesh& mesh, const std::vector<WallDisplacement>& walls) {
  for (const auto& w : walls) {
    auto it = mesh.boundaries.find(w.name);
    if (it == mesh.boundaries.end() && (w.flap.empty() || w.nodes.size())) {
      throw BadInput("walldisp: boundary '" + w.name + "' is not in the flow mesh");
    }
    if (it != mesh.boundaries.end() && !is_wall(it->second)) {
      throw BadInput("walldisp: boundary '" + w.name + "' is a " + it->second.kind +
                     " boundary, not a wall");
    }
  }
}

// The displacement at the point of a walldisp curve closest to p, linear along its segments,
// and the turn of that segment; returns the distance from p to the curve.
double interpolate_along(const WallDisplacement& w, const Vector& p, Vector& u, double& rotation) {
  double best = 1e300;
  if (w.x0.size() == 1) {
    u = w.displacement[0];
    rotation = 0.0;
    return (p - w.x0[0]).norm();
  }
  for (std::size_t s = 0; s + 1 < w.x0.size(); ++s) {
    double t = 0.0;
    const double d = geometry::distance_to_segment(p, w.x0[s], w.x0[s + 1], &t);
    if (d < best) {
      best = d;
      u = (1 - t) * w.displacement[s] + t * w.displacement[s + 1];
      // at a curve point, the turn a walldisp with node ids gives that point (the same file
      // with and without the ids deforms alike); between points, the segment's
      constexpr double kAtPoint = 1e-9;
      rotation = t <= kAtPoint       ? curve_rotation_at(w, s)
                 : t >= 1 - kAtPoint ? curve_rotation_at(w, s + 1)
                                     : chord_turn(w, s, s + 1);
    }
  }
  return best;
}

// Takes the displacement u and turn of the closest point of `curves` if it is closer than
// `best`, the distance to the closest curve so far.
void nearest_on_curves(const std::vector<const WallDisplacement*>& curves, const Vector& p,
                       Vector& u, double& rotation, double& best) {
  Vector candidate = Vector::Zero();
  double candidate_rotation = 0.0;
  for (const auto* w : curves) {
    const double d = interpolate_along(*w, p, candidate, candidate_rotation);
    if (d < best) {
      best = d;
      u = candidate;
      rotation = candidate_rotation;
    }
  }
}

// Length of a wall and, for a flap, of all its walls (an end face is short but lies within half a
// thickness of the flap's other walls): the scale of the projection tolerance.
double flap_wall_length(const Mesh& mesh, const std::string& name, const formats::Boundary& wall,
                        const std::vector<Vector>& x) {
  double total = 0.0;
  for (const auto& [other_name, other] : mesh.boundaries) {
    if (other_name != name && (wall.flap.empty() || other.flap != wall.flap))
      continue;
    for (Eigen::Index e = 0; e < other.edges.rows(); ++e) {
      total += (x[static_cast<std::size_t>(other.edges(e, 0))] -
                x[static_cast<std::size_t>(other.edges(e, 1))])
                   .norm();
    }
  }
  return total;
}

// The walldisp curves a mesh wall takes its displacement from: the one of its own name, and the
// other curves of its flap (for the nodes the first does not reach).
struct WallCurves {
  std::vector<const WallDisplacement*> same_name, same_flap;
};
WallCurves curves_of_wall(const std::string& name, const formats::Boundary& wall,
                          const std::vector<WallDisplacement>& walls) {
  WallCurves curves;
  for (const auto& w : walls) {
    if (!w.nodes.empty())
      continue;
    if (w.name == name)
      curves.same_name.push_back(&w);
    else if (!wall.flap.empty() && w.flap == wall.flap)
      curves.same_flap.push_back(&w);
  }
  return curves;
}

// Prescribes the nodes of one mesh wall from its curves: on its own curve, else on one of its
// flap's. Joins, lips and end faces are not on the walldisp curves; within a few per cent of the
// wall's length they take the nearest curve point's displacement (counted in the report).
void prescribe_wall(const std::string& name, const formats::Boundary& wall,
                    const WallCurves& curves, double wall_length, const NodePositions& nodes,
                    NodeMotions& motions, DeformReport& report) {
  std::set<std::int64_t> done;  // each node once per wall (it ends two of its edges)
  for (Eigen::Index e = 0; e < wall.edges.rows(); ++e) {
    for (int k = 0; k < 2; ++k) {
      const std::int64_t node = wall.edges(e, k);
      if (!done.insert(node).second)
        continue;
      const Vector& p = nodes.x[static_cast<std::size_t>(node)];
      Vector u = Vector::Zero();
      double rotation = 0.0;
      double best = 1e300;
      nearest_on_curves(curves.same_name, p, u, rotation, best);
      if (best > nodes.tight)
        nearest_on_curves(curves.same_flap, p, u, rotation, best);
      if (best > nodes.tight) {
        const double loose = 0.05 * std::max(wall_length, 1e-3 * nodes.extent);
        if (best > loose) {
          throw BadInput(
              "walldisp: node " + std::to_string(node) + " at " + geometry::format_point(p) +
              " of wall '" + name + "' is " + text::format_number(best) +
              " m from the walldisp curves of " +
              (curves.same_name.empty() ? "flap '" + wall.flap + "'" : "'" + name + "'") +
              ": the displacement was computed for another mesh or geometry");
        }
        ++report.projected_nodes;
        report.largest_projection = std::max(report.largest_projection, best);
      }
      motions.add(node, u, rotation);
    }
  }
}

// Flap wall boundaries of the mesh: interpolated along the walldisp curve of the same name, or
// projected onto the curves of the same flap.
void prescribe_walls(const Mesh& mesh, const std::vector<WallDisplacement>& walls,
                     const NodePositions& nodes, NodeMotions& motions, DeformReport& report) {
  report.projected_nodes = 0;
  report.largest_projection = 0.0;
  std::set<std::string> named_walls;  // their nodes came with the walldisp
  for (const auto& w : walls) {
    if (!w.nodes.empty())
      named_walls.insert(w.name);
  }
  for (const auto& [name, wall] : mesh.boundaries) {
    if (!is_wall(wall) || named_walls.count(name))
      continue;
    const WallCurves curves = curves_of_wall(name, wall, walls);
    if (curves.same_name.empty() && curves.same_flap.empty())
      continue;
    const double wall_length = flap_wall_length(mesh, name, wall, nodes.x);
    prescribe_wall(name, wall, curves, wall_length, nodes, motions, report);
  }
}

// Every other boundary node is held fixed; every boundary node gets its share of the boundary
// length.
void hold_other_boundaries(const Mesh& mesh, const std::vector<Vector>& x,
                           BoundarySources& sources) {
  for (const auto& [name, b] : mesh.boundaries) {
    for (Eigen::Index e = 0; e < b.edges.rows(); ++e) {
      const double len =
          (x[static_cast<std::size_t>(b.edges(e, 0))] - x[static_cast<std::size_t>(b.edges(e, 1))])
              .norm();
      for (int k = 0; k < 2; ++k) {
        sources.node_length[b.edges(e, k)] += 0.5 * len;
        sources.prescribed.try_emplace(b.edges(e, k), Vector::Zero());
        sources.rotation.try_emplace(b.edges(e, k), 0.0);
      }
    }
  }
}

// Displacement of every node: the prescribed one on the boundary, inside the weighted mean of
// Luke, Collins & Blades (2012) eq. 2-3 over all boundary nodes, w_s = A_s ((L/d)^3 + (alpha
// L/d)^5) with L the mesh extent and alpha = 0.1. With rotations, boundary node s moves the
// point x rigidly with its wall, u_s + (R(theta_s) - I)(x - x_s), instead of by
// u_s alone: a rigidly turning flap then turns the cells around it rigidly.
std::vector<Vector> interpolated_displacement(const NodePositions& nodes,
                                              const BoundarySources& sources, bool rotations) {
  const std::size_t n = nodes.x.size();
  const auto& x = nodes.x;
  std::vector<Vector> source_x, source_u;
  std::vector<double> source_cos_minus_1, source_sin;
  std::vector<double> source_area;
  for (const auto& [node, u] : sources.prescribed) {
    source_x.push_back(x[static_cast<std::size_t>(node)]);
    source_u.push_back(u);
    const auto turn = sources.rotation.find(node);
    const double theta = rotations && turn != sources.rotation.end() ? turn->second : 0.0;
    // cos - 1 as -2 sin^2(theta/2): no cancellation for small turns
    const double half_sin = std::sin(0.5 * theta);
    source_cos_minus_1.push_back(-2.0 * half_sin * half_sin);
    source_sin.push_back(std::sin(theta));
    const auto length = sources.node_length.find(node);  // a named node may be off the boundaries
    source_area.push_back(length == sources.node_length.end() ? 0.0 : length->second);
  }
  std::vector<Vector> displacement(n, Vector::Zero());
  std::vector<char> is_source(n, 0);
  for (const auto& [node, u] : sources.prescribed) {
    displacement[static_cast<std::size_t>(node)] = u;
    is_source[static_cast<std::size_t>(node)] = 1;
  }
  const double length_scale = nodes.extent;
  const double alpha = 0.1;
  const std::size_t ns = source_x.size();
#pragma omp parallel for schedule(dynamic, 256)
  for (std::size_t i = 0; i < n; ++i) {
    if (is_source[i])
      continue;
    Vector sum = Vector::Zero();
    double weight_sum = 0.0;
    for (std::size_t s = 0; s < ns; ++s) {
      const Vector offset = x[i] - source_x[s];
      const double d = std::max(offset.norm(), 1e-300);
      const double r = length_scale / d;
      const double r3 = r * r * r;
      const double ar = alpha * r;
      const double w = source_area[s] * (r3 + ar * ar * ar * ar * ar);
      const double c = source_cos_minus_1[s], sn = source_sin[s];
      const Vector turned(c * offset.x() - sn * offset.y(), sn * offset.x() + c * offset.y());
      sum += w * (source_u[s] + turned);
      weight_sum += w;
    }
    displacement[i] = sum / weight_sum;
  }
  return displacement;
}

// The mesh points moved by a fraction of the displacement.
h5::MatrixXdR moved_points(const Mesh& mesh, const std::vector<Vector>& displacement,
                           double fraction) {
  h5::MatrixXdR p = mesh.points;
  for (std::size_t i = 0; i < displacement.size(); ++i) {
    p(static_cast<Eigen::Index>(i), 0) += fraction * displacement[i].x();
    p(static_cast<Eigen::Index>(i), 1) += fraction * displacement[i].y();
  }
  return p;
}

// Largest fraction of the displacement that keeps every cell valid, by bisection (the moved
// positions are linear in the fraction).
double admissible_fraction(const Mesh& mesh, const std::vector<Vector>& displacement) {
  double lo = 0.0, hi = 1.0;
  for (int it = 0; it < 40; ++it) {
    const double mid = 0.5 * (lo + hi);
    (all_valid(mesh, moved_points(mesh, displacement, mid), nullptr) ? lo : hi) = mid;
  }
  return lo;
}

// The BadInput for a displacement that inverts cells: how many, where the first one is, and how
// much of the displacement the mesh takes.
BadInput inverted_cells_error(const Mesh& mesh, const Mesh& moved, const std::vector<Vector>& x,
                              std::int64_t first_bad, double fraction) {
  const Quality q = mesh_quality(moved);
  std::vector<std::int64_t> cell_nodes;
  if (first_bad < mesh.triangles.rows()) {
    for (int k = 0; k < 3; ++k)
      cell_nodes.push_back(mesh.triangles(first_bad, k));
  } else {
    for (int k = 0; k < 4; ++k)
      cell_nodes.push_back(mesh.quads(first_bad - mesh.triangles.rows(), k));
  }
  Vector where = Vector::Zero();
  for (auto node : cell_nodes)
    where += x[static_cast<std::size_t>(node)] / static_cast<double>(cell_nodes.size());
  return BadInput("deform: the displacement would invert " + std::to_string(q.invalid_cells) +
                  " cells (first: cell " + std::to_string(first_bad) + " near " +
                  geometry::format_point(where) +
                  "); the largest admissible fraction "
                  "of this displacement is " +
                  text::format_number(fraction) + " (apply it in smaller steps or remesh)");
}

}  // namespace

// The phases: the boundary nodes' displacements (named nodes, then the walls by curve, then the
// other boundaries fixed), the interpolation inside, and the validity check of the moved mesh.
Mesh deform_mesh(const Mesh& mesh, const std::vector<WallDisplacement>& walls,
                 const DeformOptions& options, DeformReport& report) {
  const NodePositions nodes = node_positions(mesh);
  BoundarySources sources;
  // a node gets the mean of what every wall it is on gives, by node id or along a curve
  NodeMotions motions;
  prescribe_named_nodes(walls, nodes, motions);
  check_wall_names(mesh, walls);
  prescribe_walls(mesh, walls, nodes, motions, report);
  motions.put_into(sources);
  hold_other_boundaries(mesh, nodes.x, sources);
  report.moved_wall_nodes = 0;
  for (const auto& [node, u] : sources.prescribed)
    report.moved_wall_nodes += u.squaredNorm() > 0.0;

  const std::vector<Vector> displacement =
      interpolated_displacement(nodes, sources, options.rotations);
  Mesh out = mesh;
  out.points = moved_points(mesh, displacement, 1.0);
  std::int64_t bad = -1;
  if (!all_valid(mesh, out.points, &bad)) {
    report.admissible_fraction = admissible_fraction(mesh, displacement);
    throw inverted_cells_error(mesh, out, nodes.x, bad, report.admissible_fraction);
  }
  report.admissible_fraction = 1.0;
  report.quality = mesh_quality(out);
  return out;
}

}  // namespace tfmb::mesh
