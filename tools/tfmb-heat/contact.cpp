#include "tfmb-heat/contact.hpp"

#include "tfmb-heat/quadrature.hpp"
#include "tfmb-heat/shape_functions.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace tfmb::heat {
namespace {

double shortest_edge(const SolidMesh& mesh, const BoundaryCurve& curve) {
  double shortest = std::numeric_limits<double>::infinity();
  for (std::size_t e = 0; e < curve.size(); ++e) {
    const auto edge = curve.edge(e);
    shortest = std::min(shortest, (mesh.points.row(edge[0]) - mesh.points.row(edge[1])).norm());
  }
  return shortest;
}

}  // namespace

std::vector<std::pair<std::int64_t, std::int64_t>> perfect_contact_pairs(
    const SolidMesh& mesh, const BoundaryCurve& a, const BoundaryCurve& b,
    const std::string& description) {
  const double tolerance = 1e-6 * std::min(shortest_edge(mesh, a), shortest_edge(mesh, b));
  std::vector<std::int64_t> a_nodes(a.nodes), b_nodes(b.nodes);
  std::sort(a_nodes.begin(), a_nodes.end());
  a_nodes.erase(std::unique(a_nodes.begin(), a_nodes.end()), a_nodes.end());
  std::sort(b_nodes.begin(), b_nodes.end());
  b_nodes.erase(std::unique(b_nodes.begin(), b_nodes.end()), b_nodes.end());
  std::vector<std::pair<std::int64_t, std::int64_t>> pairs;
  for (auto na : a_nodes) {
    std::int64_t match = -1;
    for (auto nb : b_nodes) {
      if ((mesh.points.row(na) - mesh.points.row(nb)).norm() <= tolerance) {
        match = nb;
        break;
      }
    }
    if (match < 0) {
      throw std::invalid_argument(description + ": node " + std::to_string(na) + " at (" +
                                  std::to_string(mesh.points(na, 0)) + ", " +
                                  std::to_string(mesh.points(na, 1)) +
                                  ") has no coincident node on the other side; perfect contact "
                                  "needs matching meshes (give a gap conductance otherwise)");
    }
    if (match != na) pairs.emplace_back(na, match);
  }
  return pairs;
}

std::vector<GapPoint> gap_contact_points(const SolidMesh& mesh, const BoundaryCurve& a,
                                         const BoundaryCurve& b, double conductance,
                                         int contact_index) {
  const int npa = a.nodes_per_edge, npb = b.nodes_per_edge;
  const auto rule = gauss_legendre(npa == 2 ? 3 : 5);
  std::vector<GapPoint> points;
  double n[3], dn[3];
  for (std::size_t e = 0; e < a.size(); ++e) {
    const auto edge = a.edge(e);
    // Segment-based integration: the edge is split where the end nodes of side b project onto
    // it, so each segment sees one edge of b and the quadrature stays exact for matching
    // polynomial degrees (Puso & Laursen (2004) CMAME 193, 601, segment-to-segment mortar).
    const Eigen::Vector2d a0 = mesh.points.row(edge[0]).transpose();
    const Eigen::Vector2d a1 = mesh.points.row(edge[1]).transpose();
    const Eigen::Vector2d chord_a = a1 - a0;
    std::vector<double> breaks{0.0, 1.0};
    for (auto node : b.nodes) {
      const double t = (mesh.points.row(node).transpose() - a0).dot(chord_a) / chord_a.squaredNorm();
      if (t > 1e-12 && t < 1.0 - 1e-12) breaks.push_back(t);
    }
    std::sort(breaks.begin(), breaks.end());
    breaks.erase(std::unique(breaks.begin(), breaks.end(),
                             [](double x, double y) { return std::abs(x - y) < 1e-12; }),
                 breaks.end());
    for (std::size_t segment = 0; segment + 1 < breaks.size(); ++segment) {
      const double xi0 = 2.0 * breaks[segment] - 1.0, xi1 = 2.0 * breaks[segment + 1] - 1.0;
      for (std::size_t q = 0; q < rule.points.size(); ++q) {
        const double xi = 0.5 * (xi0 + xi1) + 0.5 * (xi1 - xi0) * rule.points[q];
        edge_shape_functions(npa, xi, n, dn);
        GapPoint p;
        p.a_count = npa;
        p.conductance = conductance;
        p.contact = contact_index;
        Eigen::Vector2d x = Eigen::Vector2d::Zero(), dx = Eigen::Vector2d::Zero();
        for (int k = 0; k < npa; ++k) {
          const auto node = edge[k];
          p.a_nodes[k] = node;
          p.a_n[k] = n[k];
          x += n[k] * mesh.points.row(node).transpose();
          dx += dn[k] * mesh.points.row(node).transpose();
        }
        p.weight = rule.weights[q] * 0.5 * (xi1 - xi0) * dx.norm();
        // Closest point of side b, by projection onto each edge's chord.
        double best = std::numeric_limits<double>::infinity(), best_xi = 0.0;
        std::size_t best_edge = 0;
        for (std::size_t f = 0; f < b.size(); ++f) {
          const auto other = b.edge(f);
          const Eigen::Vector2d p0 = mesh.points.row(other[0]).transpose();
          const Eigen::Vector2d p1 = mesh.points.row(other[1]).transpose();
          const Eigen::Vector2d chord = p1 - p0;
          const double t = std::clamp((x - p0).dot(chord) / chord.squaredNorm(), 0.0, 1.0);
          const double distance = (p0 + t * chord - x).norm();
          if (distance < best) best = distance, best_xi = 2.0 * t - 1.0, best_edge = f;
        }
        edge_shape_functions(npb, best_xi, n, dn);
        const auto other = b.edge(best_edge);
        p.b_count = npb;
        for (int k = 0; k < npb; ++k) {
          p.b_nodes[k] = other[k];
          p.b_n[k] = n[k];
        }
        points.push_back(p);
      }
    }
  }
  return points;
}

}  // namespace tfmb::heat
