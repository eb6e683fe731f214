// The `loads` file kind (formats/loads.md): wall loads mapped onto the beam nodes of each flap,
// written by tfmb-loads and read by tfmb-beam. read_loads checks the file against the kind's
// schema (what tfmb-check applies) and that every flap's arrays have one row per beam node.
#pragma once

#include <Eigen/Core>
#include <filesystem>
#include <string>
#include <vector>

#include "tfmb/formats/files.hpp"

namespace tfmb::formats {

struct LoadsFlap {
  std::string name;
  double width = 0.0;               // [m] the traces were multiplied by
  std::vector<std::string> traces;  // wall traces mapped
  std::vector<double> s;            // [m] arc length of each beam node
  std::vector<Eigen::Vector2d> position;  // [m] reference position of each beam node (1.2;
                                          // empty: not stored, as in 1.0 and 1.1 files)
  // One row per beam node, (x, y, z) components.
  std::vector<Eigen::Vector3d> distributed_force;   // [N/m] L2 projection, for plots
  std::vector<Eigen::Vector3d> distributed_moment;  // [N]
  std::vector<Eigen::Vector3d> nodal_force;   // [N] consistent nodal forces (what a beam takes)
  std::vector<Eigen::Vector3d> nodal_moment;  // [N m]
  Eigen::Vector3d total_force = Eigen::Vector3d::Zero();    // [N] integral of the traces
  Eigen::Vector3d total_moment = Eigen::Vector3d::Zero();   // [N m] about the origin
  Eigen::Vector3d mapped_force = Eigen::Vector3d::Zero();   // [N] sum of the nodal loads
  Eigen::Vector3d mapped_moment = Eigen::Vector3d::Zero();  // [N m]
};

struct Loads : ReadFrom {
  Header header;
  std::string method;            // linear | conservative
  std::string load_basis;        // what the loads are per (loads.md)
  std::vector<LoadsFlap> flaps;  // by name
};

// Writes loads.h5 atomically (header, flaps, provenance).
void write_loads(const std::filesystem::path& file, const Loads& loads,
                 const Provenance& provenance);
// Reads and validates a loads file (BadInput naming the file and the object on any problem).
Loads read_loads(const std::filesystem::path& file);

}  // namespace tfmb::formats
