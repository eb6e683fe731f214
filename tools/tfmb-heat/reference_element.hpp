#pragma once
// Shape functions tabulated at the points of a quadrature rule, computed once per element type
// so that element loops only map and accumulate.
#include "tfmb-heat/mesh.hpp"
#include "tfmb-heat/quadrature.hpp"

#include <vector>

namespace tfmb::heat {

struct ReferenceElement {
  ElementType type = ElementType::tri3;
  int node_count = 0;
  QuadratureRule2D rule;
  std::vector<double> n;       // [point][node]
  std::vector<double> dn_dxi;  // [point][node]
  std::vector<double> dn_deta; // [point][node]

  std::size_t point_count() const { return rule.weights.size(); }
};

ReferenceElement make_reference_element(ElementType type, const QuadratureRule2D& rule);

}  // namespace tfmb::heat
