// tfmb-flow as a library call: read flowmesh.h5 (and optionally a restart flow.h5), solve,
// write flow.h5 with its XDMF sidecar. main.cpp only parses options into RunOptions.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include "solver.hpp"
#include "tfmb/common/log.hpp"
#include "time_accurate.hpp"

namespace tfmb::flow {

struct RunOptions {
  std::filesystem::path mesh_file;                    // tfmb/flowmesh
  std::optional<std::filesystem::path> restart_file;  // tfmb/flow of the same topology
  std::filesystem::path output;                       // tfmb/flow
  double stagnation_pressure = 0.0;                   // inflow total pressure [Pa]
  double stagnation_temperature = 0.0;                // inflow total temperature [K]
  double ambient_pressure = 101325.0;                 // outflow and far-field static pressure [Pa]
  double ambient_temperature = 288.15;                // far-field static temperature [K]
  double freestream_mach = 0.0;                       // far-field Mach number along +x
  double inflow_angle = 0.0;                          // inflow direction from +x [deg]
  double gamma = 1.4;
  double gas_constant = 287.05;  // [J/(kg K)]
  std::string model = "euler";   // euler | laminar
  std::optional<double>
      wall_temperature;               // [K] isothermal no-slip walls (laminar); adiabatic if unset
  std::optional<double> throat_area;  // [m] per unit depth (planar) or [m^2] (axisymmetric), for Cd
  double heat_transfer_dt =
      20.0;  // [K] probe below T_aw for the heat transfer coefficient (0: none)
  std::string farfield_flux = "roe";  // roe | riemann (BoundaryCondition::riemann_invariants)
  int inflow_ramp = -1;               // iterations of the total-pressure ramp (-1: automatic)
  // Start state without a restart: uniform | quasi-1d | auto (quasi-1d for an internal flow).
  std::string initial_state = "uniform";
  bool renumber = true;               // reverse Cuthill-McKee node order inside the solver
  std::string node_ordering = "rcm";  // rcm | lines (SolverSettings::renumber_lines)
  // Second order without a restart file: converge first order first (same settings, its own
  // iteration limit), then continue at second order from that state, as a restart would.
  bool first_order_start = false;
  // The first-order stage stops once its density residual has fallen by this factor (or by the
  // run's own criteria, if they come first): the second-order stage does not need it converged,
  // only past its start-up transient (NPARC 0.75 240 x 60: the same 45 second-order iterations
  // after first-order drops of 4e-3 and 1e-8, tools/tfmb-flow/README.md). 1e-3, not 1e-2: with
  // 1e-2 the flow benchmarks took 9 % fewer iterations, but the realistic nozzle (config3, and
  // config4's first iterate) ended its first-order stage at 50 iterations and its second-order
  // stage never converged (2,000 iterations); with 1e-3 it does (README, "First-order start").
  double first_order_start_drop = 1e-3;
  // The second-order stage's initial CFL number (and SER base); unset: --cfl-start. The
  // first-order stage ends at its CFL ceiling, so the second starts from a converged
  // first-order state and need not begin at a cold start's CFL number (README, "First-order
  // start").
  std::optional<double> second_order_cfl_start;
  // Second order from a restart: `frozen` holds the limiter at the restart state's values from
  // the first iteration (FlowSolver::hold_limiter; with --matrix-free auto, Newton-Krylov from
  // there), `live` evaluates it every iteration. Frozen is for a converged second-order state
  // restarted after a small change (a coupling iterate on a deformed mesh): the converged
  // solution then depends a little on where the limiter froze, as any frozen-limiter solution
  // does, so a restart from a first-order state keeps it live (NPARC 61 x 16 from a first-order
  // state: mass flow 0.07 % off the second-order one with it frozen there).
  std::string restart_limiter = "live";            // live | frozen
  std::string inner_limiter = "live";              // live | predicted (time-accurate runs)
  // A steady solve from --restart that does not converge is solved again from the start state
  // (as without --restart, first-order start included), so that a coupling iterate whose walls
  // moved far from the restart state is not lost to that state.
  bool restart_fallback = true;
  std::string turbulence_coupling = "segregated";  // segregated | coupled | auto (SA)
  std::string turbulence_step_limit = "node";      // node | nu-tilde (coupled SA steps)
  std::string matrix_free = "auto";                // false | true | auto (second order)
  std::string turbulence_jacobian = "exact";       // exact | m-matrix (SA's own linearisation)
  std::string roe_jacobian = "frozen";             // frozen | exact-first-order | exact
  std::string multigrid_post_smoother = "ilu";  // ilu | jacobi (AggregationMultigrid::PostSmoother)
  bool exact_jacobian = false;                     // --exact-jacobian: --roe-jacobian exact
  // Time-accurate run (dual time stepping) when time.time_step > 0: from the restart (or the
  // initial) state, no steady solve; flow.h5 then holds the time averages.
  TimeAccurateSettings time;
  SolverSettings settings;
  std::string command_line;
  // Every command-line option's value as TOML (cli::OptionTable::settings_toml), for
  // /provenance@settings; empty for in-process callers.
  std::string settings_toml;
};

struct RunResult {
  SolveReport report;
  std::optional<TimeAccurateResult> time_average;  // time-accurate runs
  double mass_flow = 0.0;  // through the outflow boundaries (else the inflow) [kg/(s m)] or [kg/s]
  double thrust_x = 0.0;   // [N/m] or [N]
  double thrust_y = 0.0;
  double discharge_coefficient = 0.0;
};

// Throws BadInput for invalid inputs; returns the result after writing options.output (also
// when the solver did not converge: the file is then flagged converged = 0).
RunResult run(const RunOptions& options, const Logger& logger);

}  // namespace tfmb::flow
