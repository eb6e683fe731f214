// The `structure` file kind (formats/structure.md): the beams' response, written by tfmb-beam and
// read by tfmb-loads (wall displacement), tfmb-strain (sectional strains) and tfmb-beam itself
// (--initial-state). read_structure checks the file against the kind's schema (what tfmb-check
// applies) and what the schema cannot say (flap segments run head to tail, a restart record is
// whole).
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "tfmb/formats/files.hpp"

namespace tfmb::formats {

using Vector6 = Eigen::Matrix<double, 6, 1>;

struct StructureFlap {
  std::string name;
  std::vector<std::int64_t> nodes;     // beam nodes, in order from the flap's start
  std::vector<std::int64_t> segments;  // display segments, in order, head to tail
};

struct StructureJoint {
  std::string name;
  Vector6 reaction = Vector6::Zero();  // force [N] and moment [N m] on the structure
  // Optional scalar outputs by name: relative_rotation [rad], contact_force [N], gap [m],
  // sliding [m], strain_energy [J] (structure.md lists which joint kinds have which).
  std::map<std::string, double> scalars;
  std::optional<Vector6> deformation;  // flexible joints: stretch [m] (3), wryness [1] (3)
};

// What a later dynamic run needs to continue this one (tfmb-beam --initial-state).
struct StructureRestart {
  std::vector<Eigen::Vector3d> velocity;          // [m/s] per node
  std::vector<Eigen::Vector3d> angular_velocity;  // [rad/s] per node, material frame
  std::vector<double> joint_dofs, joint_rates;    // [rad], [rad/s]
  double time = 0.0;                              // [s]
};

// The load path of a static analysis (1.3): row 0 the unloaded start, then one row per converged
// load step (tfmb-beam writes it for load stepping and arc length alike).
struct StructurePath {
  std::string method;  // load_stepping | arc_length
  std::string
      monitor;  // the monitored node and direction, e.g. "flap_a:end (0, -1, 0)"; "" if none
  std::vector<double> load_factor;                      // [1]
  std::vector<double> arc_length;                       // [m] nondecreasing
  std::vector<double> max_displacement;                 // [m] largest nodal displacement
  std::vector<double> characteristic_displacement;      // [m] monitored node along its direction
  std::vector<Eigen::Vector3d> node_displacement;       // [m] monitored node; empty without one
  std::vector<std::int64_t> iterations;                 // Newton iterations per step
  std::vector<std::int64_t> limit_points_load;          // rows where the load factor turns
  std::vector<std::int64_t> limit_points_displacement;  // rows where the displacement turns
};

struct Structure : ReadFrom {
  Header header;
  std::string analysis;  // static | dynamic | modal
  bool converged = false;
  std::vector<Eigen::Vector3d> points;                // [m] node reference positions
  std::vector<std::array<std::int64_t, 2>> segments;  // display segments (node pairs)
  std::vector<Eigen::Vector3d> displacement;          // [m] per node
  std::vector<Eigen::Vector3d> rotation;              // Wiener-Milenkovic parameters per node
  std::vector<Vector6> sectional_strain;              // per segment [1, 1/m]
  std::vector<Vector6> sectional_force;               // per segment [N, N m]
  std::vector<StructureFlap> flaps;                   // by name
  std::vector<StructureJoint> joints;                 // by name
  std::vector<double> history_time;                   // [s] dynamic
  std::vector<std::vector<Eigen::Vector3d>> history_displacement;  // [step][node] [m]
  std::vector<double> mode_frequency;                              // [Hz] modal
  std::vector<std::vector<Eigen::Vector3d>> mode_displacement;     // [mode][node], normalised
  std::optional<StructureRestart> restart;
  std::optional<StructurePath> path;  // static analyses (1.3); absent in older files

  const StructureFlap* find_flap(const std::string& name) const { return find_named(flaps, name); }
};

// Writes structure.h5 atomically and its XDMF sidecar.
void write_structure(const std::filesystem::path& file, const Structure& structure,
                     const Provenance& provenance);
// Reads and validates a structure file (BadInput naming the file and the object on any problem).
Structure read_structure(const std::filesystem::path& file);

}  // namespace tfmb::formats
