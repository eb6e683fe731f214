// The `flow` file kind (formats/flow.md): a flow solution on its mesh, with wall traces, integrals,
// conditions and the convergence record. Written by tfmb-flow (or an external flow code); read by
// tfmb-loads (wall traces), tfmb-heat (wall heating) and tfmb-flow itself (--restart).
// read_flow checks the file against the kind's schema (what tfmb-check applies) and what the
// schema cannot say (a trace's points are its nodes' mesh points, node states are physical).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "tfmb/formats/files.hpp"

namespace tfmb::formats {

// One wall boundary's trace, ordered along the boundary's edges.
struct FlowWall {
  std::string name;                  // the /mesh/boundaries entry it traces
  std::vector<std::int64_t> node;    // mesh node of each trace point
  std::vector<double> s, x, y;       // [m] arc length and position
  std::vector<double> pressure;      // [Pa]
  std::vector<double> temperature;   // [K]
  std::vector<double> wall_shear;    // [Pa] along increasing s
  std::vector<double> heat_flux;     // [W/m^2] into the wall
  std::vector<Eigen::Vector2d> normal;  // (1.4) unit normal leaving the fluid; empty if absent
  std::vector<double> heat_transfer_coefficient;   // [W/(m^2 K)] optional
  std::vector<double> adiabatic_wall_temperature;  // [K] optional
  std::vector<double> pressure_rms;                // [Pa] optional (time-accurate runs)
};

struct FlowConvergence {
  bool converged = false;
  std::string criterion;
  std::int64_t iterations = 0;
  std::optional<double> residual_reference;
  std::optional<std::int64_t> linear_iterations, residual_evaluations;
  std::optional<double> residual_seconds, wall_time;  // [s]
  // A run that did not converge: why and where.
  std::optional<std::string> stop_reason;
  std::optional<double> worst_residual_x, worst_residual_y, least_relaxation, least_relaxed_x, least_relaxed_y;
  // Time-accurate runs (fields and traces are then time means).
  bool time_average = false;
  std::optional<double> time_step, mean_change;
  std::optional<std::int64_t> time_steps, statistics_start, averaged_steps;
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> time_history;  // (S,5) or empty
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> residual_history;  // (I,k)
};

struct Flow : ReadFrom {
  Header header;
  Mesh mesh;
  // Node fields.
  std::vector<double> density;   // [kg/m^3]
  h5::MatrixXdR velocity;        // (N,3) [m/s] u, v, 0
  std::vector<double> pressure;  // [Pa]
  std::vector<double> temperature;  // [K]
  std::vector<double> mach;         // [1]
  std::vector<double> nu_tilde, eddy_viscosity, wall_distance;  // optional (turbulent runs)
  // (1.5) optional, k-omega SST runs: k [m^2/s^2] and omega [1/s]
  std::vector<double> turbulent_kinetic_energy, specific_dissipation_rate;
  std::vector<FlowWall> walls;  // by name
  // Integrals per unit depth (planar) [kg/(s m)], [N/m], [deg], [1].
  double mass_flow = 0.0, thrust_x = 0.0, thrust_y = 0.0, thrust_angle = 0.0, discharge_coefficient = 0.0;
  // Conditions [Pa], [K], [Pa], [1], [J/(kg K)].
  double stagnation_pressure = 0.0, stagnation_temperature = 0.0, ambient_pressure = 0.0, gamma = 1.4,
         gas_constant = 287.05;
  FlowConvergence convergence;

  const FlowWall* find_wall(const std::string& name) const { return find_named(walls, name); }
};

// Writes flow.h5 atomically and its XDMF sidecar.
void write_flow(const std::filesystem::path& file, const Flow& flow, const Provenance& provenance);
// Reads and validates a flow file (BadInput naming the file and the object on any problem).
Flow read_flow(const std::filesystem::path& file);

}  // namespace tfmb::formats
