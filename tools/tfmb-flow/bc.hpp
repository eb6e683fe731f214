// Boundary conditions, imposed weakly as fluxes through the boundary faces of the dual cells
// (Blazek 2015, ch. 8), except the no-slip velocity (and isothermal temperature), which is
// imposed strongly on the wall nodes by the solver.
#pragma once

#include <string>
#include <vector>

#include "gas.hpp"
#include "mesh.hpp"

namespace tfmb::flow {

enum class BcKind {
  stagnation_inflow,  // total pressure, total temperature and flow angle given
  farfield,           // far field from a free-stream state (Roe flux against it, or Riemann invariants)
  pressure_outflow,   // static pressure if the face-normal Mach number < 1, else extrapolation
  slip_wall,          // inviscid wall
  symmetry,           // symmetry plane or axis (inviscid flux as slip wall, no shear)
  wall_adiabatic,     // no-slip, zero heat flux
  wall_isothermal,    // no-slip, fixed wall temperature
};

std::string to_string(BcKind kind);

struct BoundaryCondition {
  BcKind kind = BcKind::slip_wall;
  double total_pressure = 0.0;     // stagnation_inflow [Pa]
  double total_temperature = 0.0;  // stagnation_inflow [K]
  double flow_angle = 0.0;         // stagnation_inflow: flow direction from +x [rad]
  State freestream{};              // farfield: primitive (rho, u, v, p) [kg/m^3, m/s, m/s, Pa]
  // farfield: optional free-stream state per mesh node (e.g. an exact solution); overrides
  // freestream when not empty (size = number of nodes).
  std::vector<State> node_freestream;
  // farfield: flux through the face. Default: the Roe flux between the node state and the free
  // stream (FUN3D's "farfield_roe"), a differentiable function of the node state, since each wave
  // is upwinded by its Roe-averaged speed. The alternative builds the boundary state from the
  // locally one-dimensional Riemann invariants (Blazek 2015, sec. 8.2), whose switches at V.n = 0
  // (entropy and tangential velocity from outside or inside) and at V.n = c make the residual
  // jump: on a jet into air at rest the implicit iteration then locks into a limit cycle
  // (nasa-2dcd: period 2-4 at 1e-2..1e-3 of the peak residual) instead of converging.
  bool riemann_invariants = false;
  double static_pressure = 0.0;    // pressure_outflow [Pa]
  double wall_temperature = 0.0;   // wall_isothermal [K]
  // wall_isothermal: per node of the solver's numbering [K]; overrides wall_temperature when set
  std::vector<double> node_wall_temperature;
  // slip_wall: Riemann flux against the mirror state (default: robust when the flow impinges,
  // needed for jet start-up) or the pressure-only flux (more accurate on curved walls: the
  // supersonic vortex errors halve, orders 1.97/1.95 instead of 1.89/1.84). Symmetry always
  // uses the Riemann flux.
  bool riemann_wall = true;

  bool no_slip() const { return kind == BcKind::wall_adiabatic || kind == BcKind::wall_isothermal; }
};

// Flux out of the domain through a boundary face with outward normal n (length = face measure),
// given the primitive state w at the face's node. Far field and outflow solve the Roe Riemann
// problem between w and the free stream or the characteristic boundary state (entropy_fix as in
// roe_flux), which lets a start-up shock leave through a supersonic exit instead of sticking to
// the exit nodes.
State boundary_flux(const PerfectGas& gas, const BoundaryCondition& bc, const State& w, Vec2 n,
                    int node, double entropy_fix);

// The state on the boundary side of each kind (primitive). Exposed for tests.
State stagnation_inflow_state(const PerfectGas& gas, const BoundaryCondition& bc, const State& w, Vec2 unit_n);
State farfield_state(const PerfectGas& gas, const State& w_inf, const State& w, Vec2 unit_n);
State outflow_state(const PerfectGas& gas, double p_exit, const State& w, Vec2 unit_n);

}  // namespace tfmb::flow
