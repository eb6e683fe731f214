// Geometry input: named curves as polylines [m] from a CSV polyline file, a STEP/IGES file
// (gmsh's OpenCASCADE) or a gmsh .geo file.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "tfmb/common/geometry.hpp"

namespace tfmb::input {

struct Curve {
  std::string name;              // CSV: the "curve" column; CAD: physical/entity name or tag
  geometry::Polyline points;     // [m]
};

// Reads the curves of a geometry file; coordinates are multiplied by `scale`. CAD curves are
// sampled with `curve_samples` points uniformly in their parameter (straight lines: 2).
// Throws BadInput for a missing or unreadable file, or a file without curves.
std::vector<Curve> read_geometry(const std::filesystem::path& file, double scale, int curve_samples);

// Writes curves as the CSV polyline format (curve,x,y), e.g. to inspect what a CAD file gave.
void write_curves_csv(const std::vector<Curve>& curves, const std::filesystem::path& file);

}  // namespace tfmb::input
