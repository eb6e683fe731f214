#pragma once
// The tfmb-heat stage: solidmesh.h5 + flow.h5 + model.h5 + material database -> thermal.h5.
//
// Boundary conditions come from model.h5 /thermal@solid_boundary:
//   wall_temperature      walls with a flow trace take the flow wall temperature (the seed's
//                         method)
//   convection            walls with a flow trace take h and T_aw from it
//   convection_radiation  as convection, plus radiation of every solid_outer wall
//                         (model /thermal@emissivity) to the environment temperature
// A solid wall (solid_inner / solid_outer) is matched to the flow wall of the same flap and side
// (/mesh/boundaries/*@flap, @side of both files). solid_inner walls need a trace; solid_outer
// walls without one are adiabatic (plus radiation where asked); solid_end walls are adiabatic,
// unless --joint-conductance h_c > 0: then, for every joint of model.h5,
// the closest pair of solid_end walls of its two flaps exchanges heat h_c (T_a - T_b) (gap
// conductance contact). Traces are moved onto the solid wall by projection (wall_mapping.hpp).
#include "tfmb-heat/problem.hpp"

#include <filesystem>
#include <string>

namespace tfmb {
class Logger;
}

namespace tfmb::heat {

struct Options {
  std::filesystem::path solid_mesh;        // solidmesh.h5
  std::filesystem::path flow;              // flow.h5
  std::filesystem::path model;             // model.h5
  std::filesystem::path material_db;       // material database (material-db kind)
  std::filesystem::path output;            // thermal.h5
  double environment_temperature = 300.0;  // [K] radiation sink of the outer walls
  double joint_conductance = 0.0;          // [W/(m^2 K)] across flap ends at joints; 0: none
  NewtonSettings newton;
  std::string command_line;  // stored in /provenance
  // Every command-line option's value as TOML (cli::OptionTable::settings_toml), for
  // /provenance@settings; empty for in-process callers.
  std::string settings_toml;
};

/// Runs the stage and writes the output (and its XDMF sidecar). Returns 0. Throws
/// tfmb::BadInput for invalid inputs (exit 3) and tfmb::NotConverged after writing a flagged
/// result when Newton did not converge (exit 1).
int run(const Options& options, const Logger& log);

}  // namespace tfmb::heat
