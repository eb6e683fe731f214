#include "tfmb-heat/shape_functions.hpp"

#include <stdexcept>

namespace tfmb::heat {
namespace {

// 1D quadratic Lagrange polynomials on nodes -1, 0, 1 and their derivatives.
double lagrange2(int node, double x) {
  switch (node) {
    case -1: return 0.5 * x * (x - 1.0);
    case 0: return 1.0 - x * x;
    default: return 0.5 * x * (x + 1.0);
  }
}
double lagrange2_derivative(int node, double x) {
  switch (node) {
    case -1: return x - 0.5;
    case 0: return -2.0 * x;
    default: return x + 0.5;
  }
}

constexpr int kQuadCornerXi[4] = {-1, 1, 1, -1};
constexpr int kQuadCornerEta[4] = {-1, -1, 1, 1};
// quad8 / quad9 mid-edge nodes 4..7 and centre 8.
constexpr int kQuadXi[9] = {-1, 1, 1, -1, 0, 1, 0, -1, 0};
constexpr int kQuadEta[9] = {-1, -1, 1, 1, -1, 0, 1, 0, 0};

}  // namespace

void shape_functions(ElementType type, double xi, double eta, double* n, double* dn_dxi,
                     double* dn_deta) {
  switch (type) {
    case ElementType::tri3:
      n[0] = 1.0 - xi - eta;
      n[1] = xi;
      n[2] = eta;
      dn_dxi[0] = -1.0, dn_dxi[1] = 1.0, dn_dxi[2] = 0.0;
      dn_deta[0] = -1.0, dn_deta[1] = 0.0, dn_deta[2] = 1.0;
      return;
    case ElementType::tri6: {
      // Area coordinates L0 = 1 - xi - eta, L1 = xi, L2 = eta; ZTZ (2013) eq. 6.33.
      const double l0 = 1.0 - xi - eta, l1 = xi, l2 = eta;
      n[0] = l0 * (2.0 * l0 - 1.0);
      n[1] = l1 * (2.0 * l1 - 1.0);
      n[2] = l2 * (2.0 * l2 - 1.0);
      n[3] = 4.0 * l0 * l1;
      n[4] = 4.0 * l1 * l2;
      n[5] = 4.0 * l2 * l0;
      dn_dxi[0] = -(4.0 * l0 - 1.0);
      dn_deta[0] = -(4.0 * l0 - 1.0);
      dn_dxi[1] = 4.0 * l1 - 1.0;
      dn_deta[1] = 0.0;
      dn_dxi[2] = 0.0;
      dn_deta[2] = 4.0 * l2 - 1.0;
      dn_dxi[3] = 4.0 * (l0 - l1);
      dn_deta[3] = -4.0 * l1;
      dn_dxi[4] = 4.0 * l2;
      dn_deta[4] = 4.0 * l1;
      dn_dxi[5] = -4.0 * l2;
      dn_deta[5] = 4.0 * (l0 - l2);
      return;
    }
    case ElementType::quad4:
      for (int a = 0; a < 4; ++a) {
        const double xa = kQuadCornerXi[a], ya = kQuadCornerEta[a];
        n[a] = 0.25 * (1.0 + xi * xa) * (1.0 + eta * ya);
        dn_dxi[a] = 0.25 * xa * (1.0 + eta * ya);
        dn_deta[a] = 0.25 * ya * (1.0 + xi * xa);
      }
      return;
    case ElementType::quad8:
      // Serendipity element, ZTZ (2013) eq. 6.14.
      for (int a = 0; a < 8; ++a) {
        const double xa = kQuadXi[a], ya = kQuadEta[a];
        if (a < 4) {
          n[a] = 0.25 * (1.0 + xi * xa) * (1.0 + eta * ya) * (xi * xa + eta * ya - 1.0);
          dn_dxi[a] = 0.25 * xa * (1.0 + eta * ya) * (2.0 * xi * xa + eta * ya);
          dn_deta[a] = 0.25 * ya * (1.0 + xi * xa) * (xi * xa + 2.0 * eta * ya);
        } else if (xa == 0.0) {
          n[a] = 0.5 * (1.0 - xi * xi) * (1.0 + eta * ya);
          dn_dxi[a] = -xi * (1.0 + eta * ya);
          dn_deta[a] = 0.5 * ya * (1.0 - xi * xi);
        } else {
          n[a] = 0.5 * (1.0 + xi * xa) * (1.0 - eta * eta);
          dn_dxi[a] = 0.5 * xa * (1.0 - eta * eta);
          dn_deta[a] = -eta * (1.0 + xi * xa);
        }
      }
      return;
    case ElementType::quad9:
      // Tensor product of 1D quadratic Lagrange polynomials, ZTZ (2013) sec. 6.4.
      for (int a = 0; a < 9; ++a) {
        const int xa = kQuadXi[a], ya = kQuadEta[a];
        n[a] = lagrange2(xa, xi) * lagrange2(ya, eta);
        dn_dxi[a] = lagrange2_derivative(xa, xi) * lagrange2(ya, eta);
        dn_deta[a] = lagrange2(xa, xi) * lagrange2_derivative(ya, eta);
      }
      return;
  }
  throw std::logic_error("shape_functions: unknown element type");
}

std::vector<std::array<double, 2>> reference_node_coordinates(ElementType type) {
  switch (type) {
    case ElementType::tri3: return {{0, 0}, {1, 0}, {0, 1}};
    case ElementType::tri6:
      return {{0, 0}, {1, 0}, {0, 1}, {0.5, 0}, {0.5, 0.5}, {0, 0.5}};
    case ElementType::quad4:
    case ElementType::quad8:
    case ElementType::quad9: {
      std::vector<std::array<double, 2>> nodes;
      for (int a = 0; a < nodes_per_element(type); ++a) {
        nodes.push_back({static_cast<double>(kQuadXi[a]), static_cast<double>(kQuadEta[a])});
      }
      return nodes;
    }
  }
  throw std::logic_error("reference_node_coordinates: unknown element type");
}

void edge_shape_functions(int nodes_per_edge, double xi, double* n, double* dn_dxi) {
  if (nodes_per_edge == 2) {
    n[0] = 0.5 * (1.0 - xi);
    n[1] = 0.5 * (1.0 + xi);
    dn_dxi[0] = -0.5;
    dn_dxi[1] = 0.5;
  } else {
    n[0] = lagrange2(-1, xi);
    n[1] = lagrange2(1, xi);
    n[2] = lagrange2(0, xi);
    dn_dxi[0] = lagrange2_derivative(-1, xi);
    dn_dxi[1] = lagrange2_derivative(1, xi);
    dn_dxi[2] = lagrange2_derivative(0, xi);
  }
}

}  // namespace tfmb::heat
