// The `flowmesh` file kind (formats/flowmesh.md): the fluid mesh written by tfmb-mesh flow and
// deform (or imported by tfmb-convert) and read by tfmb-flow and tfmb-loads. read_flowmesh
// checks the file against the kind's schema (what tfmb-check applies) and that it has cells and
// boundaries.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>

#include "tfmb/formats/files.hpp"

namespace tfmb::formats {

// The quality report on /mesh; every entry optional (an imported mesh may carry none).
struct MeshQualityReport {
  std::optional<double> min_angle;           // [deg]
  std::optional<double> max_aspect_ratio;    // [1]
  std::optional<double> min_cell_area;       // [m^2]
  std::optional<double> first_layer_height;  // [m] 0: no wall layers
  std::optional<double> estimated_yplus;     // [1]
  std::optional<std::int64_t> boundary_layers;
};

struct FlowMesh : ReadFrom {
  Header header;
  Mesh mesh;
  MeshQualityReport quality;
};

// Writes flowmesh.h5 atomically and its XDMF sidecar.
void write_flowmesh(const std::filesystem::path& file, const FlowMesh& flow_mesh,
                    const Provenance& provenance);
// Reads and validates a flowmesh file (BadInput naming the file and the object on any problem).
FlowMesh read_flowmesh(const std::filesystem::path& file);

}  // namespace tfmb::formats
