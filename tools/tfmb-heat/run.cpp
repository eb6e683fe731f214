#include "tfmb-heat/run.hpp"

#include "tfmb-heat/beam_outputs.hpp"
#include "tfmb-heat/boundary_geometry.hpp"
#include "tfmb-heat/heat_flux.hpp"
#include "tfmb-heat/steady_solver.hpp"
#include "tfmb-heat/wall_mapping.hpp"
#include "tfmb/common/errors.hpp"
#include "tfmb/common/h5.hpp"
#include "tfmb/common/log.hpp"
#include "tfmb/common/options.hpp"
#include "tfmb/formats/files.hpp"
#include "tfmb/formats/flow.hpp"
#include "tfmb/formats/material_db.hpp"
#include "tfmb/formats/model.hpp"
#include "tfmb/formats/schema.hpp"
#include "tfmb/formats/solidmesh.hpp"
#include "tfmb/formats/thermal.hpp"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>

namespace tfmb::heat {
namespace {

SolidMesh to_solid_mesh(const formats::Mesh& in) {
  SolidMesh mesh;
  mesh.points = in.points;
  if (in.triangles.rows() > 0) {
    ElementBlock block{ElementType::tri3, {}};
    block.nodes.assign(in.triangles.data(), in.triangles.data() + in.triangles.size());
    mesh.blocks.push_back(std::move(block));
  }
  if (in.quads.rows() > 0) {
    ElementBlock block{ElementType::quad4, {}};
    block.nodes.assign(in.quads.data(), in.quads.data() + in.quads.size());
    mesh.blocks.push_back(std::move(block));
  }
  for (const auto& [name, boundary] : in.boundaries) {
    BoundaryCurve curve;
    curve.nodes.assign(boundary.edges.data(), boundary.edges.data() + boundary.edges.size());
    mesh.boundaries[name] = std::move(curve);
  }
  return mesh;
}

// A property table of a database material as the conduction solver takes it.
PropertyTable read_property(const formats::MaterialDatabase& db,
                            const formats::DatabaseMaterial& material,
                            const std::string& property) {
  const std::string group = "/materials/" + material.name + "/" + property;
  const auto table = material.properties.find(property);
  if (table == material.properties.end())
    db.fail(group, "missing: material '" + material.name + "' has no " + property + " table");
  try {
    return PropertyTable(table->second.temperature, table->second.value);
  } catch (const std::invalid_argument& error) {
    db.fail(group, error.what());
  }
}

// Steady runs need only the conductivity; density and specific heat are read when present.
PropertyTable read_optional_property(const formats::MaterialDatabase& db,
                                     const formats::DatabaseMaterial& material,
                                     const std::string& property) {
  if (!material.properties.count(property))
    return {};
  return read_property(db, material, property);
}

struct FlowWall {
  std::string name;
  std::string flap, side;
};

// The trace dataset of a flow wall, or a BadInput naming what is missing and why it is needed.
std::vector<double> trace_values(const formats::Flow& flow, const std::string& wall,
                                 const std::string& dataset, const std::string& needed_by) {
  const std::string path = "/walls/" + wall + "/" + dataset;
  const formats::FlowWall* trace = flow.find_wall(wall);
  const std::vector<double>* values = nullptr;
  if (trace) {
    if (dataset == "x")
      values = &trace->x;
    if (dataset == "y")
      values = &trace->y;
    if (dataset == "temperature")
      values = &trace->temperature;
    if (dataset == "heat_transfer_coefficient")
      values = &trace->heat_transfer_coefficient;
    if (dataset == "adiabatic_wall_temperature")
      values = &trace->adiabatic_wall_temperature;
  }
  if (!values || values->empty())
    flow.fail(path, "missing, needed by " + needed_by);
  return *values;
}

// --- inputs --------------------------------------------------------------------------------------

// The solid side of the stage: the mesh of solidmesh.h5 and its link to the beam elements. The
// file stays open for the errors the later phases report against it.
struct SolidInput {
  explicit SolidInput(const std::filesystem::path& path);

  formats::SolidMesh file;  // as read: its mesh is written back to thermal.h5
  const formats::Header& header;
  const formats::Mesh& mesh_in;
  SolidMesh mesh;  // the conduction mesh (cell materials set by assign_materials)
  std::size_t cell_count = 0;
  const std::vector<std::string>& flap_names;
  const std::vector<std::int64_t>& cell_flap;     // per cell its flap
  const std::vector<std::int64_t>& cell_element;  // per cell its beam element
  Eigen::VectorXd node_z;  // [m] per node the through-thickness coordinate
};

SolidInput::SolidInput(const std::filesystem::path& path)
    : file(formats::read_solidmesh(path)),
      header(file.header),
      mesh_in(file.mesh),
      mesh(to_solid_mesh(mesh_in)),
      cell_count(static_cast<std::size_t>(mesh_in.cell_count())),
      flap_names(file.flap_names),
      cell_flap(file.cell_flap),
      cell_element(file.cell_element),
      node_z(Eigen::Map<const Eigen::VectorXd>(
          file.point_thickness_coordinate.data(),
          static_cast<Eigen::Index>(file.point_thickness_coordinate.size()))) {}

// The model's flap of a flap of the solid mesh; both files must describe the same flaps.
const formats::Flap& model_flap(const formats::Model& model, const std::string& name) {
  const formats::Flap* flap = model.find_flap(name);
  if (!flap) {
    model.fail("/flaps/" + name,
               "missing: the solid mesh has flap '" + name + "' but the model does not");
  }
  return *flap;
}

// The conductivity (and, where present, density and specific heat) of every flap's material from
// the database, one entry per distinct material; every cell gets its flap's.
void assign_materials(const Options& options, const formats::Model& model, SolidInput& solid,
                      ThermalProblem& problem) {
  const formats::MaterialDatabase db = formats::read_material_db(options.material_db);
  std::map<std::string, int> material_index;
  std::vector<int> flap_material(solid.flap_names.size());
  for (std::size_t f = 0; f < solid.flap_names.size(); ++f) {
    const std::string named = model_flap(model, solid.flap_names[f]).material;
    // The same name-or-alias rule as tfmb-matmap's: formats::MaterialDatabase::find.
    const formats::DatabaseMaterial* entry = db.find(named);
    if (!entry) {
      db.fail("/materials", "no material or alias '" + named + "' (flap '" + solid.flap_names[f] +
                                "' of " + options.model.string() + ")");
    }
    const std::string& material = entry->name;
    if (!material_index.count(material)) {
      material_index[material] = static_cast<int>(problem.materials.size());
      problem.materials.push_back({material, read_property(db, *entry, "conductivity"),
                                   read_optional_property(db, *entry, "density"),
                                   read_optional_property(db, *entry, "specific_heat")});
      try {
        validate_material(problem.materials.back(), false);
      } catch (const std::invalid_argument& error) {
        db.fail("/materials/" + material + "/conductivity", error.what());
      }
    }
    flap_material[f] = material_index[material];
  }
  solid.mesh.cell_material.resize(solid.cell_count);
  for (std::size_t c = 0; c < solid.cell_count; ++c)
    solid.mesh.cell_material[c] = flap_material[static_cast<std::size_t>(solid.cell_flap[c])];
}

// The walls of flow.h5 that carry traces, with the flap and side their mesh boundary names.
std::vector<FlowWall> traced_flow_walls(const formats::Flow& flow) {
  std::vector<FlowWall> flow_walls;
  for (const formats::FlowWall& wall : flow.walls) {
    const auto it = flow.mesh.boundaries.find(wall.name);
    if (it == flow.mesh.boundaries.end())
      continue;
    flow_walls.push_back({wall.name, it->second.flap, it->second.side});
  }
  return flow_walls;
}

// --- boundary conditions -------------------------------------------------------------------------

// What the wall conditions are built from (shared by the phase's helpers).
struct WallConditionInputs {
  const Options& options;
  const formats::ThermalSettings& thermal;
  const SolidMesh& mesh;
  const formats::Flow& flow;
  std::string needed_by;  // the model setting that asks for the traces, for error messages
};

double longest_boundary_edge(const SolidMesh& mesh) {
  double max_edge = 0.0;
  for (const auto& [name, curve] : mesh.boundaries) {
    for (std::size_t e = 0; e < curve.size(); ++e) {
      const auto edge = curve.edge(e);
      max_edge = std::max(max_edge, (mesh.points.row(edge[0]) - mesh.points.row(edge[1])).norm());
    }
  }
  return max_edge;
}

// The condition of a solid wall with a flow trace: the flow's wall temperature, or convection
// with its h and T_aw, each trace projected onto the solid wall (wall_mapping.hpp). Appends the
// trace's temperatures to `trace_temperatures`.
BoundarySpec traced_wall_condition(const WallConditionInputs& in, const std::string& name,
                                   const FlowWall& match, std::vector<double>& trace_temperatures) {
  const auto& curve = in.mesh.boundaries.at(name);
  const auto x = trace_values(in.flow, match.name, "x", in.needed_by);
  const auto y = trace_values(in.flow, match.name, "y", in.needed_by);
  // A trace point further than a tenth of the wall from it belongs to another wall.
  const double max_distance = 0.1 * boundary_length(in.mesh, curve);
  auto mapped = [&](const std::string& dataset) {
    const auto values = trace_values(in.flow, match.name, dataset, in.needed_by);
    try {
      return map_trace_to_boundary(
          in.mesh, curve, x, y, values,
          in.options.flow.string() + ": /walls/" + match.name + "/" + dataset, max_distance);
    } catch (const std::invalid_argument& error) {
      throw BadInput(error.what());
    }
  };
  const bool imposed = in.thermal.solid_boundary == "wall_temperature";
  const auto values = trace_values(
      in.flow, match.name, imposed ? "temperature" : "adiabatic_wall_temperature", in.needed_by);
  trace_temperatures.insert(trace_temperatures.end(), values.begin(), values.end());
  if (imposed)
    return {name, ImposedTemperature{mapped("temperature")}};
  return {name,
          Convection{mapped("heat_transfer_coefficient"), mapped("adiabatic_wall_temperature")}};
}

// A side facing a closed cavity (e.g. the inner side of an external flap) has no trace and is
// taken adiabatic; a flap the flow touches nowhere is an error (wrong flow file?).
void accept_untraced_wall(const WallConditionInputs& in, const std::vector<FlowWall>& flow_walls,
                          const std::string& name, const formats::Boundary& boundary,
                          const std::string& side, const Logger& log) {
  bool flap_wetted = false;
  for (const auto& wall : flow_walls)
    flap_wetted |= wall.flap == boundary.flap;
  if (!flap_wetted) {
    in.flow.fail("/walls", "no wall trace for flap '" + boundary.flap +
                               "' on any side, needed by solid wall '" + name + "' of " +
                               in.options.solid_mesh.string());
  }
  const bool radiates = in.thermal.solid_boundary == "convection_radiation" && side == "outer";
  log.warn("solid wall '" + name + "': no flow trace on the " + side + " side, adiabatic" +
           std::string(radiates ? " plus radiation" : ""));
}

// Conditions of the solid_inner and solid_outer walls from the flow wall of the same flap and
// side (run.hpp), plus radiation of the outer walls where the model asks for it. Returns the
// temperatures of the traces used.
std::vector<double> wall_boundary_conditions(const WallConditionInputs& in,
                                             const formats::Mesh& solid_in,
                                             const std::vector<FlowWall>& flow_walls,
                                             ThermalProblem& problem, const Logger& log) {
  std::vector<double> trace_temperatures;
  for (const auto& [name, boundary] : solid_in.boundaries) {
    if (boundary.kind != "solid_inner" && boundary.kind != "solid_outer")
      continue;
    const std::string side = boundary.kind == "solid_inner" ? "inner" : "outer";
    const FlowWall* match = nullptr;
    for (const auto& wall : flow_walls) {
      if (wall.flap == boundary.flap && wall.side == side)
        match = &wall;
    }
    if (!match) {
      accept_untraced_wall(in, flow_walls, name, boundary, side, log);
    } else {
      problem.boundary_conditions.push_back(
          traced_wall_condition(in, name, *match, trace_temperatures));
      log.verbose("solid wall '" + name + "' <- flow wall '" + match->name + "'");
    }
    if (in.thermal.solid_boundary == "convection_radiation" && side == "outer") {
      problem.boundary_conditions.push_back(
          {name, Radiation{in.thermal.emissivity, in.options.environment_temperature}});
    }
  }
  return trace_temperatures;
}

// --- joint contacts ------------------------------------------------------------------------------

Eigen::Vector2d curve_centroid(const SolidMesh& mesh, const std::string& name) {
  const auto& curve = mesh.boundaries.at(name);
  Eigen::Vector2d c = Eigen::Vector2d::Zero();
  for (auto node : curve.nodes)
    c += mesh.points.row(node).transpose();
  return Eigen::Vector2d(c / static_cast<double>(curve.nodes.size()));
}

// Gap-conductance contacts (run.hpp): each joint couples the closest pair (by centroid) of end
// walls of its two flaps; a joint whose flaps have no end walls (a continuous wall) none.
void joint_contacts(const Options& options, const formats::Model& model, const SolidInput& solid,
                    ThermalProblem& problem, const Logger& log) {
  if (!(options.joint_conductance > 0.0))
    return;
  for (const formats::Joint& model_joint : model.joints) {
    const std::string& joint = model_joint.name;
    const std::string& flap_a = model_joint.flap_a;
    const std::string& flap_b = model_joint.flap_b;
    double best = std::numeric_limits<double>::infinity();
    std::string end_a, end_b;
    for (const auto& [name_a, a] : solid.mesh_in.boundaries) {
      if (a.kind != "solid_end" || a.flap != flap_a)
        continue;
      for (const auto& [name_b, b] : solid.mesh_in.boundaries) {
        if (b.kind != "solid_end" || b.flap != flap_b)
          continue;
        const double distance =
            (curve_centroid(solid.mesh, name_a) - curve_centroid(solid.mesh, name_b)).norm();
        if (distance < best)
          best = distance, end_a = name_a, end_b = name_b;
      }
    }
    if (end_a.empty()) {
      log.warn("joint '" + joint + "': no solid_end walls of flaps '" + flap_a + "' and '" +
               flap_b + "' in the solid mesh (continuous wall?); no joint contact");
      continue;
    }
    problem.contacts.push_back({end_a, end_b, options.joint_conductance});
    log.verbose("joint '" + joint + "': contact '" + end_a + "' - '" + end_b + "'");
  }
}

// --- solve ---------------------------------------------------------------------------------------

// Newton starts from the mean temperature of the flow traces the walls took; a solid mesh no
// trace reaches is an error.
double initial_temperature(const std::vector<double>& trace_temperatures, const formats::Flow& flow,
                           const Options& options) {
  if (trace_temperatures.empty()) {
    flow.fail("/walls",
              "no wall trace matches a solid_inner wall of " + options.solid_mesh.string());
  }
  double initial = 0.0;
  for (double t : trace_temperatures)
    initial += t;
  return initial / static_cast<double>(trace_temperatures.size());
}

// The steady nonlinear conduction solve (steady_solver.hpp); logs Newton's history and the heat
// into the solid through every wall. Newton's iterations against their limit show as a progress
// line (Newton stops once converged, so the time left is an upper bound), as tfmb-flow's.
SteadyResult solve_conduction(const ThermalProblem& problem, double initial,
                              const NewtonSettings& newton, const Logger& log) {
  SteadyResult result;
  std::map<std::string, double> rates;
  try {
    Progress progress(log, "Newton", static_cast<std::size_t>(std::max(newton.max_iterations, 0)),
                      {.unit = "iterations", .total_is_limit = true});
    NewtonSettings settings = newton;
    settings.on_iteration = [&progress](int iteration, double, double) {
      progress.update(static_cast<std::size_t>(iteration));
    };
    result = solve_steady(problem, initial, settings);
    progress.finish();
    const Assembler assembler(problem, false);
    rates = assembler.boundary_heat_rates(assembler.to_dofs(result.temperature), {});
  } catch (const std::invalid_argument& error) {
    throw BadInput(error.what());
  }
  for (std::size_t i = 0; i < result.newton.max_update.size(); ++i) {
    std::ostringstream line;
    line << "Newton " << i + 1 << ": residual " << result.newton.residual_norm[i]
         << " W/m, largest update " << result.newton.max_update[i] << " K";
    log.info(line.str());
  }
  for (const auto& [name, rate] : rates) {
    std::ostringstream line;
    line << "heat into the solid through '" << name << "': " << rate << " W/m";
    log.verbose(line.str());
  }
  return result;
}

// --- per beam element outputs --------------------------------------------------------------------

// The beam elements' temperatures (beam_outputs.hpp), numbered flap after flap: the elements of
// flap f are offsets[f] .. offsets[f + 1] - 1.
struct BeamElementTemperatures {
  std::vector<std::int64_t> offsets;
  BeamThermalOutputs outputs;
};

BeamElementTemperatures beam_element_outputs(const formats::Model& model, const SolidInput& solid,
                                             const Eigen::VectorXd& temperature) {
  const std::size_t flaps = solid.flap_names.size();
  std::vector<std::int64_t> flap_elements(flaps);
  for (std::size_t f = 0; f < flaps; ++f)
    flap_elements[f] = model_flap(model, solid.flap_names[f]).elements;
  BeamElementTemperatures beam;
  beam.offsets.assign(flaps + 1, 0);
  for (std::size_t f = 0; f < flaps; ++f)
    beam.offsets[f + 1] = beam.offsets[f] + flap_elements[f];
  std::vector<std::int64_t> cell_to_beam(solid.cell_count);
  for (std::size_t c = 0; c < solid.cell_count; ++c) {
    const auto f = static_cast<std::size_t>(solid.cell_flap[c]);
    if (solid.cell_element[c] >= flap_elements[f]) {
      solid.file.fail("/link/cell_element", "cell " + std::to_string(c) + " maps to element " +
                                                std::to_string(solid.cell_element[c]) +
                                                " of flap '" + solid.flap_names[f] +
                                                "', which has " + std::to_string(flap_elements[f]) +
                                                " elements in the model");
    }
    cell_to_beam[c] = beam.offsets[f] + solid.cell_element[c];
  }
  try {
    beam.outputs = beam_element_temperatures(solid.mesh, temperature, cell_to_beam, solid.node_z,
                                             static_cast<std::size_t>(beam.offsets.back()));
  } catch (const std::invalid_argument& error) {
    solid.file.fail("/link", error.what());
  }
  return beam;
}

// --- output --------------------------------------------------------------------------------------

std::vector<double> slice(const std::vector<double>& values, std::int64_t begin, std::int64_t end) {
  return std::vector<double>(values.begin() + static_cast<std::ptrdiff_t>(begin),
                             values.begin() + static_cast<std::ptrdiff_t>(end));
}

// thermal.h5 (formats/thermal): the solid mesh with nodal temperature and heat flux, the beam
// elements' temperatures per flap, Newton's convergence and the provenance; then its XDMF sidecar.
void write_thermal(const Options& options, const formats::ThermalSettings& thermal,
                   const SolidInput& solid, const SteadyResult& result,
                   const Eigen::Matrix<double, Eigen::Dynamic, 2, Eigen::RowMajor>& flux,
                   const BeamElementTemperatures& beam) {
  formats::Thermal out;
  out.header.creator = "tfmb-heat " + std::string(TFMB_HEAT_VERSION);
  out.header.geometry = solid.header.geometry;
  out.header.depth = solid.header.depth;
  out.mesh = solid.mesh_in;
  out.temperature.assign(result.temperature.data(),
                         result.temperature.data() + result.temperature.size());
  out.heat_flux = h5::MatrixXdR::Zero(flux.rows(), 3);
  out.heat_flux.leftCols(2) = flux;
  for (std::size_t f = 0; f < solid.flap_names.size(); ++f) {
    const std::int64_t begin = beam.offsets[f], end = beam.offsets[f + 1];
    out.beam.push_back({solid.flap_names[f], slice(beam.outputs.mean_temperature, begin, end),
                        slice(beam.outputs.temperature_difference, begin, end)});
  }
  out.converged = result.newton.converged;
  out.iterations = result.newton.iterations;
  out.criterion = "largest Newton temperature update below " +
                  std::to_string(options.newton.temperature_tolerance) + " K";
  formats::Provenance provenance;
  provenance.command_line = options.command_line;
  // Every option as given (declared once in main.cpp), then what the model resolved.
  provenance.settings = options.settings_toml + "\n[resolved]\nsolid_boundary = " +
                        cli::toml_string(thermal.solid_boundary) +
                        "\nemissivity = " + cli::toml_float(thermal.emissivity) + "\n";
  provenance.inputs = {options.solid_mesh, options.flow, options.model, options.material_db};
  formats::write_thermal(options.output, out, provenance);
}

// The summary line; a result Newton did not converge to is written (flagged) and then reported
// as NotConverged (exit 1).
void report_result(const Options& options, const SolidMesh& mesh, const SteadyResult& result,
                   double seconds, const Logger& log) {
  std::ostringstream summary;
  summary << mesh.node_count() << " nodes, " << result.newton.iterations << " Newton iterations, T "
          << result.temperature.minCoeff() << " .. " << result.temperature.maxCoeff() << " K, "
          << seconds << " s -> " << options.output.string();
  if (!result.newton.converged) {
    throw NotConverged("Newton did not converge in " +
                       std::to_string(options.newton.max_iterations) +
                       " iterations (result written, flagged in /convergence): " + summary.str());
  }
  log.summary(summary.str());
}

}  // namespace

// The phases, in the order of the sections above: inputs (solid mesh, model, materials, flow
// walls), boundary conditions from the flow wall traces, joint contacts, the solve, the per beam
// element outputs, thermal.h5.
int run(const Options& options, const Logger& log) {
  const auto start = std::chrono::steady_clock::now();
  SolidInput solid(options.solid_mesh);
  const formats::Model model = formats::read_model(options.model);
  ThermalProblem problem;
  problem.mesh = &solid.mesh;
  assign_materials(options, model, solid, problem);
  const formats::Flow flow = formats::read_flow(options.flow);
  const std::vector<FlowWall> flow_walls = traced_flow_walls(flow);

  // Flow and solid walls are discretised differently: allow half a solid edge at the wall ends.
  problem.trace_tolerance = 0.5 * longest_boundary_edge(solid.mesh);
  const WallConditionInputs walls{
      options, model.thermal, solid.mesh, flow,
      options.model.string() + ": /thermal@solid_boundary = " + model.thermal.solid_boundary};
  const auto trace_temperatures =
      wall_boundary_conditions(walls, solid.mesh_in, flow_walls, problem, log);
  joint_contacts(options, model, solid, problem, log);

  const double initial = initial_temperature(trace_temperatures, flow, options);
  const SteadyResult result = solve_conduction(problem, initial, options.newton, log);
  const BeamElementTemperatures beam = beam_element_outputs(model, solid, result.temperature);
  const auto flux = nodal_heat_flux(problem, result.temperature);
  write_thermal(options, model.thermal, solid, result, flux, beam);

  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  report_result(options, solid.mesh, result, seconds, log);
  return 0;
}

}  // namespace tfmb::heat
