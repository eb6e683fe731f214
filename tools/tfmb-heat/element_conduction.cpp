#include "tfmb-heat/element_conduction.hpp"

#include <stdexcept>

namespace tfmb::heat {

namespace {
// Jacobian determinant and physical shape-function gradients (2 x n) at quadrature point q.
double map_point(const ReferenceElement& ref, std::size_t q, const ElementCoordinates& xy,
                 Eigen::Matrix<double, 2, Eigen::Dynamic, 0, 2, 9>& gradient) {
  const auto n = static_cast<Eigen::Index>(ref.node_count);
  const std::size_t offset = q * static_cast<std::size_t>(ref.node_count);
  Eigen::Matrix<double, 2, Eigen::Dynamic, 0, 2, 9> dref(2, n);
  for (Eigen::Index a = 0; a < n; ++a) {
    dref(0, a) = ref.dn_dxi[offset + static_cast<std::size_t>(a)];
    dref(1, a) = ref.dn_deta[offset + static_cast<std::size_t>(a)];
  }
  const Eigen::Matrix2d jacobian = dref * xy;  // [dx/dxi dy/dxi; dx/deta dy/deta]
  const double det = jacobian.determinant();
  if (!(det > 0.0)) throw std::invalid_argument("element with non-positive Jacobian");
  gradient = jacobian.inverse() * dref;
  return det;
}
}  // namespace

void add_conduction_element(const ReferenceElement& ref, const ElementCoordinates& xy,
                            const ElementVector& temperature, const Material& material,
                            const ElementTimeTerm& time_term,
                            const std::function<double(double, double)>& source, Tangent kind,
                            ElementVector& residual, ElementMatrix* tangent) {
  const auto n = static_cast<Eigen::Index>(ref.node_count);
  Eigen::Matrix<double, 2, Eigen::Dynamic, 0, 2, 9> gradient(2, n);
  const bool consistent = kind == Tangent::consistent;
  for (std::size_t q = 0; q < ref.point_count(); ++q) {
    const double weight = ref.rule.weights[q] * map_point(ref, q, xy, gradient);
    const Eigen::Map<const Eigen::VectorXd> shape(&ref.n[q * static_cast<std::size_t>(n)], n);
    const double t = shape.dot(temperature);
    const Eigen::Vector2d grad_t = gradient * temperature;
    const double k = material.conductivity.value(t);
    residual.noalias() += (weight * k) * (gradient.transpose() * grad_t);
    if (tangent) {
      tangent->noalias() += (weight * k) * (gradient.transpose() * gradient);
      if (consistent) {
        const double dk = material.conductivity.slope(t);
        if (dk != 0.0) tangent->noalias() += (weight * dk) * (gradient.transpose() * grad_t) * shape.transpose();
      }
    }
    if (time_term.rate_factor > 0.0) {
      const double rho = material.density.value(t), cp = material.specific_heat.value(t);
      const double capacity = rho * cp;
      const double rate = time_term.rate_factor * t + shape.dot(*time_term.history);
      residual.noalias() += (weight * capacity * rate) * shape;
      if (tangent) {
        double factor = capacity * time_term.rate_factor;
        if (consistent) {
          const double dcapacity = material.density.slope(t) * cp + rho * material.specific_heat.slope(t);
          factor += dcapacity * rate;
        }
        tangent->noalias() += (weight * factor) * shape * shape.transpose();
      }
    }
    if (source) {
      const Eigen::Vector2d x = xy.transpose() * shape;
      residual.noalias() -= (weight * source(x(0), x(1))) * shape;
    }
  }
}

double element_integral(const ReferenceElement& ref, const ElementCoordinates& xy,
                        const ElementVector& nodal_field) {
  const auto n = static_cast<Eigen::Index>(ref.node_count);
  Eigen::Matrix<double, 2, Eigen::Dynamic, 0, 2, 9> gradient(2, n);
  double integral = 0.0;
  for (std::size_t q = 0; q < ref.point_count(); ++q) {
    const double weight = ref.rule.weights[q] * map_point(ref, q, xy, gradient);
    const Eigen::Map<const Eigen::VectorXd> shape(&ref.n[q * static_cast<std::size_t>(n)], n);
    integral += weight * shape.dot(nodal_field);
  }
  return integral;
}

}  // namespace tfmb::heat
