// Mesh deformation for two-way coupling: wall nodes take the wall displacement exactly (linear
// interpolation along the walldisp curve), every other node the inverse-distance-weighted
// displacement of all boundary nodes (Luke, Collins & Blades, J. Comput. Phys. 231 (2012)
// 5859, eq. 2-3: w_i = A_i ((L/d_i)^a + (alpha L/d_i)^b), a = 3, b = 5, alpha = 0.1); other
// boundaries are held fixed. Same topology, so the flow solver can restart.
#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <limits>
#include <sstream>

#include "mesh_tools.hpp"
#include "tfmb/common/errors.hpp"
#include "tfmb/common/polyline.hpp"
#include "tfmb/common/text.hpp"
#include "tfmb/formats/schema.hpp"

namespace tfmb::mesh {
namespace {

bool all_valid(const Mesh& mesh, const h5::MatrixXdR& points, std::int64_t* first_bad) {
  const auto cells = static_cast<std::int64_t>(mesh.cell_count());
  for (std::int64_t c = 0; c < cells; ++c) {
    if (cell_min_corner_area(points, mesh, c) <= 0.0) {
      if (first_bad) *first_bad = c;
      return false;
    }
  }
  return true;
}

}  // namespace

std::vector<WallDisplacement> read_walldisp(const std::filesystem::path& file) {
  const h5::Reader r = formats::open_checked(file, "walldisp");
  std::vector<WallDisplacement> walls;
  for (const auto& name : r.children("/walls")) {
    WallDisplacement w;
    w.boundary = name;
    if (r.has_attr("/walls/" + name, "flap")) w.flap = r.attr_string("/walls/" + name, "flap");
    const auto x0 = r.read_matrix("/walls/" + name + "/x0", {}, 2);
    const auto u = r.read_matrix("/walls/" + name + "/displacement", x0.rows(), 2);
    if (x0.rows() < 1) r.fail("/walls/" + name + "/x0", "no points");
    for (Eigen::Index i = 0; i < x0.rows(); ++i) {
      w.x0.emplace_back(x0(i, 0), x0(i, 1));
      w.displacement.emplace_back(u(i, 0), u(i, 1));
    }
    if (r.exists("/walls/" + name + "/node")) {
      w.nodes = r.read_index_vector("/walls/" + name + "/node", static_cast<std::size_t>(x0.rows()), 0,
                                    std::numeric_limits<std::int64_t>::max());
    }
    walls.push_back(std::move(w));
  }
  return walls;
}

Mesh deform_mesh(const Mesh& mesh, const std::vector<WallDisplacement>& walls, DeformReport& report) {
  const auto n = static_cast<std::size_t>(mesh.points.rows());
  std::vector<Eigen::Vector2d> x(n);
  for (std::size_t i = 0; i < n; ++i) x[i] = mesh.points.row(static_cast<Eigen::Index>(i)).transpose();
  double extent = 0.0;
  {
    Eigen::Vector2d lo = x[0], hi = x[0];
    for (const auto& p : x) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
    extent = (hi - lo).norm();
  }
  // Prescribed displacements: walls from walldisp, every other boundary node fixed.
  std::map<std::int64_t, Eigen::Vector2d> prescribed;
  std::map<std::int64_t, double> node_length;  // boundary length associated with each node
  const double tight = 1e-9 * extent + 1e-12;
  // 1. Points that name their mesh node.
  for (const auto& w : walls) {
    if (w.nodes.empty()) continue;
    for (std::size_t k = 0; k < w.nodes.size(); ++k) {
      const auto node = w.nodes[k];
      if (node >= static_cast<std::int64_t>(n)) {
        throw BadInput("walldisp: /walls/" + w.boundary + "/node: node " + std::to_string(node) +
                       " is not in the flow mesh (" + std::to_string(n) + " nodes)");
      }
      const double d = (x[static_cast<std::size_t>(node)] - w.x0[k]).norm();
      if (d > tight + 1e-6 * extent) {
        throw BadInput("walldisp: /walls/" + w.boundary + "/x0 row " + std::to_string(k) + " is " +
                       text::format_number(d) + " m from flow-mesh node " + std::to_string(node) +
                       ": computed for another mesh");
      }
      prescribed[node] = w.displacement[k];
    }
  }
  // 2. Flap wall boundaries of the mesh: interpolate along the walldisp curve of the same name,
  //    or project onto the curves of the same flap.
  auto interpolate = [](const WallDisplacement& w, const Eigen::Vector2d& p, Eigen::Vector2d& u) {
    double best = 1e300;
    if (w.x0.size() == 1) {
      u = w.displacement[0];
      return (p - w.x0[0]).norm();
    }
    for (std::size_t s = 0; s + 1 < w.x0.size(); ++s) {
      double t = 0.0;
      const double d = geometry::distance_to_segment(p, w.x0[s], w.x0[s + 1], &t);
      if (d < best) {
        best = d;
        u = (1 - t) * w.displacement[s] + t * w.displacement[s + 1];
      }
    }
    return best;
  };
  for (const auto& w : walls) {
    auto it = mesh.boundaries.find(w.boundary);
    if (it == mesh.boundaries.end() && (w.flap.empty() || w.nodes.size())) {
      throw BadInput("walldisp: boundary '" + w.boundary + "' is not in the flow mesh");
    }
    if (it != mesh.boundaries.end() && it->second.kind != "wall" && it->second.kind != "slip_wall") {
      throw BadInput("walldisp: boundary '" + w.boundary + "' is a " + it->second.kind + " boundary, not a wall");
    }
  }
  report.projected_nodes = 0;
  report.largest_projection = 0.0;
  for (const auto& [name, b] : mesh.boundaries) {
    if (b.kind != "wall" && b.kind != "slip_wall") continue;
    std::vector<const WallDisplacement*> same_name, same_flap;
    for (const auto& w : walls) {
      if (!w.nodes.empty()) continue;
      if (w.boundary == name) same_name.push_back(&w);
      else if (!b.flap.empty() && w.flap == b.flap) same_flap.push_back(&w);
    }
    if (same_name.empty() && same_flap.empty()) continue;
    // Length of this wall and, for a flap, of all its walls (an end face is short but lies
    // within half a thickness of the flap's other walls).
    double boundary_length = 0.0;
    for (const auto& [other_name, other] : mesh.boundaries) {
      if (other_name != name && (b.flap.empty() || other.flap != b.flap)) continue;
      for (Eigen::Index e = 0; e < other.edges.rows(); ++e) {
        boundary_length += (x[static_cast<std::size_t>(other.edges(e, 0))] - x[static_cast<std::size_t>(other.edges(e, 1))]).norm();
      }
    }
    for (Eigen::Index e = 0; e < b.edges.rows(); ++e) {
      for (int k = 0; k < 2; ++k) {
        const std::int64_t node = b.edges(e, k);
        if (prescribed.count(node)) continue;
        const Eigen::Vector2d& p = x[static_cast<std::size_t>(node)];
        Eigen::Vector2d u = Eigen::Vector2d::Zero();
        Eigen::Vector2d candidate = Eigen::Vector2d::Zero();
        double best = 1e300;
        for (const auto* w : same_name) {
          const double d = interpolate(*w, p, candidate);
          if (d < best) {
            best = d;
            u = candidate;
          }
        }
        if (best > tight) {
          for (const auto* w : same_flap) {
            const double d = interpolate(*w, p, candidate);
            if (d < best) {
              best = d;
              u = candidate;
            }
          }
        }
        if (best > tight) {
          // Joins, lips and end faces are not on the walldisp curves; within a few per cent of
          // the wall's length they take the nearest curve point's displacement.
          const double loose = 0.05 * std::max(boundary_length, 1e-3 * extent);
          if (best > loose) {
            throw BadInput("walldisp: node " + std::to_string(node) + " at " +
                           geometry::format_point(p) + " of wall '" + name + "' is " +
                           text::format_number(best) + " m from the walldisp curves of " +
                           (same_name.empty() ? "flap '" + b.flap + "'" : "'" + name + "'") +
                           ": the displacement was computed for another mesh or geometry");
          }
          ++report.projected_nodes;
          report.largest_projection = std::max(report.largest_projection, best);
        }
        prescribed[node] = u;
      }
    }
  }
  for (const auto& [name, b] : mesh.boundaries) {
    for (Eigen::Index e = 0; e < b.edges.rows(); ++e) {
      const double len = (x[static_cast<std::size_t>(b.edges(e, 0))] - x[static_cast<std::size_t>(b.edges(e, 1))]).norm();
      for (int k = 0; k < 2; ++k) {
        node_length[b.edges(e, k)] += 0.5 * len;
        prescribed.try_emplace(b.edges(e, k), Eigen::Vector2d::Zero());
      }
    }
  }
  std::vector<Eigen::Vector2d> source_x, source_u;
  std::vector<double> source_area;
  for (const auto& [node, u] : prescribed) {
    source_x.push_back(x[static_cast<std::size_t>(node)]);
    source_u.push_back(u);
    source_area.push_back(node_length[node]);
  }
  std::vector<Eigen::Vector2d> displacement(n, Eigen::Vector2d::Zero());
  std::vector<char> is_source(n, 0);
  for (const auto& [node, u] : prescribed) {
    displacement[static_cast<std::size_t>(node)] = u;
    is_source[static_cast<std::size_t>(node)] = 1;
  }
  report.moved_wall_nodes = 0;
  for (const auto& [node, u] : prescribed) report.moved_wall_nodes += u.squaredNorm() > 0.0;
  const double length_scale = extent;
  const double alpha = 0.1;
  const std::size_t ns = source_x.size();
#pragma omp parallel for schedule(dynamic, 256)
  for (std::size_t i = 0; i < n; ++i) {
    if (is_source[i]) continue;
    Eigen::Vector2d sum = Eigen::Vector2d::Zero();
    double weight_sum = 0.0;
    for (std::size_t s = 0; s < ns; ++s) {
      const double d = std::max((x[i] - source_x[s]).norm(), 1e-300);
      const double r = length_scale / d;
      const double r3 = r * r * r;
      const double ar = alpha * r;
      const double w = source_area[s] * (r3 + ar * ar * ar * ar * ar);
      sum += w * source_u[s];
      weight_sum += w;
    }
    displacement[i] = sum / weight_sum;
  }
  auto moved = [&](double fraction) {
    h5::MatrixXdR p = mesh.points;
    for (std::size_t i = 0; i < n; ++i) {
      p(static_cast<Eigen::Index>(i), 0) += fraction * displacement[i].x();
      p(static_cast<Eigen::Index>(i), 1) += fraction * displacement[i].y();
    }
    return p;
  };
  Mesh out = mesh;
  out.points = moved(1.0);
  std::int64_t bad = -1;
  if (!all_valid(mesh, out.points, &bad)) {
    // Bisection on the fraction of the displacement that keeps every cell valid (the moved
    // positions are linear in the fraction).
    double lo = 0.0, hi = 1.0;
    for (int it = 0; it < 40; ++it) {
      const double mid = 0.5 * (lo + hi);
      (all_valid(mesh, moved(mid), nullptr) ? lo : hi) = mid;
    }
    report.admissible_fraction = lo;
    const Quality q = mesh_quality(out);
    const auto c = bad;
    Eigen::Vector2d where = Eigen::Vector2d::Zero();
    const auto nodes_of = [&](std::int64_t cell) {
      std::vector<std::int64_t> v;
      if (cell < mesh.triangles.rows()) for (int k = 0; k < 3; ++k) v.push_back(mesh.triangles(cell, k));
      else for (int k = 0; k < 4; ++k) v.push_back(mesh.quads(cell - mesh.triangles.rows(), k));
      return v;
    };
    const auto nodes = nodes_of(c);
    for (auto node : nodes) where += x[static_cast<std::size_t>(node)] / static_cast<double>(nodes.size());
    throw BadInput("deform: the displacement would invert " + std::to_string(q.invalid_cells) +
                   " cells (first: cell " + std::to_string(c) + " near " +
                   geometry::format_point(where) +
                   "); the largest admissible fraction "
                   "of this displacement is " +
                   text::format_number(lo) + " (apply it in smaller steps or remesh)");
  }
  report.admissible_fraction = 1.0;
  report.quality = mesh_quality(out);
  return out;
}

}  // namespace tfmb::mesh
