// The schemas of every file kind, version 1.0. Each kind's prose spec is formats/<kind>.md; the
// tables there are printed from here (tfmb-check --spec <kind>) and a test keeps them equal.
// Changing a layout: change it here, bump the version, update the spec, reader/writer and tests.
#include "tfmb/formats/schema.hpp"

namespace tfmb::formats {
namespace {

using h5::DType;

DatasetRule f64(std::string path, std::vector<std::string> shape, std::string units,
                std::string meaning, bool required = true) {
  return {std::move(path), DType::float64, std::move(shape), std::move(units), required, "", 0,
          std::move(meaning)};
}

DatasetRule i64(std::string path, std::vector<std::string> shape, std::string bound,
                std::string meaning, bool required = true, std::int64_t lower = 0) {
  return {std::move(path), DType::int64, std::move(shape), "1", required, std::move(bound), lower,
          std::move(meaning)};
}

DatasetRule str(std::string path, std::vector<std::string> shape, std::string meaning,
                bool required = true) {
  return {std::move(path), DType::string, std::move(shape), "1", required, "", 0,
          std::move(meaning)};
}

AttributeRule sattr(std::string object, std::string name, std::string meaning,
                    std::vector<std::string> allowed = {}, bool required = true) {
  AttributeRule rule;
  rule.object_path = std::move(object);
  rule.name = std::move(name);
  rule.type = AttrType::string;
  rule.required = required;
  rule.allowed = std::move(allowed);
  rule.meaning = std::move(meaning);
  return rule;
}

AttributeRule nattr(std::string object, std::string name, std::string units, std::string meaning,
                    std::optional<double> minimum = {}, std::optional<double> maximum = {},
                    bool required = true, AttrType type = AttrType::float64) {
  AttributeRule rule;
  rule.object_path = std::move(object);
  rule.name = std::move(name);
  rule.type = type;
  rule.required = required;
  rule.minimum = minimum;
  rule.maximum = maximum;
  rule.units = std::move(units);
  rule.meaning = std::move(meaning);
  return rule;
}

void add_root(Schema& s, bool geometric) {
  s.attributes.push_back(sattr("/", "format", "file kind", {s.format}));
  s.attributes.push_back(sattr("/", "format_version", "major.minor; readers refuse another major"));
  s.attributes.push_back(sattr("/", "creator", "program and version that wrote the file"));
  s.attributes.push_back(sattr("/", "created",
                               "UTC time of writing, or 'not recorded' (default, so that identical "
                               "runs give byte-identical files)"));
  if (geometric) {
    s.attributes.push_back(sattr("/", "geometry", "x along the nozzle axis, y transverse",
                                 {"planar", "axisymmetric"}));
    s.attributes.push_back(nattr("/", "depth", "m",
                                 "planar: the depth that per-unit-depth quantities refer to "
                                 "(normally 1); axisymmetric: 1",
                                 0.0, std::nullopt));
  }
}

void add_provenance(Schema& s) {
  s.attributes.push_back(sattr("/provenance", "command_line", "command that wrote the file", {}, false));
  s.attributes.push_back(sattr("/provenance", "settings", "resolved settings (TOML text)", {}, false));
  s.datasets.push_back(str("/provenance/input_files", {"K"}, "input files as given", false));
  s.datasets.push_back(str("/provenance/input_sha256", {"K"}, "SHA-256 of each input file", false));
}

void add_mesh(Schema& s) {
  s.mesh_bearing = true;
  s.datasets.push_back(f64("/mesh/points", {"N", "2"}, "m", "node coordinates x, y"));
  s.datasets.push_back(i64("/mesh/cells/triangle", {"Nt", "3"}, "N",
                           "0-based node ids, counter-clockwise; global cell id = row"));
  s.datasets.push_back(i64("/mesh/cells/quad", {"Nq", "4"}, "N",
                           "0-based node ids, counter-clockwise; global cell id = Nt + row"));
  s.datasets.push_back(i64("/mesh/topology_xdmf_mixed", {"*"}, "",
                           "derived: XDMF Mixed topology stream (4 = triangle, 5 = quad)", false));
  s.datasets.push_back(i64("/mesh/regions/*", {"*"}, "Nt+Nq", "cell ids of a physical region", false));
  s.datasets.push_back(i64("/mesh/boundaries/*/edges", {"*", "2"}, "N",
                           "boundary edges (node ids), ordered head to tail along the curve"));
  s.attributes.push_back(sattr("/mesh/boundaries/*", "kind", "boundary condition kind",
                               {"inflow", "farfield", "outflow", "wall", "slip_wall", "symmetry",
                                "axis", "solid_inner", "solid_outer", "solid_end"}));
  s.attributes.push_back(sattr("/mesh/boundaries/*", "flap", "flap a wall belongs to", {}, false));
  s.attributes.push_back(sattr("/mesh/boundaries/*", "side", "wetted side of the flap",
                               {"inner", "outer", "end"}, false));
}

Schema model() {
  Schema s{"model", "tfmb/model", 1, 0,
           "the analysis model: flaps as beams, sections, joints, supports, walls, flow domain, "
           "conditions",
           false, {}, {}};
  add_root(s, true);
  s.attributes.push_back(sattr("/flaps/*", "material", "material name in the material database"));
  s.attributes.push_back(nattr("/flaps/*", "thickness", "m", "wall thickness", 0.0));
  s.attributes.push_back(nattr("/flaps/*", "width", "m", "flap width (depth direction)", 0.0));
  s.attributes.push_back(sattr("/flaps/*", "half", "nozzle half", {"upper", "lower", "none"}));
  s.attributes.push_back(sattr("/joints/*", "kind", "joint kind",
                               {"rigid", "revolute", "revolute_spring", "revolute_clearance",
                                "flexible", "prescribed_rotation"}));
  s.attributes.push_back(sattr("/joints/*", "flap_a", "first flap"));
  s.attributes.push_back(sattr("/joints/*", "end_a", "end of the first flap", {"start", "end"}));
  s.attributes.push_back(sattr("/joints/*", "flap_b", "second flap"));
  s.attributes.push_back(sattr("/joints/*", "end_b", "end of the second flap", {"start", "end"}));
  s.attributes.push_back(sattr("/supports/*", "flap", "supported flap"));
  s.attributes.push_back(sattr("/supports/*", "end", "supported end", {"start", "end"}));
  s.attributes.push_back(sattr("/supports/*", "kind", "support kind", {"clamp", "pinned"}));
  s.attributes.push_back(sattr("/domain/boundaries/*", "kind", "boundary condition kind",
                               {"inflow", "farfield", "outflow", "wall", "slip_wall", "symmetry",
                                "axis"}));
  s.attributes.push_back(nattr("/conditions", "nozzle_pressure_ratio", "1",
                               "stagnation over ambient pressure", 1.0));
  s.attributes.push_back(nattr("/conditions", "stagnation_temperature", "K", "", 0.0));
  s.attributes.push_back(nattr("/conditions", "ambient_pressure", "Pa", "", 0.0));
  s.attributes.push_back(nattr("/conditions", "ambient_temperature", "K", "", 0.0));
  s.attributes.push_back(nattr("/conditions", "gamma", "1", "ratio of specific heats", 1.0, 2.0));
  s.attributes.push_back(nattr("/conditions", "gas_constant", "J/(kg K)", "", 0.0));
  s.datasets.push_back(f64("/flaps/*/reference_curve", {"nr", "2"}, "m",
                           "beam reference line, one row per beam node, start to end"));
  s.datasets.push_back(f64("/flaps/*/section_stiffness", {"6", "6"}, "*",
                           "6x6 sectional stiffness (axial, 2 shears, torsion, 2 bendings): N, N m^2"));
  s.datasets.push_back(f64("/flaps/*/section_mass", {"6", "6"}, "*",
                           "6x6 sectional mass: kg/m, kg m"));
  s.datasets.push_back(f64("/flaps/*/inner_wall", {"ni", "2"}, "m", "wetted inner surface"));
  s.datasets.push_back(f64("/flaps/*/outer_wall", {"no", "2"}, "m", "wetted outer surface"));
  s.datasets.push_back(f64("/joints/*/point", {"2"}, "m", "joint location"));
  s.datasets.push_back(f64("/joints/*/parameters", {"*"}, "*",
                           "kind-specific parameters (see model.md)", false));
  s.datasets.push_back(f64("/domain/boundaries/*/points", {"nb", "2"}, "m",
                           "flow domain boundary curve"));
  add_provenance(s);
  return s;
}

Schema flowmesh() {
  Schema s{"flowmesh", "tfmb/flowmesh", 1, 0,
           "mixed quad/triangle fluid mesh with tagged boundaries", true, {}, {}};
  add_root(s, true);
  add_mesh(s);
  s.attributes.push_back(nattr("/mesh", "min_angle", "deg", "quality report: smallest cell angle",
                               0.0, 180.0, false));
  s.attributes.push_back(nattr("/mesh", "max_aspect_ratio", "1", "quality report", 1.0,
                               std::nullopt, false));
  add_provenance(s);
  return s;
}

Schema solidmesh() {
  Schema s{"solidmesh", "tfmb/solidmesh", 1, 0,
           "mesh of the flap walls for heat conduction, linked to the beam elements", true, {}, {}};
  add_root(s, true);
  add_mesh(s);
  s.datasets.push_back(str("/link/flap_names", {"F"}, "flap names"));
  s.datasets.push_back(i64("/link/cell_flap", {"Nt+Nq"}, "F", "flap of each cell"));
  s.datasets.push_back(i64("/link/cell_element", {"Nt+Nq"}, "",
                           "beam element (within its flap) each cell belongs to"));
  s.datasets.push_back(f64("/link/point_thickness_coordinate", {"N"}, "m",
                           "signed distance from the beam reference line, positive towards the "
                           "outer surface"));
  add_provenance(s);
  return s;
}

Schema flow() {
  Schema s{"flow", "tfmb/flow", 1, 0,
           "flow solution: node fields, wall traces, integrated thrust and mass flow", true, {}, {}};
  add_root(s, true);
  add_mesh(s);
  s.datasets.push_back(f64("/fields/point/density", {"N"}, "kg/m^3", ""));
  s.datasets.push_back(f64("/fields/point/velocity", {"N", "3"}, "m/s", "u, v, 0"));
  s.datasets.push_back(f64("/fields/point/pressure", {"N"}, "Pa", "static pressure"));
  s.datasets.push_back(f64("/fields/point/temperature", {"N"}, "K", "static temperature"));
  s.datasets.push_back(f64("/fields/point/mach", {"N"}, "1", ""));
  s.datasets.push_back(f64("/fields/point/nu_tilde", {"N"}, "m^2/s", "Spalart-Allmaras variable", false));
  s.datasets.push_back(f64("/fields/point/eddy_viscosity", {"N"}, "Pa s", "", false));
  s.datasets.push_back(f64("/fields/point/wall_distance", {"N"}, "m", "", false));
  s.datasets.push_back(i64("/walls/*/node", {"n"}, "N", "mesh node of each trace point"));
  s.datasets.push_back(f64("/walls/*/s", {"n"}, "m", "arc length along the wall"));
  s.datasets.push_back(f64("/walls/*/x", {"n"}, "m", ""));
  s.datasets.push_back(f64("/walls/*/y", {"n"}, "m", ""));
  s.datasets.push_back(f64("/walls/*/pressure", {"n"}, "Pa", "wall static pressure"));
  s.datasets.push_back(f64("/walls/*/temperature", {"n"}, "K", "wall temperature"));
  s.datasets.push_back(f64("/walls/*/wall_shear", {"n"}, "Pa",
                           "wall shear stress along the wall direction of increasing s"));
  s.datasets.push_back(f64("/walls/*/heat_flux", {"n"}, "W/m^2", "into the wall"));
  s.datasets.push_back(f64("/walls/*/heat_transfer_coefficient", {"n"}, "W/(m^2 K)", "", false));
  s.datasets.push_back(f64("/walls/*/adiabatic_wall_temperature", {"n"}, "K", "", false));
  s.attributes.push_back(nattr("/integrals", "mass_flow", "kg/(s m)", "per unit depth (planar)"));
  s.attributes.push_back(nattr("/integrals", "thrust_x", "N/m", "per unit depth (planar)"));
  s.attributes.push_back(nattr("/integrals", "thrust_y", "N/m", "per unit depth (planar)"));
  s.attributes.push_back(nattr("/integrals", "thrust_angle", "deg", "atan2(thrust_y, thrust_x)"));
  s.attributes.push_back(nattr("/integrals", "discharge_coefficient", "1",
                               "mass flow over ideal (isentropic, sonic throat) mass flow", 0.0));
  s.attributes.push_back(nattr("/conditions", "stagnation_pressure", "Pa", "", 0.0));
  s.attributes.push_back(nattr("/conditions", "stagnation_temperature", "K", "", 0.0));
  s.attributes.push_back(nattr("/conditions", "ambient_pressure", "Pa", "", 0.0));
  s.attributes.push_back(nattr("/conditions", "gamma", "1", "", 1.0, 2.0));
  s.attributes.push_back(nattr("/conditions", "gas_constant", "J/(kg K)", "", 0.0));
  s.attributes.push_back(nattr("/convergence", "converged", "1", "1 if the criterion was met",
                               0.0, 1.0, true, AttrType::int64));
  s.attributes.push_back(sattr("/convergence", "criterion", "convergence criterion used"));
  s.attributes.push_back(nattr("/convergence", "iterations", "1", "nonlinear iterations", 0.0,
                               std::nullopt, true, AttrType::int64));
  s.datasets.push_back(f64("/convergence/residual_history", {"I", "*"}, "1",
                           "per iteration: L2 residual of each equation relative to the first"));
  add_provenance(s);
  return s;
}

Schema thermal() {
  Schema s{"thermal", "tfmb/thermal", 1, 0,
           "solid temperatures and per beam element mean temperature and through-thickness "
           "difference",
           true, {}, {}};
  add_root(s, true);
  add_mesh(s);
  s.datasets.push_back(f64("/fields/point/temperature", {"N"}, "K", ""));
  s.datasets.push_back(f64("/fields/point/heat_flux", {"N", "3"}, "W/m^2", "", false));
  s.datasets.push_back(f64("/beam/*/mean_temperature", {"ne"}, "K", "area mean per beam element"));
  s.datasets.push_back(f64("/beam/*/delta_temperature", {"ne"}, "K",
                           "outer minus inner surface temperature of the linear fit through the "
                           "thickness"));
  add_provenance(s);
  return s;
}

Schema material_db() {
  Schema s{"material-db", "tfmb/material-db", 1, 0,
           "tabulated material properties against temperature, with sources", false, {}, {}};
  add_root(s, false);
  s.attributes.push_back(sattr("/materials/*", "description", "alloy and condition"));
  s.attributes.push_back(nattr("/materials/*", "reference_temperature", "K",
                               "reference of the mean thermal expansion coefficient", 0.0));
  s.attributes.push_back(sattr("/materials/*/*", "source", "where the values come from"));
  s.attributes.push_back(sattr("/materials/*/*", "exactness", "trust level",
                               {"exact_table", "transcription", "digitised", "derived"}));
  s.datasets.push_back(f64("/materials/*/*/temperature", {"n"}, "K", "strictly increasing"));
  s.datasets.push_back(f64("/materials/*/*/value", {"n"}, "*", "property at each temperature"));
  add_provenance(s);
  return s;
}

Schema materials() {
  Schema s{"materials", "tfmb/materials", 1, 0,
           "per beam element properties at its temperature, section stiffness, thermal strains",
           false, {}, {}};
  add_root(s, true);
  s.attributes.push_back(sattr("/flaps/*", "material", "material name"));
  const std::vector<std::pair<std::string, std::string>> per_element = {
      {"temperature", "K"},       {"youngs_modulus", "Pa"},   {"shear_modulus", "Pa"},
      {"poisson_ratio", "1"},     {"thermal_expansion", "1/K"}, {"yield_strength", "Pa"},
      {"ultimate_strength", "Pa"}, {"allowable_strain", "1"},  {"thermal_strain", "1"},
      {"thermal_curvature", "1/m"}};
  for (const auto& [name, units] : per_element) {
    s.datasets.push_back(f64("/flaps/*/" + name, {"ne"}, units, "per beam element"));
  }
  s.datasets.push_back(f64("/flaps/*/section_stiffness", {"ne", "6", "6"}, "*", "N, N m^2"));
  s.datasets.push_back(f64("/flaps/*/section_mass", {"ne", "6", "6"}, "*", "kg/m, kg m"));
  s.datasets.push_back(i64("/flaps/*/clamped", {"ne"}, "2",
                           "1 if the temperature was outside the table and clamped"));
  add_provenance(s);
  return s;
}

Schema loads() {
  Schema s{"loads", "tfmb/loads", 1, 0, "distributed and nodal beam loads from the wall traces",
           false, {}, {}};
  add_root(s, true);
  s.attributes.push_back(sattr("/", "method", "mapping method", {"linear", "conservative"}));
  s.attributes.push_back(nattr("/flaps/*", "total_force", "N", "integral of the traces (x, y, z)",
                               std::nullopt, std::nullopt, true, AttrType::float64_vector));
  s.attributes.push_back(nattr("/flaps/*", "total_moment", "N m", "about the origin (x, y, z)",
                               std::nullopt, std::nullopt, true, AttrType::float64_vector));
  s.datasets.push_back(f64("/flaps/*/s", {"nn"}, "m", "arc length of each beam node"));
  s.datasets.push_back(f64("/flaps/*/distributed_force", {"nn", "3"}, "N/m",
                           "force per unit beam length at each node, over the flap width"));
  s.datasets.push_back(f64("/flaps/*/distributed_moment", {"nn", "3"}, "N",
                           "moment per unit beam length at each node"));
  s.datasets.push_back(f64("/flaps/*/nodal_force", {"nn", "3"}, "N", "consistent nodal forces"));
  s.datasets.push_back(f64("/flaps/*/nodal_moment", {"nn", "3"}, "N m", "consistent nodal moments"));
  add_provenance(s);
  return s;
}

Schema walldisp() {
  Schema s{"walldisp", "tfmb/walldisp", 1, 0,
           "displacement of every wall point from the beam solution", false, {}, {}};
  add_root(s, true);
  s.datasets.push_back(f64("/walls/*/x0", {"n", "2"}, "m", "undeformed wall point"));
  s.datasets.push_back(f64("/walls/*/displacement", {"n", "2"}, "m", "displacement"));
  add_provenance(s);
  return s;
}

Schema structure() {
  Schema s{"structure", "tfmb/structure", 1, 0,
           "beam solution: displacements, rotations, sectional strains and forces, joints",
           false, {}, {}};
  add_root(s, true);
  s.attributes.push_back(sattr("/", "analysis", "analysis kind", {"static", "dynamic", "modal"}));
  s.attributes.push_back(nattr("/", "converged", "1", "1 if the solution converged", 0.0, 1.0,
                               true, AttrType::int64));
  s.datasets.push_back(f64("/beam/points", {"N", "3"}, "m", "beam node reference positions"));
  s.datasets.push_back(i64("/beam/segments", {"E", "2"}, "N",
                           "display segments between nodes (an element of order p gives p)"));
  s.datasets.push_back(f64("/fields/point/displacement", {"N", "3"}, "m", ""));
  s.datasets.push_back(f64("/fields/point/rotation", {"N", "3"}, "1",
                           "Wiener-Milenkovic rotation parameters"));
  s.datasets.push_back(f64("/fields/cell/sectional_strain", {"E", "6"}, "*",
                           "axial, 2 shear, torsion, 2 curvatures: 1, 1/m"));
  s.datasets.push_back(f64("/fields/cell/sectional_force", {"E", "6"}, "*",
                           "axial, 2 shear forces, torsion, 2 bending moments: N, N m"));
  s.datasets.push_back(i64("/flaps/*/nodes", {"nn"}, "N", "beam nodes of the flap, in order"));
  s.datasets.push_back(i64("/flaps/*/segments", {"ns"}, "E", "segments of the flap, in order"));
  s.datasets.push_back(f64("/joints/*/reaction", {"6"}, "*", "force (N) and moment (N m)"));
  s.datasets.push_back(f64("/joints/*/relative_rotation", {"*"}, "rad", "", false));
  s.datasets.push_back(f64("/joints/*/contact_force", {"*"}, "N", "clearance joints", false));
  s.datasets.push_back(f64("/joints/*/gap", {"*"}, "m", "clearance joints", false));
  s.datasets.push_back(f64("/history/time", {"T"}, "s", "dynamic analysis", false));
  s.datasets.push_back(f64("/history/displacement", {"T", "N", "3"}, "m", "", false));
  add_provenance(s);
  return s;
}

Schema strain() {
  Schema s{"strain", "tfmb/strain", 1, 0,
           "mechanical, thermal and total fibre strains and margins of safety", false, {}, {}};
  add_root(s, true);
  s.attributes.push_back(nattr("/", "worst_margin_total", "1", "smallest total-strain margin"));
  s.attributes.push_back(sattr("/", "worst_flap", "flap of the smallest margin"));
  const std::vector<std::pair<std::string, std::string>> per_element = {
      {"s", "m"},
      {"mechanical_inner", "1"},
      {"mechanical_outer", "1"},
      {"thermal", "1"},
      {"total_inner", "1"},
      {"total_outer", "1"},
      {"allowable", "1"},
      {"margin_mechanical", "1"},
      {"margin_thermal", "1"},
      {"margin_total", "1"}};
  for (const auto& [name, units] : per_element) {
    s.datasets.push_back(f64("/flaps/*/" + name, {"ne"}, units, "per beam element"));
  }
  add_provenance(s);
  return s;
}

}  // namespace

const std::vector<Schema>& all_schemas() {
  static const std::vector<Schema> schemas = {model(),     flowmesh(),  solidmesh(), flow(),
                                              thermal(),   material_db(), materials(), loads(),
                                              walldisp(),  structure(), strain()};
  return schemas;
}

}  // namespace tfmb::formats
