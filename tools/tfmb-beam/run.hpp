// The tfmb-beam stage on files: model.h5 [+ loads.h5] [+ materials.h5] -> structure.h5.
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "tfmb-beam/model.hpp"
#include "tfmb-beam/static_solver.hpp"
#include "tfmb/common/log.hpp"
#include "tfmb/formats/model.hpp"

namespace tfmb::beam {

struct Options {
  std::filesystem::path model;      // tfmb/model
  std::filesystem::path loads;      // tfmb/loads (optional)
  std::filesystem::path materials;  // tfmb/materials (optional)
  std::filesystem::path output;     // tfmb/structure
  std::string analysis;             // static | dynamic | modal; empty: the model's /analysis @time
  int load_steps = 0;               // static: 0 -> the model's /analysis @load_steps
  double end_time = 0.0;            // dynamic [s]; 0 -> the model's
  double time_step = 0.0;           // dynamic [s]; 0 -> the model's
  /// dynamic: continue from the final state and motion (/restart) of an earlier dynamic
  /// structure.h5 of the same model (two-way exchanges of dynamics, the seed's config2)
  std::filesystem::path initial_state;
  double rho_infinity = 0.8;  // dynamic: spectral radius at infinity
  int modes = 6;              // modal: number of modes
  bool arc_length = false;    // static: arc-length continuation to load factor 1 (limit points)
  bool dead_loads = false;    // loads.h5 forces as dead loads (default: follower, pressure)
  /// Dead point loads "flap:start|end:fx,fy[,mz]" [N, N m] at flap ends (e.g. the seed's centre
  /// load of cases/beam-revolute); held constant in time in dynamics.
  std::vector<std::string> point_loads;
  std::string command_line;
  /// Every command-line option's value as TOML (cli::OptionTable::settings_toml), for
  /// /provenance@settings; empty for in-process callers.
  std::string settings_toml;
};

/// A beam model built from the files, with the mapping back to the flaps.
struct FileModel {
  Model model;
  std::vector<std::string> flap_names;
  std::map<std::string, std::vector<int>> flap_nodes;     // beam nodes of each flap, in order
  std::map<std::string, std::vector<int>> flap_elements;  // quadratic elements of each flap
  std::vector<std::string> joint_names;  // per model.joints entry ("" for planar guides)
  formats::AnalysisSettings analysis;    // the model's /analysis (defaults of --analysis etc.)
  /// The load path's monitored node: the first --point-load's node along its force (none without).
  PathMonitor monitor;
  std::string monitor_name;  // e.g. "beam_a:end (0, -1, 0)"
};

/// Reads and checks the inputs (throws tfmb::BadInput naming the file and object on errors).
FileModel read_model(const Options& options);

/// Runs the analysis and writes structure.h5. Returns the exit code (0; throws NotConverged after
/// writing a flagged file when Newton fails).
int run(const Options& options, const Logger& log);

}  // namespace tfmb::beam
