// Wall traces of one flap -> loads on its beam nodes. All outputs are over the flap width w:
// the flow traces are per unit depth, so forces per unit depth are multiplied by w.
//
// Both methods give, per beam node i, a distributed force q_i [N/m] and distributed moment
// m_i [N] per unit beam length (linear between nodes), and nodal forces F_i [N] and moments
// M_i [N m] equal to the consistent integrals of those linear distributions:
//   F_i = sum over elements e of i of int_e N_i q ds   (Zienkiewicz & Taylor, The Finite
//   Element Method vol. 1, 6th ed., sec. 2.2: consistent load vector).
//
// linear (the seed's interface module, its Fig. 8): q_i and m_i from the traces interpolated
//   linearly at the wall points facing node i (where node line i crosses each wall); the wall
//   traction times the ratio of wall to beam arc length there, and the moment of that force
//   about the beam node (offset of the wall from the reference line).
// conservative: the traction of every wall piece is carried to the beam point it projects to,
//   shared between the two element nodes with the linear shape functions, and the offset
//   moment (x_wall - x_beam) x t added in the same way:
//   F_i = w int N_i(xi(x)) t ds,  M_i = w int N_i(xi(x)) (x - x_b(x)) x t ds.
//   Because sum_i N_i = 1 and sum_i N_i r_i = x_b on straight elements, sum F_i equals the
//   trace force and sum (r_i x F_i + M_i) the trace moment, up to rounding. The distributed
//   loads written with it are the L2 projection of the trace load on the linear beam
//   elements (M q = F with the consistent 1D mass matrix), so the beam sees the same totals
//   whether it uses the nodal or the distributed loads.
#pragma once

#include <functional>
#include <vector>

#include "beam_line.hpp"
#include "trace.hpp"

namespace tfmb::loads {

enum class Method { linear, conservative };
const char* method_name(Method method);

struct FlapLoads {
  std::vector<double> arc_length;       // per node [m]
  std::vector<Vec2> distributed_force;  // [N/m]
  std::vector<double> distributed_moment;  // z [N]
  std::vector<Vec2> nodal_force;        // [N]
  std::vector<double> nodal_moment;     // z [N m]
  Resultant traces;                     // integral of the traces over the width [N, N m]
  Resultant mapped;                     // sum of the nodal loads about the origin [N, N m]
};

// `traces` are the traces of one flap (any side, oriented). Linear uses the inner and outer
// traces only (as the seed did); conservative uses all, including the end faces.
FlapLoads map_loads(Method method, const BeamLine& beam, const std::vector<const WallTrace*>& traces,
                    double width);

// Pressure [Pa] and wall shear [Pa] of an analytic field at a wall point of a side.
using WallField = std::function<std::pair<double, double>(Side, const Vec2&)>;

// The linear method with the field evaluated exactly at the wall points facing the beam nodes
// instead of interpolated in the traces (same geometry, normals and length ratios): what the
// linear method would give with error-free traces. Used by --diff.
FlapLoads map_linear_exact(const BeamLine& beam, const std::vector<const WallTrace*>& traces, double width,
                           const WallField& field);

// Resultant of nodal loads about the origin.
Resultant nodal_resultant(const BeamLine& beam, const std::vector<Vec2>& force,
                          const std::vector<double>& moment);

// Consistent nodal loads of a distribution linear between nodes.
void consistent_nodal_loads(const BeamLine& beam, const std::vector<Vec2>& distributed_force,
                            const std::vector<double>& distributed_moment,
                            std::vector<Vec2>& nodal_force, std::vector<double>& nodal_moment);

// Where node line i crosses the traces of one side: the wall point, traction and local
// wall-to-beam length ratio are what the linear method uses.
struct WallSample {
  bool found = false;
  Vec2 point = Vec2::Zero();
  Vec2 traction = Vec2::Zero();
  Vec2 normal = Vec2::Zero();   // out of the solid (interpolated between vertex normals)
  Vec2 tangent = Vec2::Zero();  // along increasing trace index
};
WallSample sample_at_node(const BeamLine& beam, std::size_t node,
                          const std::vector<const WallTrace*>& side_traces);

}  // namespace tfmb::loads
