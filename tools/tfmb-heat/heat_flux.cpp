#include "tfmb-heat/heat_flux.hpp"

#include "tfmb-heat/element_conduction.hpp"
#include "tfmb-heat/reference_element.hpp"
#include "tfmb-heat/shape_functions.hpp"

#include <cmath>
#include <stdexcept>

namespace tfmb::heat {

namespace {
// Calls visit(weight, x, y, shape) at every point of the accurate rule of every element, with
// shape the element's shape-function values and weight = w |J|.
template <typename Visit>
void for_each_point(const SolidMesh& mesh, Visit&& visit) {
  for (const auto& block : mesh.blocks) {
    const auto ref = make_reference_element(block.type, accurate_rule(block.type));
    const auto npe = static_cast<std::size_t>(ref.node_count);
    for (std::size_t e = 0; e < block.size(); ++e) {
      const auto nodes = block.element(e);
      for (std::size_t q = 0; q < ref.point_count(); ++q) {
        double x = 0, y = 0, j11 = 0, j12 = 0, j21 = 0, j22 = 0;
        for (std::size_t a = 0; a < npe; ++a) {
          const double px = mesh.points(nodes[a], 0), py = mesh.points(nodes[a], 1);
          const double n = ref.n[q * npe + a];
          x += n * px;
          y += n * py;
          j11 += ref.dn_dxi[q * npe + a] * px;
          j12 += ref.dn_dxi[q * npe + a] * py;
          j21 += ref.dn_deta[q * npe + a] * px;
          j22 += ref.dn_deta[q * npe + a] * py;
        }
        visit(ref.rule.weights[q] * (j11 * j22 - j12 * j21), x, y, nodes, &ref.n[q * npe]);
      }
    }
  }
}
}  // namespace

Eigen::Matrix<double, Eigen::Dynamic, 2, Eigen::RowMajor> nodal_heat_flux(
    const ThermalProblem& problem, const Eigen::VectorXd& t) {
  const auto& mesh = *problem.mesh;
  Eigen::Matrix<double, Eigen::Dynamic, 2, Eigen::RowMajor> flux =
      Eigen::Matrix<double, Eigen::Dynamic, 2, Eigen::RowMajor>::Zero(static_cast<Eigen::Index>(mesh.node_count()), 2);
  Eigen::VectorXd weight = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(mesh.node_count()));
  std::size_t cell = 0;
  for (const auto& block : mesh.blocks) {
    const auto npe = nodes_per_element(block.type);
    const auto ref_nodes = reference_node_coordinates(block.type);
    const auto area_ref = make_reference_element(block.type, stiffness_rule(block.type));
    std::vector<double> n(static_cast<std::size_t>(npe)), dxi(n.size()), deta(n.size());
    ElementCoordinates xy(npe, 2);
    ElementVector ones = ElementVector::Ones(npe);
    for (std::size_t e = 0; e < block.size(); ++e, ++cell) {
      const auto nodes = block.element(e);
      for (int a = 0; a < npe; ++a) xy.row(a) = mesh.points.row(nodes[static_cast<std::size_t>(a)]);
      const double area = element_integral(area_ref, xy, ones);
      const auto& material = problem.materials[static_cast<std::size_t>(mesh.cell_material[cell])];
      for (int a = 0; a < npe; ++a) {
        shape_functions(block.type, ref_nodes[static_cast<std::size_t>(a)][0], ref_nodes[static_cast<std::size_t>(a)][1], n.data(), dxi.data(), deta.data());
        Eigen::Matrix2d jacobian = Eigen::Matrix2d::Zero();
        Eigen::Vector2d dt_ref = Eigen::Vector2d::Zero();
        for (int b = 0; b < npe; ++b) {
          const double tb = t[nodes[static_cast<std::size_t>(b)]];
          jacobian(0, 0) += dxi[static_cast<std::size_t>(b)] * xy(b, 0);
          jacobian(0, 1) += dxi[static_cast<std::size_t>(b)] * xy(b, 1);
          jacobian(1, 0) += deta[static_cast<std::size_t>(b)] * xy(b, 0);
          jacobian(1, 1) += deta[static_cast<std::size_t>(b)] * xy(b, 1);
          dt_ref(0) += dxi[static_cast<std::size_t>(b)] * tb;
          dt_ref(1) += deta[static_cast<std::size_t>(b)] * tb;
        }
        const Eigen::Vector2d gradient = jacobian.inverse() * dt_ref;
        const auto node = nodes[static_cast<std::size_t>(a)];
        // Fourier's law q = -k(T) grad T.
        flux.row(node) -= area * material.conductivity.value(t[node]) * gradient.transpose();
        weight[node] += area;
      }
    }
  }
  for (Eigen::Index i = 0; i < flux.rows(); ++i) {
    if (weight[i] > 0.0) flux.row(i) /= weight[i];
  }
  return flux;
}

double l2_error(const SolidMesh& mesh, const Eigen::VectorXd& t,
                const std::function<double(double, double)>& exact) {
  double sum = 0.0;
  for_each_point(mesh, [&](double weight, double x, double y, std::span<const std::int64_t> nodes,
                           const double* shape) {
    double th = 0.0;
    for (std::size_t a = 0; a < nodes.size(); ++a) th += shape[a] * t[nodes[a]];
    const double error = th - exact(x, y);
    sum += weight * error * error;
  });
  return std::sqrt(sum);
}

double mesh_area(const SolidMesh& mesh) {
  double area = 0.0;
  for_each_point(mesh, [&](double weight, double, double, std::span<const std::int64_t>, const double*) {
    area += weight;
  });
  return area;
}

}  // namespace tfmb::heat
