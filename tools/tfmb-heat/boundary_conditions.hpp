#pragma once
// Boundary conditions on tagged boundary curves and contact between bodies.
// Sign convention: heat flux q_in [W/m^2] is positive into the solid.
#include "tfmb-heat/trace.hpp"

#include <optional>
#include <string>
#include <variant>

namespace tfmb::heat {

/// T = T_wall(s) at the boundary nodes (the seed's approach: wall temperature from the flow).
struct ImposedTemperature {
  Trace temperature;  // [K] along the wall
};

/// q_in = h(s) (T_aw(s) - T). Newton tangent h.
struct Convection {
  Trace heat_transfer_coefficient;      // h [W/(m^2 K)], >= 0
  Trace adiabatic_wall_temperature;     // T_aw [K]
};

/// q_in = eps sigma (T_env^4 - T^4) (grey surface seeing an environment at T_env).
/// Newton tangent 4 eps sigma T^3.
struct Radiation {
  double emissivity = 0.0;              // [-], in [0, 1]
  double environment_temperature = 0.0; // [K]
};

/// q_in = q(s).
struct ImposedHeatFlux {
  Trace heat_flux;  // [W/m^2], positive into the solid
};

/// q_in = 0 (the default for untagged edges; stated explicitly to document intent).
struct Adiabatic {};

using BoundaryCondition =
    std::variant<ImposedTemperature, Convection, Radiation, ImposedHeatFlux, Adiabatic>;

/// One condition on one tagged boundary. Several conditions on the same boundary add up
/// (e.g. convection plus radiation); an imposed temperature overrides the others at its nodes.
struct BoundarySpec {
  std::string boundary;
  BoundaryCondition condition;
};

/// Thermal contact between two boundary curves (e.g. two flaps at a joint).
/// perfect (no gap conductance): the nodes of side a are tied to coincident nodes of side b
/// (same temperature), so the meshes must match along the contact.
/// gap conductance h_c [W/(m^2 K)]: q from a to b = h_c (T_a - T_b), integrated along side a
/// with T_b taken at the closest point of side b (the sides need not match).
struct ContactSpec {
  std::string boundary_a;
  std::string boundary_b;
  std::optional<double> gap_conductance;
};

const char* condition_name(const BoundaryCondition& condition);

}  // namespace tfmb::heat
