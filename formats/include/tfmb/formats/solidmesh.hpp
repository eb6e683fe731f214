// The `solidmesh` file kind (formats/solidmesh.md): the mesh of the flap walls and its link to
// the beam elements, written by tfmb-mesh solid and read by tfmb-heat. read_solidmesh checks the
// file against the kind's schema (what tfmb-check applies) and that every cell has a flap.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "tfmb/formats/files.hpp"

namespace tfmb::formats {

struct SolidMesh : ReadFrom {
  Header header;
  Mesh mesh;
  std::vector<std::string> flap_names;             // indexed by cell_flap
  std::vector<std::int64_t> cell_flap;             // per cell: its flap
  std::vector<std::int64_t> cell_element;          // per cell: its beam element within the flap
  std::vector<double> point_thickness_coordinate;  // [m] per node, positive towards the outer wall
};

// Writes solidmesh.h5 atomically and its XDMF sidecar.
void write_solidmesh(const std::filesystem::path& file, const SolidMesh& solid,
                     const Provenance& provenance);
// Reads and validates a solidmesh file (BadInput naming the file and the object on any problem).
SolidMesh read_solidmesh(const std::filesystem::path& file);

}  // namespace tfmb::formats
