// The `model` file kind (formats/model.md): what tfmb-input builds from case.toml and the
// geometry and what every later stage (mesh, beam, loads, matmap, heat) reads. Plain structs;
// read_model and write_model are the only code that knows the HDF5 layout, and read_model checks
// the file against the kind's schema (the one tfmb-check applies) before it reads it.
#pragma once

#include <Eigen/Core>
#include <filesystem>
#include <string>
#include <vector>

#include "tfmb/common/geometry.hpp"
#include "tfmb/formats/files.hpp"

namespace tfmb::formats {

using geometry::Point;
using geometry::Polyline;
using Matrix6 = Eigen::Matrix<double, 6, 6>;

// Sectional properties of a flap. Order of the generalised strains (DESIGN.md §6, the seed's
// Table 1): axial, shear 2 (in-plane transverse), shear 3 (depth), torsion, bending about 2,
// bending about 3 (in-plane bending, the flap's main deflection).
struct Section {
  std::string kind = "rectangle";  // "rectangle" (from thickness, width, E, nu, rho) or "explicit"
  Matrix6 stiffness = Matrix6::Zero();  // [N] (rows/cols 1-3), [N m^2] (4-6), [N m] coupling
  Matrix6 mass = Matrix6::Zero();       // [kg/m] (1-3), [kg m] (4-6)
  double youngs_modulus = 0.0;          // [Pa], rectangle only (0 if explicit)
  double poisson_ratio = 0.0;           // [1]
  double density = 0.0;                 // [kg/m^3]
};

struct Flap {
  std::string name;
  std::vector<std::string> curves;  // geometry curve names, in order
  std::string half = "none";        // upper | lower | none
  std::string material;             // name in the material database
  double thickness = 0.0;           // [m]
  double width = 1.0;               // [m] extent in the depth direction
  int elements = 1;                 // two-node beam elements along the reference curve
  Section section;
  Polyline reference_geometry;  // [m] the full-resolution beam reference line, start to end
  Polyline reference_curve;     // [m] beam nodes: elements+1 points at equal arc length
  // Wall surfaces offset by +-thickness/2; "inner" is the side facing the nozzle axis (y = 0) for
  // upper/lower flaps, the right side of the reference direction for half = none.
  Polyline inner_wall, outer_wall;                 // [m], start to end
  std::vector<double> inner_wall_s, outer_wall_s;  // [m] arc length on reference_geometry of each
                                                   // wall point's foot
  Polyline solid_outline;  // [m] closed counter-clockwise outline of the thickness region
};

struct Joint {
  std::string name;
  std::string kind;  // rigid | revolute | revolute_spring | revolute_clearance | flexible |
                     // prescribed_rotation | prismatic
  std::string flap_a, end_a, flap_b, end_b;    // ends: "start" | "end"
  Point point = Point::Zero();                 // [m]
  double stiffness = 0.0;                      // revolute_spring [N m/rad]
  double damping = 0.0;                        // revolute_spring [N m s/rad]
  double inner_radius = 0.0;                   // revolute_clearance [m] (pin)
  double outer_radius = 0.0;                   // revolute_clearance [m] (bore)
  double contact_stiffness = 0.0;              // revolute_clearance [N/m]
  double friction = 0.0;                       // revolute_clearance [1]
  Matrix6 stiffness_matrix = Matrix6::Zero();  // flexible: [N/m] (1-3), [N m/rad] (4-6)
  std::string deformation_measure;             // flexible: "proposed" | "typical"
  /// flexible: lambda(sigma, p) and mu(sigma, p) of the proposed measures: "default", the seed's
  /// cases "1a" ... "4d", or "custom" with the polynomial terms below (model.md).
  std::string measure_functions = "default";
  Eigen::MatrixX3d lambda_terms,
      mu_terms;  // flexible, custom: rows (coefficient, power of sigma, power of |p|)
  Eigen::MatrixX2d rotation_table;  // prescribed_rotation: rows (time [s], angle [rad])
  Point axis = Point::Zero();       // prismatic: sliding direction (unit vector)
};

struct Support {
  std::string name;
  std::string flap, end;  // end: start | end
  std::string kind;       // clamp | pinned | sliding_clamp | sliding_pinned
  Point point = Point::Zero();
  Point axis = Point::Zero();  // sliding kinds: unit sliding direction; zero: the flap's direction
                               // at the end
  bool slides() const { return kind == "sliding_clamp" || kind == "sliding_pinned"; }
};

// One piece of the flow domain boundary; the pieces in order form the counter-clockwise loop.
struct DomainBoundary {
  std::string name;
  std::string kind;  // inflow | farfield | outflow | wall | slip_wall | symmetry
  std::string flap;  // walls of a flap: its name; else ""
  std::string side;  // walls of a flap: inner | outer | end; else ""
  Polyline points;   // [m], in loop direction (domain on the left)
};

struct DomainSettings {
  std::string kind = "nozzle";     // nozzle | channel | flatplate
  double plenum_length = 0.0;      // [m] nozzle: inflow face upstream of the first flap start
  double downstream_length = 0.0;  // [m] nozzle: outflow face downstream of the nozzle exit
  double farfield_height = 0.0;    // [m] nozzle: |y| of the far-field boundary; flatplate: top
  bool boattail = false;           // nozzle: the last flap of each half returns to the nacelle
  std::string wall_curve;          // channel: geometry curve of the upper wall
  double plate_length = 0.0;       // flatplate [m]
  double upstream_length = 0.0;    // flatplate [m] symmetry plane ahead of the plate
};

struct Domain {
  DomainSettings settings;
  std::vector<DomainBoundary> boundaries;  // counter-clockwise loop
};

struct FlowConditions {
  double nozzle_pressure_ratio = 1.0;   // [1] p0 / p_ambient
  double stagnation_temperature = 0.0;  // [K]
  double ambient_pressure = 0.0;        // [Pa]
  double ambient_temperature = 0.0;     // [K]
  double ambient_mach = 0.0;            // [1] external stream
  double exit_pressure_ratio = 0.0;     // [1] channel: p_exit / p0 (0: not used)
  double gamma = 1.4;                   // [1]
  double gas_constant = 287.05;         // [J/(kg K)]
  double prandtl = 0.72, turbulent_prandtl = 0.9;
  // spalart_allmaras | k_omega_sst | k_omega_sst_v | laminar | inviscid
  std::string turbulence = "spalart_allmaras";
  double reference_length = 0.0;                // [m] for the Reynolds number and y+ estimate
  double yplus_target = 0.0;                    // [1] 0: first_cell_height given
  double first_cell_height = 0.0;               // [m] resolved (given or from yplus_target)
  // [m] nu / u_tau of the flat-plate skin-friction estimate tfmb-input sizes the first cell with:
  // a cell height h has y+ = h / viscous_length. 0: not recorded (model files before 2.5).
  double viscous_length = 0.0;
};

struct ThermalSettings {
  std::string flow_wall = "adiabatic";              // adiabatic | isothermal
  double wall_temperature = 0.0;                    // [K] isothermal
  std::string solid_boundary = "wall_temperature";  // wall_temperature | convection |
                                                    // convection_radiation
  double emissivity = 0.0;                          // [1]
  double reference_temperature = 294.26;            // [K] stress-free temperature
};

struct MeshControls {
  double wall_size = 0.0;  // [m] cell length along walls
  double far_size = 0.0;   // [m] cell size at the far field
  double growth = 1.2;     // [1] boundary layer growth ratio
  int max_layers = 40;     // boundary layer layers (at most)
  double scale = 1.0;      // multiplies every size (coarse test meshes: > 1)
  int cells_along = 0, cells_across = 0, cells_upstream = 0;  // structured domains
  double leading_edge_spacing = 0.0;                          // [m] flatplate
  // Nozzle walls: at most 2 pi R / cells_per_circle along a wall of radius of curvature R, so
  // a tight throat arc is resolved like a circle of that many cells (0: off; model 2.2).
  int cells_per_circle = 0;
  // Nozzle walls: cells across each flap end face at least (the base behind a blunt trailing
  // edge: config1 at second-order SA with 2 gave an asymmetric base and h < 0 next to it, 10
  // resolved it).
  int end_cells = 2;
  int solid_cells_per_element = 4, solid_layers = 4;
};

struct AnalysisSettings {
  std::string kind = "oneway";             // oneway | twoway | structure | flow
  std::string time = "static";             // static | dynamic
  double end_time = 0.0, time_step = 0.0;  // [s] dynamic
  int load_steps = 10;
  int max_coupling_iterations = 20;
  double coupling_tolerance = 1e-4;      // [m] wall displacement change
  std::string convergence = "absolute";  // absolute | relative | residual-relative
  std::string acceleration = "aitken";   // constant | aitken | iqn-ils
  double relaxation = 0.5;               // [1]
};

struct Model : ReadFrom {
  std::string geometry = "planar";  // header: planar | axisymmetric
  std::string title;
  double depth = 1.0;  // [m]
  std::vector<Flap> flaps;
  std::vector<Joint> joints;
  std::vector<Support> supports;
  Domain domain;
  FlowConditions flow;
  ThermalSettings thermal;
  MeshControls mesh;
  AnalysisSettings analysis;

  const Flap* find_flap(const std::string& name) const { return find_named(flaps, name); }
};

// Writes model.h5 atomically (header, everything above, provenance); `creator` is the program
// and version, e.g. "tfmb-input 0.1.0".
void write_model(const Model& model, const std::filesystem::path& file, const std::string& creator,
                 const Provenance& provenance);
// Reads and validates a model file: schema, then the cross-references and per-kind requirements
// (BadInput naming the file and the object on any problem).
Model read_model(const std::filesystem::path& file);

}  // namespace tfmb::formats
