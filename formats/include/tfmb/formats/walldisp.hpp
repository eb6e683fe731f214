// The `walldisp` file kind (formats/walldisp.md): the displacement of every flap wall point from
// the beam solution, written by tfmb-loads (displace) and the two-way driver, read by tfmb-mesh
// (deform). read_walldisp checks the file against the kind's schema (what tfmb-check applies) and
// that every wall has points.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "tfmb/formats/files.hpp"

namespace tfmb::formats {

struct WallDisplacement {
  std::string name;  // a flow-mesh boundary name, or <flap>_<side> of the model
  std::string flap, side;
  std::vector<std::int64_t> nodes;            // flow-mesh node of each point (empty: model points)
  std::vector<Eigen::Vector2d> x0;            // [m] undeformed point
  std::vector<Eigen::Vector2d> displacement;  // [m]
};

struct WallDisplacements : ReadFrom {
  Header header;
  std::string wall_source;              // where the points come from (model walls or a flow mesh)
  std::vector<WallDisplacement> walls;  // by name
};

// Writes walldisp.h5 atomically.
void write_walldisp(const std::filesystem::path& file, const WallDisplacements& walls,
                    const Provenance& provenance);
// Reads and validates a walldisp file (BadInput naming the file and the object on any problem).
WallDisplacements read_walldisp(const std::filesystem::path& file);

}  // namespace tfmb::formats
