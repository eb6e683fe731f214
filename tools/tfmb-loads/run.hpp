// tfmb-loads stages: `forces` (wall traces -> beam loads) and `displace` (beam motion -> wall
// displacement). main.cpp parses options into these structs; tests call the functions in
// process.
#pragma once

#include <filesystem>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "io.hpp"
#include "mapping.hpp"
#include "tfmb/common/log.hpp"

namespace tfmb::loads {

struct ForcesOptions {
  std::filesystem::path flow_file;  // empty with `function`
  std::filesystem::path model_file;
  std::filesystem::path output;
  Method method = Method::conservative;
  // "p_inner=...; p_outer=...; tau_inner=...; tau_outer=..." (p=..., tau=... set both sides);
  // variables x, y [m]. Replaces the flow file: the traces are the model walls, each segment
  // cut into `function_samples` pieces.
  std::string function;
  int function_samples = 8;
  bool diff = false;                            // report the mapping error against `function`
  double coverage_tolerance = 1e-3;             // relative to the flap length
  std::optional<double> missing_side_pressure;  // [Pa] for a flap side without traces
  std::filesystem::path reference_mesh;  // two-way: undeformed flowmesh (see read_flow_traces)
  std::string command_line;
  std::string settings_toml;  // the command line's options (cli::OptionTable) for /provenance
};

struct FlapDiff {
  double max_distributed_force_error = 0.0;  // [N/m]
  double max_distributed_force = 0.0;        // [N/m] of the reference
  double force_error = 0.0;                  // |mapped - exact| / |exact| of the total force
  double moment_error = 0.0;
};

struct ForcesResult {
  LoadsFile loads;
  std::vector<FlapDiff> diffs;  // with diff, per flap
};

// Throws BadInput for invalid inputs (uncovered flaps, unknown flaps, bad traces).
ForcesResult run_forces(const ForcesOptions& options, const Logger& logger, std::ostream& out);

struct DisplaceOptions {
  std::filesystem::path structure_file;  // empty with `function`
  std::filesystem::path model_file;
  std::filesystem::path mesh_file;  // optional flowmesh/flow: wall points = mesh wall nodes
  std::filesystem::path output;
  // "ux=...; uy=...; rz=..." beam displacement [m] and rotation [rad] at the beam nodes as
  // functions of x, y [m]; replaces the structure file.
  std::string function;
  bool diff = false;              // compare with (ux, uy) of `function` at the wall points
  double match_tolerance = 1e-6;  // structure nodes vs model reference curve, relative to length
  std::string command_line;
  std::string settings_toml;  // the command line's options (cli::OptionTable) for /provenance
};

struct DisplaceResult {
  std::vector<WallDisplacement> walls;
  std::vector<double> max_error;  // with diff, per wall [m]
};

DisplaceResult run_displace(const DisplaceOptions& options, const Logger& logger,
                            std::ostream& out);

}  // namespace tfmb::loads
