#include "tfmb-heat/reference_element.hpp"

#include "tfmb-heat/shape_functions.hpp"

namespace tfmb::heat {

ReferenceElement make_reference_element(ElementType type, const QuadratureRule2D& rule) {
  ReferenceElement ref;
  ref.type = type;
  ref.node_count = nodes_per_element(type);
  ref.rule = rule;
  const auto npe = static_cast<std::size_t>(ref.node_count);
  ref.n.resize(rule.weights.size() * npe);
  ref.dn_dxi.resize(ref.n.size());
  ref.dn_deta.resize(ref.n.size());
  for (std::size_t q = 0; q < rule.weights.size(); ++q) {
    shape_functions(type, rule.points[q][0], rule.points[q][1], &ref.n[q * npe],
                    &ref.dn_dxi[q * npe], &ref.dn_deta[q * npe]);
  }
  return ref;
}

}  // namespace tfmb::heat
