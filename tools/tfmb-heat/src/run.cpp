#include "tfmb/heat/run.hpp"

#include "tfmb/common/errors.hpp"
#include "tfmb/common/h5.hpp"
#include "tfmb/common/log.hpp"
#include "tfmb/formats/files.hpp"
#include "tfmb/formats/model.hpp"
#include "tfmb/formats/schema.hpp"
#include "tfmb/heat/beam_outputs.hpp"
#include "tfmb/heat/boundary_geometry.hpp"
#include "tfmb/heat/heat_flux.hpp"
#include "tfmb/heat/steady_solver.hpp"
#include "tfmb/heat/wall_mapping.hpp"

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

PropertyTable read_property(const h5::Reader& db, const std::string& material,
                            const std::string& property) {
  const std::string group = "/materials/" + material + "/" + property;
  if (!db.exists(group)) db.fail(group, "missing: material '" + material + "' has no " + property + " table");
  auto temperature = db.read_vector(group + "/temperature");
  auto value = db.read_vector(group + "/value", temperature.size());
  try {
    return PropertyTable(std::move(temperature), std::move(value));
  } catch (const std::invalid_argument& error) {
    db.fail(group, error.what());
  }
}

// Steady runs need only the conductivity; density and specific heat are read when present.
PropertyTable read_optional_property(const h5::Reader& db, const std::string& material,
                                     const std::string& property) {
  if (!db.exists("/materials/" + material + "/" + property)) return {};
  return read_property(db, material, property);
}

std::string lower_trimmed(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (!std::isspace(static_cast<unsigned char>(c))) out += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  }
  return out;
}

// The database group of a material named in the model: its own name or one of its aliases,
// matched without case (as tfmb-matmap does). Empty if none.
std::string resolve_material(const h5::Reader& db, const std::string& name) {
  const std::string key = lower_trimmed(name);
  const auto materials = db.children("/materials");
  for (const auto& m : materials) {
    if (lower_trimmed(m) == key) return m;
  }
  for (const auto& m : materials) {
    const std::string group = "/materials/" + m;
    if (!db.has_attr(group, "aliases")) continue;
    std::stringstream aliases(db.attr_string(group, "aliases"));
    for (std::string alias; std::getline(aliases, alias, ',');) {
      if (lower_trimmed(alias) == key) return m;
    }
  }
  return {};
}

struct FlowWall {
  std::string name;
  std::string flap, side;
};

// The trace dataset of a flow wall, or a BadInput naming what is missing and why it is needed.
std::vector<double> trace_values(const h5::Reader& flow, const std::string& wall,
                                 const std::string& dataset, const std::string& needed_by) {
  const std::string path = "/walls/" + wall + "/" + dataset;
  if (!flow.exists(path)) flow.fail(path, "missing, needed by " + needed_by);
  return flow.read_vector(path);
}

}  // namespace

int run(const Options& options, const Logger& log) {
  const auto start = std::chrono::steady_clock::now();
  // --- inputs -------------------------------------------------------------------------------
  const auto solid_file = formats::open_checked(options.solid_mesh, "solidmesh");
  const auto header = formats::read_header(solid_file);
  const auto solid_in = formats::read_mesh(solid_file);
  SolidMesh mesh = to_solid_mesh(solid_in);
  const auto n_cells = static_cast<std::size_t>(solid_in.cell_count());
  const auto flap_names = solid_file.read_strings("/link/flap_names");
  const auto cell_flap = solid_file.read_index_vector("/link/cell_flap", n_cells, 0,
                                                      static_cast<std::int64_t>(flap_names.size()));
  const auto cell_element = solid_file.read_index_vector("/link/cell_element", n_cells, 0,
                                                         std::numeric_limits<std::int64_t>::max());
  const auto z_values = solid_file.read_vector("/link/point_thickness_coordinate", mesh.node_count());
  const Eigen::VectorXd node_z = Eigen::Map<const Eigen::VectorXd>(z_values.data(), static_cast<Eigen::Index>(z_values.size()));

  const formats::Model model = formats::read_model(options.model);
  const std::string solid_boundary = model.thermal.solid_boundary;
  const double emissivity = model.thermal.emissivity;

  const auto db = formats::open_checked(options.material_db, "material-db");
  ThermalProblem problem;
  problem.mesh = &mesh;
  std::map<std::string, int> material_index;
  std::vector<int> flap_material(flap_names.size());
  std::vector<std::int64_t> flap_elements(flap_names.size());
  for (std::size_t f = 0; f < flap_names.size(); ++f) {
    const std::string flap_group = "/flaps/" + flap_names[f];
    const formats::Flap* model_flap = model.find_flap(flap_names[f]);
    if (!model_flap) {
      model.fail(flap_group, "missing: the solid mesh has flap '" + flap_names[f] + "' but the model does not");
    }
    const std::string named = model_flap->material;
    flap_elements[f] = model_flap->elements;
    const std::string material = resolve_material(db, named);
    if (material.empty()) {
      db.fail("/materials", "no material or alias '" + named + "' (flap '" + flap_names[f] + "' of " +
                                options.model.string() + ")");
    }
    if (!material_index.count(material)) {
      material_index[material] = static_cast<int>(problem.materials.size());
      problem.materials.push_back({material, read_property(db, material, "conductivity"),
                                   read_optional_property(db, material, "density"),
                                   read_optional_property(db, material, "specific_heat")});
      try {
        validate_material(problem.materials.back(), false);
      } catch (const std::invalid_argument& error) {
        db.fail("/materials/" + material + "/conductivity", error.what());
      }
    }
    flap_material[f] = material_index[material];
  }
  mesh.cell_material.resize(n_cells);
  for (std::size_t c = 0; c < n_cells; ++c) mesh.cell_material[c] = flap_material[static_cast<std::size_t>(cell_flap[c])];

  const auto flow = formats::open_checked(options.flow, "flow");
  const auto flow_mesh = formats::read_mesh(flow);
  std::vector<FlowWall> flow_walls;
  if (flow.exists("/walls")) {
    for (const auto& name : flow.children("/walls")) {
      const auto it = flow_mesh.boundaries.find(name);
      if (it == flow_mesh.boundaries.end()) continue;
      flow_walls.push_back({name, it->second.flap, it->second.side});
    }
  }

  // --- boundary conditions --------------------------------------------------------------------
  double max_edge = 0.0;
  for (const auto& [name, curve] : mesh.boundaries) {
    for (std::size_t e = 0; e < curve.size(); ++e) {
      const auto edge = curve.edge(e);
      max_edge = std::max(max_edge, (mesh.points.row(edge[0]) - mesh.points.row(edge[1])).norm());
    }
  }
  // Flow and solid walls are discretised differently: allow half a solid edge at the wall ends.
  problem.trace_tolerance = 0.5 * max_edge;
  const std::string needed_by = options.model.string() + ": /thermal@solid_boundary = " + solid_boundary;
  std::vector<double> trace_temperatures;
  for (const auto& [name, boundary] : solid_in.boundaries) {
    if (boundary.kind != "solid_inner" && boundary.kind != "solid_outer") continue;
    const std::string side = boundary.kind == "solid_inner" ? "inner" : "outer";
    const auto& curve = mesh.boundaries.at(name);
    const double wall_length = boundary_length(mesh, curve);
    const FlowWall* match = nullptr;
    for (const auto& wall : flow_walls) {
      if (wall.flap == boundary.flap && wall.side == side) match = &wall;
    }
    if (!match) {
      // A side facing a closed cavity (e.g. the inner side of an external flap) has no trace and
      // is taken adiabatic; a flap the flow touches nowhere is an error (wrong flow file?).
      bool flap_wetted = false;
      for (const auto& wall : flow_walls) flap_wetted |= wall.flap == boundary.flap;
      if (!flap_wetted) {
        flow.fail("/walls", "no wall trace for flap '" + boundary.flap + "' on any side, needed by solid wall '" +
                                name + "' of " + options.solid_mesh.string());
      }
      log.warn("solid wall '" + name + "': no flow trace on the " + side + " side, adiabatic" +
               std::string(solid_boundary == "convection_radiation" && side == "outer" ? " plus radiation" : ""));
    } else {
      const auto x = trace_values(flow, match->name, "x", needed_by);
      const auto y = trace_values(flow, match->name, "y", needed_by);
      const double max_distance = 0.1 * wall_length;
      auto mapped = [&](const std::string& dataset) {
        const auto values = trace_values(flow, match->name, dataset, needed_by);
        try {
          return map_trace_to_boundary(mesh, curve, x, y, values,
                                       options.flow.string() + ": /walls/" + match->name + "/" + dataset,
                                       max_distance);
        } catch (const std::invalid_argument& error) {
          throw BadInput(error.what());
        }
      };
      if (solid_boundary == "wall_temperature") {
        const auto values = trace_values(flow, match->name, "temperature", needed_by);
        trace_temperatures.insert(trace_temperatures.end(), values.begin(), values.end());
        problem.boundary_conditions.push_back({name, ImposedTemperature{mapped("temperature")}});
      } else {
        const auto values = trace_values(flow, match->name, "adiabatic_wall_temperature", needed_by);
        trace_temperatures.insert(trace_temperatures.end(), values.begin(), values.end());
        problem.boundary_conditions.push_back(
            {name, Convection{mapped("heat_transfer_coefficient"), mapped("adiabatic_wall_temperature")}});
      }
      log.verbose("solid wall '" + name + "' <- flow wall '" + match->name + "'");
    }
    if (solid_boundary == "convection_radiation" && side == "outer") {
      problem.boundary_conditions.push_back({name, Radiation{emissivity, options.environment_temperature}});
    }
  }
  if (options.joint_conductance > 0.0) {
    // Each joint couples the closest pair of end walls of its two flaps.
    auto centroid = [&](const std::string& name) {
      const auto& curve = mesh.boundaries.at(name);
      Eigen::Vector2d c = Eigen::Vector2d::Zero();
      for (auto node : curve.nodes) c += mesh.points.row(node).transpose();
      return Eigen::Vector2d(c / static_cast<double>(curve.nodes.size()));
    };
    for (const formats::Joint& model_joint : model.joints) {
      const std::string& joint = model_joint.name;
      const std::string& flap_a = model_joint.flap_a;
      const std::string& flap_b = model_joint.flap_b;
      double best = std::numeric_limits<double>::infinity();
      std::string end_a, end_b;
      for (const auto& [name_a, a] : solid_in.boundaries) {
        if (a.kind != "solid_end" || a.flap != flap_a) continue;
        for (const auto& [name_b, b] : solid_in.boundaries) {
          if (b.kind != "solid_end" || b.flap != flap_b) continue;
          const double distance = (centroid(name_a) - centroid(name_b)).norm();
          if (distance < best) best = distance, end_a = name_a, end_b = name_b;
        }
      }
      if (end_a.empty()) {
        log.warn("joint '" + joint + "': no solid_end walls of flaps '" + flap_a + "' and '" + flap_b +
                 "' in the solid mesh (continuous wall?); no joint contact");
        continue;
      }
      problem.contacts.push_back({end_a, end_b, options.joint_conductance});
      log.verbose("joint '" + joint + "': contact '" + end_a + "' - '" + end_b + "'");
    }
  }
  if (trace_temperatures.empty()) {
    flow.fail("/walls", "no wall trace matches a solid_inner wall of " + options.solid_mesh.string());
  }

  // --- solve -----------------------------------------------------------------------------------
  double initial = 0.0;
  for (double t : trace_temperatures) initial += t;
  initial /= static_cast<double>(trace_temperatures.size());
  SteadyResult result;
  std::map<std::string, double> rates;
  try {
    result = solve_steady(problem, initial, options.newton);
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

  // --- per beam element outputs ----------------------------------------------------------------
  std::vector<std::int64_t> offsets(flap_names.size() + 1, 0);
  for (std::size_t f = 0; f < flap_names.size(); ++f) offsets[f + 1] = offsets[f] + flap_elements[f];
  std::vector<std::int64_t> cell_to_beam(n_cells);
  for (std::size_t c = 0; c < n_cells; ++c) {
    const auto f = static_cast<std::size_t>(cell_flap[c]);
    if (cell_element[c] >= flap_elements[f]) {
      solid_file.fail("/link/cell_element", "cell " + std::to_string(c) + " maps to element " +
                                                std::to_string(cell_element[c]) + " of flap '" +
                                                flap_names[f] + "', which has " +
                                                std::to_string(flap_elements[f]) + " elements in the model");
    }
    cell_to_beam[c] = offsets[f] + cell_element[c];
  }
  BeamThermalOutputs beam;
  try {
    beam = beam_element_temperatures(mesh, result.temperature, cell_to_beam, node_z,
                                     static_cast<std::size_t>(offsets.back()));
  } catch (const std::invalid_argument& error) {
    solid_file.fail("/link", error.what());
  }
  const auto flux = nodal_heat_flux(problem, result.temperature);

  // --- output ----------------------------------------------------------------------------------
  {
    h5::Writer out(options.output);
    formats::Header out_header;
    out_header.creator = "tfmb-heat " + std::string(TFMB_HEAT_VERSION);
    out_header.geometry = header.geometry;
    out_header.depth = header.depth;
    formats::write_header(out, "thermal", out_header);
    formats::write_mesh(out, solid_in);
    out.write("/fields/point/temperature",
              std::vector<double>(result.temperature.data(), result.temperature.data() + result.temperature.size()),
              "K", "nodal temperature");
    h5::MatrixXdR flux3 = h5::MatrixXdR::Zero(flux.rows(), 3);
    flux3.leftCols(2) = flux;
    out.write("/fields/point/heat_flux", flux3, "W/m^2", "q = -k grad T, area-weighted nodal average");
    for (std::size_t f = 0; f < flap_names.size(); ++f) {
      const auto begin = static_cast<std::size_t>(offsets[f]), end = static_cast<std::size_t>(offsets[f + 1]);
      const std::string group = "/beam/" + flap_names[f];
      out.write(group + "/mean_temperature",
                std::vector<double>(beam.mean_temperature.begin() + static_cast<std::ptrdiff_t>(begin),
                                    beam.mean_temperature.begin() + static_cast<std::ptrdiff_t>(end)),
                "K", "area mean per beam element");
      out.write(group + "/delta_temperature",
                std::vector<double>(beam.temperature_difference.begin() + static_cast<std::ptrdiff_t>(begin),
                                    beam.temperature_difference.begin() + static_cast<std::ptrdiff_t>(end)),
                "K", "outer minus inner surface temperature of the linear fit through the thickness");
    }
    out.create_group("/convergence");
    out.set_attr("/convergence", "converged", static_cast<std::int64_t>(result.newton.converged ? 1 : 0));
    out.set_attr("/convergence", "iterations", static_cast<std::int64_t>(result.newton.iterations));
    out.set_attr("/convergence", "criterion",
                 "largest Newton temperature update below " + std::to_string(options.newton.temperature_tolerance) + " K");
    formats::Provenance provenance;
    provenance.command_line = options.command_line;
    std::ostringstream settings;
    settings << "solid_boundary = \"" << solid_boundary << "\"\nemissivity = " << emissivity
             << "\nenvironment_temperature = " << options.environment_temperature
             << "\njoint_conductance = " << options.joint_conductance
             << "\ntemperature_tolerance = " << options.newton.temperature_tolerance
             << "\nmax_iterations = " << options.newton.max_iterations << "\n";
    provenance.settings = settings.str();
    provenance.inputs = {options.solid_mesh, options.flow, options.model, options.material_db};
    formats::write_provenance(out, provenance);
    out.commit();
  }
  formats::write_xdmf_sidecar(options.output);

  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::ostringstream summary;
  summary << mesh.node_count() << " nodes, " << result.newton.iterations << " Newton iterations, T "
          << result.temperature.minCoeff() << " .. " << result.temperature.maxCoeff() << " K, "
          << seconds << " s -> " << options.output.string();
  if (!result.newton.converged) {
    throw NotConverged("Newton did not converge in " + std::to_string(options.newton.max_iterations) +
                       " iterations (result written, flagged in /convergence): " + summary.str());
  }
  log.summary(summary.str());
  return 0;
}

}  // namespace tfmb::heat
