// tfmb-mesh: fluid mesh (gmsh for the triangles, our own structured boundary-layer strips),
// solid mesh of the flap walls, and deformation of a fluid mesh by a wall displacement.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "tfmb/common/geometry.hpp"
#include "tfmb/common/log.hpp"
#include "tfmb/formats/files.hpp"
#include "tfmb/formats/model.hpp"
#include "tfmb/formats/walldisp.hpp"

namespace tfmb::mesh {

using formats::Mesh;
using formats::Model;
using geometry::Point;
using geometry::Polyline;

// y+ of a wall cell of height h from the model's viscous length (model 2.5: tfmb-input's
// flat-plate estimate); empty if the model records none.
std::optional<double> estimated_yplus(const Model& model, double height);

// --- quality -------------------------------------------------------------------------------
struct Quality {
  double min_angle = 180.0;       // [deg] smallest interior angle of any cell
  double max_aspect_ratio = 1.0;  // [1] longest over shortest edge of a cell, largest
  double min_area = 0.0;          // [m^2] smallest corner-triangle area (quads: 4 corners)
  std::int64_t worst_cell = -1;   // cell with min_area
  std::size_t invalid_cells = 0;  // cells with a non-positive corner area
};
Quality mesh_quality(const Mesh& mesh);
// Smallest signed area of the corner triangles of a cell (positive: valid, counter-clockwise).
double cell_min_corner_area(const h5::MatrixXdR& points, const Mesh& mesh, std::int64_t cell);
// Reorders cells to counter-clockwise where they are clockwise.
void orient_counter_clockwise(Mesh& mesh);

// --- flow mesh -----------------------------------------------------------------------------
struct FlowMeshOptions {
  double scale = 0.0;  // 0: the model's mesh.scale; else overrides it
  int algorithm = 6;   // gmsh 2D algorithm (5 Delaunay, 6 Frontal-Delaunay)
  // Refuse a nozzle mesh estimated above this many cells before sampling anything (the case
  // meshes have 10^4-10^5; 2e6 is minutes and gigabytes in gmsh).
  double max_cells = 2e6;
};
struct FlowMeshReport {
  Quality quality;
  int boundary_layers = 0;
  double first_layer_height = 0.0;        // [m]
  std::optional<double> estimated_yplus;  // [1] empty: the model records no viscous length
  double seconds = 0.0;
};
// Builds the fluid mesh of a model's flow domain (nozzle: quad layers on walls + gmsh triangles;
// channel and flatplate: structured quads). Boundaries named as the model's domain boundaries.
Mesh build_flow_mesh(const Model& model, const FlowMeshOptions& options, FlowMeshReport& report,
                     const Logger& log);

// --- solid mesh ----------------------------------------------------------------------------
struct SolidLink {
  std::vector<std::string> flap_names;
  std::vector<std::int64_t> cell_flap, cell_element;
  std::vector<double> point_thickness_coordinate;  // [m] positive towards the outer surface
};
Mesh build_solid_mesh(const Model& model, SolidLink& link);

// --- deformation ---------------------------------------------------------------------------
// A wall's displacement as walldisp.h5 gives it (formats/walldisp.hpp): `name` is a flow-mesh
// boundary or <flap>_<side> of the model; `nodes` empty when the points are the model's.
using formats::WallDisplacement;
struct DeformReport {
  Quality quality;
  double admissible_fraction = 1.0;  // largest fraction of the displacement keeping cells valid
  std::size_t moved_wall_nodes = 0;
  std::size_t projected_nodes = 0;  // wall nodes off the walldisp curves (joins, lips, end faces)
  double largest_projection = 0.0;  // [m] their largest distance to the curves
};
struct DeformOptions {
  // interpolate each wall node's rotation as well as its displacement (Luke, Collins & Blades
  // 2012); false: displacements only, as before 2026-11-27
  bool rotations = true;
};
// Moves the wall nodes by the wall displacement and the rest by inverse-distance weighting (Luke,
// Collins & Blades 2012). Wall nodes: given by node id (walldisp `node`), else interpolated along
// the walldisp curve of the same name, else (flap walls the walldisp does not list, e.g. end
// faces, and the joins between flaps) taken from the nearest point of that flap's walldisp
// curves; a node two walls give (a joint's shared node) takes their mean. Throws BadInput (with
// the admissible fraction found by bisection) if a cell would invert.
Mesh deform_mesh(const Mesh& mesh, const std::vector<WallDisplacement>& walls,
                 const DeformOptions& options, DeformReport& report);

// --- commands ------------------------------------------------------------------------------
struct Options {
  std::string command;  // flow | solid | deform
  std::filesystem::path input, walldisp, output;
  double scale = 0.0;  // 0: the case's mesh.scale
  int algorithm = 6;
  double max_cells = FlowMeshOptions{}.max_cells;
  DeformOptions deform;
  std::string command_line;
  std::string settings_toml;  // the command line's options (cli::OptionTable) for /provenance
};
int run(const Options& options, const Logger& log);

}  // namespace tfmb::mesh
