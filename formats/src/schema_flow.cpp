// Layout of the "flow" file kind; prose spec in formats/flow.md.
#include "schema_rules.hpp"

namespace tfmb::formats::detail {

Schema flow_schema() {
  Schema s{"flow",
           "tfmb/flow",
           1,
           5,
           "flow solution: node fields, wall traces, integrated thrust and mass flow",
           true,
           {},
           {}};
  add_root(s, true);
  add_mesh(s);
  s.datasets.push_back(f64("/fields/point/density", {"N"}, "kg/m^3", ""));
  s.datasets.push_back(f64("/fields/point/velocity", {"N", "3"}, "m/s", "u, v, 0"));
  s.datasets.push_back(f64("/fields/point/pressure", {"N"}, "Pa", "static pressure"));
  s.datasets.push_back(f64("/fields/point/temperature", {"N"}, "K", "static temperature"));
  s.datasets.push_back(f64("/fields/point/mach", {"N"}, "1", ""));
  s.datasets.push_back(f64("/fields/point/nu_tilde", {"N"}, "m^2/s", "Spalart-Allmaras variable", false));
  s.datasets.push_back(f64("/fields/point/turbulent_kinetic_energy", {"N"}, "m^2/s^2",
                           "(1.5) k of the k-omega SST model", false));
  s.datasets.push_back(f64("/fields/point/specific_dissipation_rate", {"N"}, "1/s",
                           "(1.5) omega of the k-omega SST model", false));
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
  s.datasets.push_back(f64("/walls/*/normal", {"n", "2"}, "1",
                           "unit normal leaving the fluid (into the wall) at each trace point: the "
                           "pressure's traction on the wall is pressure * normal",
                           false));
  s.datasets.push_back(f64("/walls/*/heat_transfer_coefficient", {"n"}, "W/(m^2 K)",
                           "q_w / (T_aw - T_w) of an isothermal probe run below T_aw (viscous, adiabatic walls)", false));
  s.datasets.push_back(f64("/walls/*/adiabatic_wall_temperature", {"n"}, "K",
                           "wall temperature of the adiabatic viscous solution (recovery temperature)", false));
  s.datasets.push_back(f64("/walls/*/pressure_rms", {"n"}, "Pa",
                           "time-accurate runs: RMS of the wall pressure fluctuation over the "
                           "statistics window (the other trace datasets are then time means)",
                           false));
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
  s.attributes.push_back(nattr("/convergence", "residual_reference", "1",
                               "largest density residual of the run, the reference of the drop; a "
                               "restart continues from it",
                               0.0, std::nullopt, false));
  s.attributes.push_back(nattr("/convergence", "linear_iterations", "1",
                               "linear solver iterations, all nonlinear iterations", 0.0,
                               std::nullopt, false, AttrType::int64));
  s.attributes.push_back(nattr("/convergence", "residual_evaluations", "1",
                               "residual evaluations (one per nonlinear iteration and one per "
                               "matrix-free product)",
                               0.0, std::nullopt, false, AttrType::int64));
  s.attributes.push_back(nattr("/convergence", "residual_seconds", "s",
                               "wall time spent in residual evaluations", 0.0, std::nullopt,
                               false));
  s.attributes.push_back(nattr("/convergence", "wall_time", "s", "wall time of the solve", 0.0,
                               std::nullopt, false));
  s.attributes.push_back(sattr("/convergence", "stop_reason",
                               "a run that did not converge: why it stopped (iteration limit, CFL "
                               "collapse, repeated non-physical updates)",
                               {}, false));
  s.attributes.push_back(nattr("/convergence", "worst_residual_x", "m",
                               "a run that did not converge: node with the largest density "
                               "residual per volume at the end",
                               std::nullopt, std::nullopt, false));
  s.attributes.push_back(
      nattr("/convergence", "worst_residual_y", "m", "", std::nullopt, std::nullopt, false));
  s.attributes.push_back(nattr("/convergence", "least_relaxation", "1",
                               "a run that did not converge: smallest fraction of the Newton "
                               "update applied at a node in the last iteration",
                               0.0, 1.0, false));
  s.attributes.push_back(nattr("/convergence", "least_relaxed_x", "m", "where it was applied",
                               std::nullopt, std::nullopt, false));
  s.attributes.push_back(
      nattr("/convergence", "least_relaxed_y", "m", "", std::nullopt, std::nullopt, false));
  s.attributes.push_back(nattr("/convergence", "time_average", "1",
                               "1: a time-accurate run; fields and wall traces are time means over "
                               "the statistics window, integrals those of the mean state",
                               0.0, 1.0, false, AttrType::int64));
  s.attributes.push_back(nattr("/convergence", "time_step", "s", "physical time step", 0.0,
                               std::nullopt, false));
  s.attributes.push_back(nattr("/convergence", "time_steps", "1", "physical time steps run", 1.0,
                               std::nullopt, false, AttrType::int64));
  s.attributes.push_back(nattr("/convergence", "statistics_start", "1",
                               "first step (1-based) in the time averages", 1.0, std::nullopt,
                               false, AttrType::int64));
  s.attributes.push_back(nattr("/convergence", "averaged_steps", "1", "steps in the time averages",
                               1.0, std::nullopt, false, AttrType::int64));
  s.attributes.push_back(nattr("/convergence", "mean_change", "1",
                               "largest difference of the wall pressure means of the statistics "
                               "window's two halves, relative to the stagnation pressure",
                               0.0, std::nullopt, false));
  s.datasets.push_back(f64("/convergence/time_history", {"S", "5"}, "1",
                           "time-accurate runs, per physical step: time [s], inner iterations, "
                           "inner residual drop reached, wall pressure force x and y [N/m planar, "
                           "N/rad axisymmetric]",
                           false));
  s.datasets.push_back(f64("/convergence/residual_history", {"I", "*"}, "1",
                           "per iteration: L2 residual of each equation relative to its largest value in the run"));
  add_provenance(s);
  return s;
}

}  // namespace tfmb::formats::detail
