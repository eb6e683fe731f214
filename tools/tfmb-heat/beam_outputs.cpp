#include "tfmb-heat/beam_outputs.hpp"

#include "tfmb-heat/reference_element.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <string>

namespace tfmb::heat {

BeamThermalOutputs beam_element_temperatures(const SolidMesh& mesh, const Eigen::VectorXd& t,
                                             const std::vector<std::int64_t>& cell_to_beam,
                                             const Eigen::VectorXd& node_z,
                                             std::size_t beam_count) {
  if (cell_to_beam.size() != mesh.cell_count()) {
    throw std::invalid_argument("solid-to-beam map: " + std::to_string(cell_to_beam.size()) +
                                " entries for " + std::to_string(mesh.cell_count()) + " cells");
  }
  if (static_cast<std::size_t>(node_z.size()) != mesh.node_count() ||
      static_cast<std::size_t>(t.size()) != mesh.node_count()) {
    throw std::invalid_argument("solid-to-beam map: z or temperature size differs from the node count");
  }
  // Moments per beam element: int dA, int T, int z, int z^2, int T z.
  std::vector<double> a(beam_count, 0.0), it(beam_count, 0.0), iz(beam_count, 0.0),
      izz(beam_count, 0.0), itz(beam_count, 0.0);
  std::vector<double> z_min(beam_count, std::numeric_limits<double>::infinity());
  std::vector<double> z_max(beam_count, -std::numeric_limits<double>::infinity());
  std::size_t cell = 0;
  for (const auto& block : mesh.blocks) {
    // Accurate rule: the moments are polynomials of up to twice the element order.
    const auto ref = make_reference_element(block.type, accurate_rule(block.type));
    const auto npe = static_cast<std::size_t>(ref.node_count);
    for (std::size_t e = 0; e < block.size(); ++e, ++cell) {
      const auto beam = cell_to_beam[cell];
      if (beam < 0) continue;
      if (static_cast<std::size_t>(beam) >= beam_count) {
        throw std::invalid_argument("solid-to-beam map: cell " + std::to_string(cell) +
                                    " maps to beam element " + std::to_string(beam) + " of " +
                                    std::to_string(beam_count));
      }
      const auto b = static_cast<std::size_t>(beam);
      const auto nodes = block.element(e);
      for (auto node : nodes) {
        z_min[b] = std::min(z_min[b], node_z[node]);
        z_max[b] = std::max(z_max[b], node_z[node]);
      }
      for (std::size_t q = 0; q < ref.point_count(); ++q) {
        double tq = 0, zq = 0, j11 = 0, j12 = 0, j21 = 0, j22 = 0;
        for (std::size_t k = 0; k < npe; ++k) {
          const double n = ref.n[q * npe + k];
          const double px = mesh.points(nodes[k], 0), py = mesh.points(nodes[k], 1);
          tq += n * t[nodes[k]];
          zq += n * node_z[nodes[k]];
          j11 += ref.dn_dxi[q * npe + k] * px;
          j12 += ref.dn_dxi[q * npe + k] * py;
          j21 += ref.dn_deta[q * npe + k] * px;
          j22 += ref.dn_deta[q * npe + k] * py;
        }
        const double w = ref.rule.weights[q] * (j11 * j22 - j12 * j21);
        a[b] += w;
        it[b] += w * tq;
        iz[b] += w * zq;
        izz[b] += w * zq * zq;
        itz[b] += w * tq * zq;
      }
    }
  }
  BeamThermalOutputs out;
  for (std::size_t b = 0; b < beam_count; ++b) {
    if (!(a[b] > 0.0)) {
      throw std::invalid_argument("solid-to-beam map: beam element " + std::to_string(b) +
                                  " has no solid cells");
    }
    const double t_mean = it[b] / a[b], z_c = iz[b] / a[b];
    // Least-squares line T = T_mean + g (z - z_c) over the section.
    const double second_moment = izz[b] - a[b] * z_c * z_c;
    const double first_moment = itz[b] - a[b] * z_c * t_mean;
    const double gradient = second_moment > 0.0 ? first_moment / second_moment : 0.0;
    const double thickness = z_max[b] - z_min[b];
    out.area.push_back(a[b]);
    out.mean_temperature.push_back(t_mean);
    out.temperature_gradient.push_back(gradient);
    out.thickness.push_back(thickness);
    out.temperature_difference.push_back(gradient * thickness);
    out.z_centroid.push_back(z_c);
  }
  return out;
}

}  // namespace tfmb::heat
