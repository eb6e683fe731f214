#include "tfmb-beam/inertia.hpp"

#include "tfmb-beam/beam_element.hpp"

namespace tfmb::beam {

MassModel build_mass(const Model& model) {
  MassModel mm;
  const int nn = static_cast<int>(model.nodes.size());
  mm.nodal_inertia.assign(nn, Eigen::Matrix3d::Zero());
  std::vector<Eigen::Triplet<double>> trip;
  // Three-point Gauss: exact for N_i N_j (quartic) on a straight element.
  const double pts[3] = {-std::sqrt(0.6), 0.0, std::sqrt(0.6)};
  const double wts[3] = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};
  for (const Element& el : model.elements) {
    const Section& sec = model.sections[el.section];
    for (int q = 0; q < 3; ++q) {
      const auto n = shape_quadratic(pts[q]);
      const auto dn = shape_quadratic_derivative(pts[q]);
      Eigen::Vector3d dx = Eigen::Vector3d::Zero();
      for (int j = 0; j < 3; ++j) dx += dn[j] * model.nodes[el.nodes[j]].position;
      const double wj = wts[q] * dx.norm();
      for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) trip.emplace_back(el.nodes[i], el.nodes[j], wj * n[i] * n[j] * sec.mass_per_length);
        // Lumped rotary inertia, using the node's frame for the section orientation.
        mm.nodal_inertia[el.nodes[i]] += wj * n[i] * sec.inertia_per_length;
      }
    }
  }
  mm.mass_scalar.resize(nn, nn);
  mm.mass_scalar.setFromTriplets(trip.begin(), trip.end());
  return mm;
}

}  // namespace tfmb::beam
