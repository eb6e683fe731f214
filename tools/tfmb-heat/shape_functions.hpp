#pragma once
// Lagrange / serendipity shape functions on the reference elements.
//   triangles: xi, eta >= 0, xi + eta <= 1 (node 0 at the origin)
//   quads:     [-1, 1]^2 (node 0 at (-1, -1))
// Zienkiewicz, Taylor & Zhu (2013) The Finite Element Method, 7th ed., ch. 6.
#include "tfmb-heat/mesh.hpp"

#include <array>
#include <vector>

namespace tfmb::heat {

/// N, dN/dxi, dN/deta at (xi, eta); each array holds nodes_per_element(type) values.
void shape_functions(ElementType type, double xi, double eta, double* n, double* dn_dxi,
                     double* dn_deta);

/// Reference coordinates of the element's nodes, in node order.
std::vector<std::array<double, 2>> reference_node_coordinates(ElementType type);

/// Edge shape functions on xi in [-1, 1]: 2 nodes (linear) or 3 (quadratic: ends, then mid).
void edge_shape_functions(int nodes_per_edge, double xi, double* n, double* dn_dxi);

}  // namespace tfmb::heat
