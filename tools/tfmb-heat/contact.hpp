#pragma once
// Thermal contact between two boundary curves.
#include "tfmb-heat/mesh.hpp"

#include <array>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace tfmb::heat {

/// Perfect contact: pairs (node of a, coincident node of b). Nodes coincide when closer than
/// 1e-6 times the shortest edge of either curve. Throws std::invalid_argument when a node of a
/// has no coincident node on b (non-matching meshes need a gap conductance).
std::vector<std::pair<std::int64_t, std::int64_t>> perfect_contact_pairs(
    const SolidMesh& mesh, const BoundaryCurve& a, const BoundaryCurve& b,
    const std::string& description);

/// One quadrature point of a gap-conductance contact: heat h_c (T_a - T_b) weight flows from
/// side a (at the point) to side b (at the closest point of b, found by projection onto the
/// chords of b's edges).
struct GapPoint {
  std::array<std::int64_t, 3> a_nodes{}, b_nodes{};
  std::array<double, 3> a_n{}, b_n{};
  int a_count = 0, b_count = 0;
  double weight = 0.0;       // [m]
  double conductance = 0.0;  // h_c [W/(m^2 K)]
  int contact = -1;
};

std::vector<GapPoint> gap_contact_points(const SolidMesh& mesh, const BoundaryCurve& a,
                                         const BoundaryCurve& b, double conductance,
                                         int contact_index);

}  // namespace tfmb::heat
