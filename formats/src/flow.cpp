// The flow kind's one reader and writer: formats/flow.md (schema in schema_flow.cpp).
#include "tfmb/formats/flow.hpp"

#include <cmath>

#include "tfmb/common/errors.hpp"
#include "tfmb/common/h5.hpp"
#include "tfmb/formats/schema.hpp"

namespace tfmb::formats {
namespace {

void write_wall(h5::Writer& w, const FlowWall& t) {
  const std::string g = "/walls/" + t.name;
  w.write(g + "/node", t.node, "1");
  w.write(g + "/s", t.s, "m", "arc length along the wall");
  w.write(g + "/x", t.x, "m");
  w.write(g + "/y", t.y, "m");
  w.write(g + "/pressure", t.pressure, "Pa", "wall static pressure");
  w.write(g + "/temperature", t.temperature, "K", "wall temperature");
  w.write(g + "/wall_shear", t.wall_shear, "Pa", "along the direction of increasing s");
  w.write(g + "/heat_flux", t.heat_flux, "W/m^2", "into the wall");
  if (!t.normal.empty()) {
    h5::MatrixXdR normal(static_cast<Eigen::Index>(t.normal.size()), 2);
    for (std::size_t k = 0; k < t.normal.size(); ++k) normal.row(static_cast<Eigen::Index>(k)) = t.normal[k].transpose();
    w.write(g + "/normal", normal, "1", "unit normal leaving the fluid (into the wall)");
  }
  if (!t.pressure_rms.empty())
    w.write(g + "/pressure_rms", t.pressure_rms, "Pa",
            "root mean square of the wall pressure fluctuation over the statistics window");
  if (!t.adiabatic_wall_temperature.empty())
    w.write(g + "/adiabatic_wall_temperature", t.adiabatic_wall_temperature, "K",
            "wall temperature of the adiabatic solution");
  if (!t.heat_transfer_coefficient.empty())
    w.write(g + "/heat_transfer_coefficient", t.heat_transfer_coefficient, "W/(m^2 K)",
            "q_w / (T_aw - T_w) of an isothermal probe run below T_aw");
}

void write_convergence(h5::Writer& w, const FlowConvergence& c) {
  const std::string g = "/convergence";
  w.create_group(g);
  w.set_attr(g, "converged", static_cast<std::int64_t>(c.converged ? 1 : 0));
  w.set_attr(g, "criterion", c.criterion);
  w.set_attr(g, "iterations", c.iterations);
  auto optional = [&](const char* name, const auto& value) {
    if (value) w.set_attr(g, name, *value);
  };
  optional("residual_reference", c.residual_reference);
  optional("linear_iterations", c.linear_iterations);
  optional("residual_evaluations", c.residual_evaluations);
  optional("residual_seconds", c.residual_seconds);
  optional("wall_time", c.wall_time);
  optional("stop_reason", c.stop_reason);
  optional("worst_residual_x", c.worst_residual_x);
  optional("worst_residual_y", c.worst_residual_y);
  optional("least_relaxation", c.least_relaxation);
  optional("least_relaxed_x", c.least_relaxed_x);
  optional("least_relaxed_y", c.least_relaxed_y);
  if (c.time_average) w.set_attr(g, "time_average", static_cast<std::int64_t>(1));
  optional("time_step", c.time_step);
  optional("time_steps", c.time_steps);
  optional("statistics_start", c.statistics_start);
  optional("averaged_steps", c.averaged_steps);
  optional("mean_change", c.mean_change);
  if (c.time_history.rows() > 0)
    w.write(g + "/time_history", c.time_history, "1",
            "per physical step: time [s], inner iterations, inner residual drop reached, "
            "wall pressure force x and y [N/m planar, N/rad axisymmetric]");
  w.write(g + "/residual_history", c.residual_history, "1",
          "per iteration: RMS residual of continuity, x-momentum, y-momentum, energy relative to "
          "its largest value in the run");
}

FlowWall read_wall(const h5::Reader& r, const std::string& name, std::int64_t node_count) {
  const std::string g = "/walls/" + name;
  FlowWall t;
  t.name = name;
  t.x = r.read_vector(g + "/x");
  const std::size_t n = t.x.size();
  t.node = r.read_index_vector(g + "/node", n, 0, node_count);
  t.s = r.read_vector(g + "/s", n);
  t.y = r.read_vector(g + "/y", n);
  t.pressure = r.read_vector(g + "/pressure", n);
  t.temperature = r.read_vector(g + "/temperature", n);
  t.wall_shear = r.read_vector(g + "/wall_shear", n);
  t.heat_flux = r.read_vector(g + "/heat_flux", n);
  if (r.exists(g + "/normal")) {
    const h5::MatrixXdR normal = r.read_matrix(g + "/normal", static_cast<Eigen::Index>(n), 2);
    for (Eigen::Index k = 0; k < normal.rows(); ++k) {
      if (std::abs(normal.row(k).norm() - 1.0) > 1e-6)
        r.fail(g + "/normal", "row " + std::to_string(k) + " is not a unit vector");
      t.normal.emplace_back(normal(k, 0), normal(k, 1));
    }
  }
  for (auto [dataset, target] : {std::pair{"heat_transfer_coefficient", &t.heat_transfer_coefficient},
                                 std::pair{"adiabatic_wall_temperature", &t.adiabatic_wall_temperature},
                                 std::pair{"pressure_rms", &t.pressure_rms}}) {
    if (r.exists(g + "/" + dataset)) *target = r.read_vector(g + "/" + dataset, n);
  }
  for (std::size_t k = 0; k < n; ++k)
    if (!(t.pressure[k] > 0.0)) r.fail(g + "/pressure", "point " + std::to_string(k) + ": not positive");
  // Absolute temperatures: tfmb-heat takes them as its wall conditions, and a negated one was
  // refused only later, as a solid temperature at a mesh node, without naming this file.
  for (auto [dataset, values] :
       {std::pair{"temperature", &t.temperature},
        std::pair{"adiabatic_wall_temperature", &t.adiabatic_wall_temperature}}) {
    for (std::size_t k = 0; k < values->size(); ++k)
      if (!((*values)[k] > 0.0))
        r.fail(g + "/" + dataset, "point " + std::to_string(k) + ": not positive (" +
                                      std::to_string((*values)[k]) + " K)");
  }
  return t;
}

FlowConvergence read_convergence(const h5::Reader& r) {
  const std::string g = "/convergence";
  FlowConvergence c;
  c.converged = r.attr_i64(g, "converged") == 1;
  c.criterion = r.attr_string(g, "criterion");
  c.iterations = r.attr_i64(g, "iterations");
  auto f64 = [&](const char* name, std::optional<double>& target) {
    if (r.has_attr(g, name)) target = r.attr_f64(g, name);
  };
  auto i64 = [&](const char* name, std::optional<std::int64_t>& target) {
    if (r.has_attr(g, name)) target = r.attr_i64(g, name);
  };
  f64("residual_reference", c.residual_reference);
  i64("linear_iterations", c.linear_iterations);
  i64("residual_evaluations", c.residual_evaluations);
  f64("residual_seconds", c.residual_seconds);
  f64("wall_time", c.wall_time);
  if (r.has_attr(g, "stop_reason")) c.stop_reason = r.attr_string(g, "stop_reason");
  f64("worst_residual_x", c.worst_residual_x);
  f64("worst_residual_y", c.worst_residual_y);
  f64("least_relaxation", c.least_relaxation);
  f64("least_relaxed_x", c.least_relaxed_x);
  f64("least_relaxed_y", c.least_relaxed_y);
  c.time_average = r.has_attr(g, "time_average") && r.attr_i64(g, "time_average") == 1;
  f64("time_step", c.time_step);
  i64("time_steps", c.time_steps);
  i64("statistics_start", c.statistics_start);
  i64("averaged_steps", c.averaged_steps);
  f64("mean_change", c.mean_change);
  if (r.exists(g + "/time_history")) c.time_history = r.read_matrix(g + "/time_history", std::nullopt, 5);
  c.residual_history = r.read_matrix(g + "/residual_history", std::nullopt, std::nullopt);
  return c;
}

}  // namespace

void write_flow(const std::filesystem::path& file, const Flow& flow, const Provenance& provenance) {
  h5::Writer w(file);
  write_header(w, "flow", flow.header);
  write_mesh(w, flow.mesh);
  w.write("/fields/point/density", flow.density, "kg/m^3");
  w.write("/fields/point/velocity", flow.velocity, "m/s", "u, v, 0");
  w.write("/fields/point/pressure", flow.pressure, "Pa", "static pressure");
  w.write("/fields/point/temperature", flow.temperature, "K", "static temperature");
  w.write("/fields/point/mach", flow.mach, "1");
  if (!flow.nu_tilde.empty()) w.write("/fields/point/nu_tilde", flow.nu_tilde, "m^2/s", "Spalart-Allmaras variable");
  if (!flow.turbulent_kinetic_energy.empty())
    w.write("/fields/point/turbulent_kinetic_energy", flow.turbulent_kinetic_energy, "m^2/s^2",
            "k of the k-omega SST model");
  if (!flow.specific_dissipation_rate.empty())
    w.write("/fields/point/specific_dissipation_rate", flow.specific_dissipation_rate, "1/s",
            "omega of the k-omega SST model");
  if (!flow.eddy_viscosity.empty()) w.write("/fields/point/eddy_viscosity", flow.eddy_viscosity, "Pa s");
  if (!flow.wall_distance.empty()) w.write("/fields/point/wall_distance", flow.wall_distance, "m");
  for (const FlowWall& t : flow.walls) write_wall(w, t);
  w.create_group("/integrals");
  w.set_attr("/integrals", "mass_flow", flow.mass_flow);
  w.set_attr("/integrals", "thrust_x", flow.thrust_x);
  w.set_attr("/integrals", "thrust_y", flow.thrust_y);
  w.set_attr("/integrals", "thrust_angle", flow.thrust_angle);
  w.set_attr("/integrals", "discharge_coefficient", flow.discharge_coefficient);
  w.create_group("/conditions");
  w.set_attr("/conditions", "stagnation_pressure", flow.stagnation_pressure);
  w.set_attr("/conditions", "stagnation_temperature", flow.stagnation_temperature);
  w.set_attr("/conditions", "ambient_pressure", flow.ambient_pressure);
  w.set_attr("/conditions", "gamma", flow.gamma);
  w.set_attr("/conditions", "gas_constant", flow.gas_constant);
  write_convergence(w, flow.convergence);
  write_provenance(w, provenance);
  w.commit();
  write_xdmf_sidecar(file);
}

Flow read_flow(const std::filesystem::path& file) {
  const h5::Reader r = open_checked(file, "flow");
  Flow flow;
  flow.source = file;
  flow.header = read_header(r);
  flow.mesh = read_mesh(r);
  const std::size_t n = flow.mesh.node_count();
  flow.density = r.read_vector("/fields/point/density", n);
  flow.velocity = r.read_matrix("/fields/point/velocity", static_cast<Eigen::Index>(n), 3);
  flow.pressure = r.read_vector("/fields/point/pressure", n);
  flow.temperature = r.read_vector("/fields/point/temperature", n);
  flow.mach = r.read_vector("/fields/point/mach", n);
  for (std::size_t k = 0; k < n; ++k) {
    if (!(flow.density[k] > 0.0) || !(flow.pressure[k] > 0.0) || !(flow.temperature[k] > 0.0))
      r.fail("/fields/point", "node " + std::to_string(k) +
                                  " has a non-physical state (density, pressure and temperature must be positive)");
  }
  for (auto [name, target] :
       {std::pair{"nu_tilde", &flow.nu_tilde}, std::pair{"eddy_viscosity", &flow.eddy_viscosity},
        std::pair{"wall_distance", &flow.wall_distance},
        std::pair{"turbulent_kinetic_energy", &flow.turbulent_kinetic_energy},
        std::pair{"specific_dissipation_rate", &flow.specific_dissipation_rate}}) {
    const std::string path = std::string("/fields/point/") + name;
    if (r.exists(path)) *target = r.read_vector(path, n);
  }
  // a restart hands these to the SST equations, which need k >= 0 and omega > 0
  for (std::size_t k = 0; k < flow.turbulent_kinetic_energy.size(); ++k)
    if (!(flow.turbulent_kinetic_energy[k] >= 0.0))
      r.fail("/fields/point/turbulent_kinetic_energy",
             "node " + std::to_string(k) + " has a negative k");
  for (std::size_t k = 0; k < flow.specific_dissipation_rate.size(); ++k)
    if (!(flow.specific_dissipation_rate[k] > 0.0))
      r.fail("/fields/point/specific_dissipation_rate",
             "node " + std::to_string(k) + " has omega <= 0");
  if (r.is_group("/walls"))
    for (const std::string& name : r.children("/walls"))
      flow.walls.push_back(read_wall(r, name, static_cast<std::int64_t>(n)));
  flow.mass_flow = r.attr_f64("/integrals", "mass_flow");
  flow.thrust_x = r.attr_f64("/integrals", "thrust_x");
  flow.thrust_y = r.attr_f64("/integrals", "thrust_y");
  flow.thrust_angle = r.attr_f64("/integrals", "thrust_angle");
  flow.discharge_coefficient = r.attr_f64("/integrals", "discharge_coefficient");
  flow.stagnation_pressure = r.attr_f64("/conditions", "stagnation_pressure");
  flow.stagnation_temperature = r.attr_f64("/conditions", "stagnation_temperature");
  flow.ambient_pressure = r.attr_f64("/conditions", "ambient_pressure");
  flow.gamma = r.attr_f64("/conditions", "gamma");
  flow.gas_constant = r.attr_f64("/conditions", "gas_constant");
  // The gas state of the conditions is physical: positive absolute pressures and temperature,
  // positive gas constant, gamma > 1 (a restart and the heat-transfer probe divide by gamma - 1).
  for (auto [name, value] : {std::pair{"stagnation_pressure", flow.stagnation_pressure},
                             std::pair{"stagnation_temperature", flow.stagnation_temperature},
                             std::pair{"ambient_pressure", flow.ambient_pressure},
                             std::pair{"gas_constant", flow.gas_constant}}) {
    if (!(value > 0.0))
      r.fail("/conditions",
             std::string("attribute '") + name + "' must be positive, is " + std::to_string(value));
  }
  if (!(flow.gamma > 1.0))
    r.fail("/conditions",
           "attribute 'gamma' must be greater than 1, is " + std::to_string(flow.gamma));
  flow.convergence = read_convergence(r);
  return flow;
}

}  // namespace tfmb::formats
