#include "tfmb-heat/boundary_geometry.hpp"

#include "tfmb-heat/quadrature.hpp"
#include "tfmb-heat/shape_functions.hpp"

#include <cmath>
#include <stdexcept>

namespace tfmb::heat {
namespace {

// Length of the edge between reference coordinates xi_a and xi_b (Gauss, 5 points).
double edge_length(const SolidMesh& mesh, std::span<const std::int64_t> edge, double xi_a,
                   double xi_b) {
  static const QuadratureRule1D rule = gauss_legendre(5);
  const int npe = static_cast<int>(edge.size());
  double n[3], dn[3], length = 0.0;
  for (std::size_t q = 0; q < rule.points.size(); ++q) {
    const double xi = 0.5 * (xi_a + xi_b) + 0.5 * (xi_b - xi_a) * rule.points[q];
    edge_shape_functions(npe, xi, n, dn);
    double dx = 0.0, dy = 0.0;
    for (int a = 0; a < npe; ++a) {
      dx += dn[a] * mesh.points(edge[a], 0);
      dy += dn[a] * mesh.points(edge[a], 1);
    }
    length += rule.weights[q] * 0.5 * (xi_b - xi_a) * std::hypot(dx, dy);
  }
  return length;
}

}  // namespace

std::vector<double> boundary_arc_length(const SolidMesh& mesh, const BoundaryCurve& curve) {
  const std::size_t npe = static_cast<std::size_t>(curve.nodes_per_edge);
  std::vector<double> s(curve.nodes.size(), 0.0);
  double s_now = 0.0;
  std::int64_t chain_end = -1;
  for (std::size_t e = 0; e < curve.size(); ++e) {
    const auto edge = curve.edge(e);
    bool reversed = false;
    if (e == 0) {
      // The first edge is reversed when its first node continues into the second edge.
      if (curve.size() > 1) {
        const auto next = curve.edge(1);
        reversed = (edge[0] == next[0] || edge[0] == next[1]) && edge[1] != next[0] &&
                   edge[1] != next[1];
      }
    } else if (edge[0] == chain_end) {
      reversed = false;
    } else if (edge[1] == chain_end) {
      reversed = true;
    } else {
      throw std::invalid_argument("boundary edge " + std::to_string(e) +
                                  " does not continue the previous edge (the wall must be one "
                                  "connected chain of edges for arc-length traces)");
    }
    const double length = edge_length(mesh, edge, -1.0, 1.0);
    const std::size_t first = reversed ? 1 : 0, last = reversed ? 0 : 1;
    s[e * npe + first] = s_now;
    s[e * npe + last] = s_now + length;
    if (npe == 3) {
      const double half = reversed ? edge_length(mesh, edge, 0.0, 1.0)
                                   : edge_length(mesh, edge, -1.0, 0.0);
      s[e * npe + 2] = s_now + half;
    }
    s_now += length;
    chain_end = edge[last];
  }
  return s;
}

double boundary_length(const SolidMesh& mesh, const BoundaryCurve& curve) {
  double length = 0.0;
  for (std::size_t e = 0; e < curve.size(); ++e) length += edge_length(mesh, curve.edge(e), -1, 1);
  return length;
}

}  // namespace tfmb::heat
