// Venkatakrishnan's limiter (Venkatakrishnan 1995, J. Comput. Phys. 118:120; Blazek 2015,
// eq. 5.67-5.69) for the edge-midpoint reconstruction of the node-centred scheme.
#pragma once

#include <vector>

#include "gas.hpp"
#include "mesh_dual.hpp"

namespace tfmb::flow {

// phi[node][k] in [0, 1] for each of the 4 reconstructed variables. epsilon2[node][k] is the
// smoothing (K h)^3 scaled to the variable, see make_venkat_epsilon. to_neighbour: the vectors
// the reconstruction measures to each neighbour (StencilGeometry), half of which reaches the face.
void venkatakrishnan_limiter(const DualMesh& dual, const std::vector<Vec2>& to_neighbour,
                             const std::vector<State>& q,
                             const std::vector<std::array<double, 8>>& grad,
                             const std::vector<State>& epsilon2, std::vector<State>& phi);

// epsilon^2 = (K h_i / L)^3 * q_ref^2, with h_i = sqrt(dual area), L the domain length scale
// (sqrt of its area) and q_ref a reference magnitude per variable, so the limiter does not
// depend on the units of the mesh or of the state.
std::vector<State> make_venkat_epsilon(const DualMesh& dual, double k_venkat, const State& q_ref);

// Wang's variant (Wang 2000, AIAA 2000-0604; as in SU2's VENKATAKRISHNAN_WANG): epsilon =
// coefficient * (global max - global min) of each variable, the same for every node. Small
// fluctuations of nearly uniform fields (pressure across a boundary layer) then stay unlimited
// on any cell size, while jumps of the order of the range (shocks) are limited.
std::vector<State> make_wang_epsilon(const std::vector<State>& q, double coefficient,
                                     int num_nodes);

}  // namespace tfmb::flow
