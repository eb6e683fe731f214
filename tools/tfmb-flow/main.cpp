// tfmb-flow: steady 2D compressible flow (Euler, laminar Navier-Stokes or Spalart-Allmaras RANS,
// planar or axisymmetric) on a mixed triangle/quad flow mesh.
//
// Sample runs:
//   tfmb-flow flowmesh.h5 --p0 5.5e5 --T0 294 --ambient-pressure 101330 -o flow.h5
//   tfmb-flow flowmesh.h5 --p0 5.5e5 --T0 294 --restart flow_prev.h5 -o flow.h5
//   tfmb-flow flowmesh.h5 --p0 2e5 --T0 300 --model laminar --wall-temperature 400 -o flow.h5
//   tfmb-flow flowmesh.h5 --p0 2.44e5 --T0 294 --model sa --restart flow.h5 --time-step 2e-6
//     --time-steps 400 --statistics-start 201 -o flow_mean.h5      (time-accurate, averaged)
#include <iostream>

#include "run.hpp"
#include "tfmb/common/cli.hpp"
#include "tfmb/common/errors.hpp"

int main(int argc, char** argv) {
  CLI::App app{"Steady compressible flow on a flow mesh (tfmb/flowmesh) -> flow file (tfmb/flow).",
               "tfmb-flow"};
  // A later option overrides an earlier one, so that a workflow can append to a case's options
  // (the two-way loop sets --stationary-tolerance from the coupling residual).
  app.option_defaults()->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
  tfmb::cli::CommonOptions common;
  tfmb::cli::add_common_options(app, common, true);
  tfmb::flow::RunOptions o;
  std::filesystem::path restart;
  std::optional<double> wall_temperature, throat_area;
  // (no CLI::ExistingFile: a missing input is a bad input, exit 3 from its reader, as in every
  // stage, not a usage error)
  app.add_option("mesh", o.mesh_file, "flow mesh (tfmb/flowmesh)")->required();
  tfmb::cli::add_output_option(app, o.output, "flow file (tfmb/flow)");
  app.add_option("--restart", restart,
                 "start from this flow file (same mesh topology, e.g. before a wall deformation)");
  app.add_option("--p0", o.stagnation_pressure, "[Pa] inflow total pressure");
  app.add_option("--T0", o.stagnation_temperature, "[K] inflow total temperature");
  app.add_option("--ambient-pressure", o.ambient_pressure,
                 "[Pa] outflow and far-field static pressure")
      ->capture_default_str();
  app.add_option("--ambient-temperature", o.ambient_temperature, "[K] far-field static temperature")
      ->capture_default_str();
  app.add_option("--freestream-mach", o.freestream_mach, "[-] far-field Mach number along +x")
      ->capture_default_str();
  app.add_option("--inflow-angle", o.inflow_angle, "[deg] inflow direction from +x")
      ->capture_default_str();
  app.add_option("--gamma", o.gamma, "[-] ratio of specific heats")->capture_default_str();
  app.add_option("--gas-constant", o.gas_constant, "[J/(kg K)] specific gas constant")
      ->capture_default_str();
  app.add_option(
         "--model", o.model,
         "euler, laminar (Sutherland viscosity, Pr 0.72), sa (Spalart-Allmaras RANS with ft2, "
         "SA-neg for negative nu_tilde, Pr_t 0.9) or sa-noft2")
      ->check(CLI::IsMember({"euler", "laminar", "sa", "sa-noft2"}))
      ->capture_default_str();
  app.add_option(
         "--heat-transfer-dt", o.heat_transfer_dt,
         "[K] viscous runs with adiabatic walls: after converging, a probe run with the walls this "
         "much "
         "below the adiabatic wall temperature gives the heat transfer coefficient (0: skip)")
      ->capture_default_str();
  app.add_option(
         "--inflow-ramp", o.inflow_ramp,
         "iterations over which the inflow total pressure rises from the ambient pressure to --p0 "
         "(-1: 50 for a jet into a far field started from rest, else 0)")
      ->capture_default_str();
  app.add_option("--wall-temperature", wall_temperature,
                 "[K] isothermal no-slip walls (laminar; default adiabatic)");
  app.add_option("--throat-area", throat_area,
                 "[m] throat height per unit depth (planar) or [m^2] area (axisymmetric) for the "
                 "discharge coefficient");
  app.add_option("--order", o.settings.order, "spatial order of the convective fluxes, 1 or 2")
      ->check(CLI::Range(1, 2))
      ->capture_default_str();
  app.add_option(
         "--limiter-coefficient", o.settings.venkat_wang,
         "[-] Venkatakrishnan-Wang epsilon as a fraction of each variable's range (smaller: "
         "stronger limiting at shocks; larger: smoother, more accurate boundary layers)")
      ->capture_default_str();
  app.add_option(
         "--wall-aligned-aspect-ratio", o.settings.wall_aligned_aspect_ratio,
         "[-] second order: at nodes whose neighbour distances differ by more than this factor and "
         "whose nearest boundary is a wall, gradients and reconstruction use wall-aligned vectors "
         "(needed on curved walls with thin wall layers; 0: Cartesian everywhere)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  // On by default: second order started from the initial state diverged where the first-order
  // start converges (NPARC 0.75 on 240 x 60 and 480 x 120, tools/tfmb-flow/README.md).
  o.first_order_start = true;
  app.add_flag("--first-order-start,!--no-first-order-start", o.first_order_start,
               "with --order 2 and no --restart: converge at first order first, then continue "
               "at second order from that state (a restart from a first-order run, in one call; "
               "on by default)");
  app.add_option("--first-order-start-drop", o.first_order_start_drop,
                 "with the first-order start: end the first-order stage once its density residual "
                 "has fallen by this factor (or by --residual-drop or stationarity, if first)")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  app.add_option("--matrix-free", o.matrix_free,
                 "second order: true: each pseudo-time step solves with the Jacobian of the "
                 "second-order residual applied matrix-free (Newton-Krylov), preconditioned by ILU "
                 "of the first-order Jacobian; false: the first-order Jacobian alone (defect "
                 "correction, cheaper per iteration but it converges linearly and caps the CFL on "
                 "stretched wall layers); auto: defect correction while the limiter is live, "
                 "Newton-Krylov from the iteration on which it is frozen (--limiter-freeze-drop, "
                 "--limiter-stall-iterations)")
      ->check(CLI::IsMember({"false", "true", "auto"}))
      ->capture_default_str();
  app.add_option("--restart-limiter", o.restart_limiter,
                 "second order from --restart: live: the limiter evaluated every iteration; "
                 "frozen: held at the restart state's values from the first iteration (with "
                 "--matrix-free auto: Newton-Krylov from there), for a converged second-order "
                 "state restarted after a small change such as a wall deformation")
      ->check(CLI::IsMember({"live", "frozen"}))
      ->capture_default_str();
  app.add_option("--turbulence-coupling", o.turbulence_coupling,
                 "SA: segregated (one implicit nu_tilde step after each mean-flow step, eddy "
                 "viscosity lagged), coupled (mean flow and nu_tilde in one Newton step, 5x5 "
                 "blocks with their cross terms; with --matrix-free true the Krylov operator holds "
                 "every cross term) or auto (segregated until the density residual has fallen by "
                 "--coupling-switch-drop, coupled from then on)")
      ->check(CLI::IsMember({"segregated", "coupled", "auto"}))
      ->capture_default_str();
  app.add_option("--turbulence-jacobian", o.turbulence_jacobian,
                 "SA: linearisation of the nu_tilde equation in the implicit operator: exact (the "
                 "diffusion with d(nu + nu_tilde)/d nu_tilde and the whole source derivative) or "
                 "m-matrix (positive diffusion coefficients and the stabilising part of the "
                 "source only: diagonally dominant, but a Picard rather than a Newton step)")
      ->check(CLI::IsMember({"exact", "m-matrix"}))
      ->capture_default_str();
  app.add_option("--limiter-freeze-drop", o.settings.limiter_freeze_drop,
                 "second order: freeze the limiter once the density residual has fallen by this "
                 "factor (0: only after --limiter-stall-iterations without a new minimum); the "
                 "frozen limiter is a fixed, valid scheme and the Newton steps then see the "
                 "residual they drive to zero")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  app.add_option("--eisenstat-walker", o.settings.eisenstat_walker,
                 "matrix-free steps: GMRES tolerance by Eisenstat-Walker forcing (tighter as the "
                 "residual falls faster, down to 1e-3; --matrix-free-linear-tolerance the "
                 "loosest) instead of the fixed tolerance")
      ->capture_default_str();
  app.add_option("--limiter-stall-iterations", o.settings.limiter_stall_iterations,
                 "second order: freeze the limiter when the density residual has not reached a "
                 "new minimum for this many iterations (0: never; a chattering limiter)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  app.add_option("--held-limiter-max-drop", o.settings.held_limiter_max_drop,
                 "with --restart-limiter frozen: release the held limiter when the restart "
                 "state's density residual is above this fraction of the run's reference (a "
                 "large change since the restart file)")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  app.add_option("--ilu-fill", o.settings.ilu_fill_level,
                 "level of fill of the block ILU preconditioner (0: ILU(0), the pattern of the "
                 "first-order Jacobian; k: also the fill-in of level <= k)")
      ->check(CLI::Range(0, 8))
      ->capture_default_str();
  app.add_option("--coupling-switch-drop", o.settings.coupling_switch_drop,
                 "--turbulence-coupling auto: density residual drop from which the steps are "
                 "coupled")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option("--time-step", o.time.time_step,
                 "[s] time-accurate run (dual time stepping, BDF2) with this physical time step "
                 "from the restart or initial state; flow.h5 then holds time averages and the "
                 "wall pressure RMS (0: steady)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  app.add_option("--time-steps", o.time.time_steps, "number of physical time steps")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  app.add_option("--statistics-start", o.time.statistics_start,
                 "first physical step (1-based) that enters the time averages")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option("--inner-iterations", o.time.inner_iterations,
                 "pseudo-time iterations per physical time step (limit)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option("--inner-residual-drop", o.time.inner_residual_drop,
                 "[-] a physical step is converged when its density residual fell by this factor")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option("--statistics-tolerance", o.time.statistics_tolerance,
                 "[-] the time average counts as converged when the wall pressure means of the "
                 "window's two halves differ by less than this, relative to p0")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option("--entropy-fix", o.settings.entropy_fix,
                 "[-] Harten entropy-fix width as a fraction of the sound speed")
      ->capture_default_str();
  app.add_option("--max-iterations", o.settings.max_iterations, "nonlinear iteration limit")
      ->capture_default_str();
  app.add_option("--residual-drop", o.settings.residual_drop,
                 "[-] converged when the density residual fell by this factor")
      ->capture_default_str();
  app.add_option("--cfl-start", o.settings.cfl_start, "[-] initial CFL number")
      ->capture_default_str();
  app.add_option("--cfl-max", o.settings.cfl_max, "[-] largest CFL number of the ramp")
      ->capture_default_str();
  app.add_option("--cfl-stall-iterations", o.settings.cfl_stall_iterations,
                 "halve the CFL ceiling after this many iterations without a new residual minimum "
                 "(0: never)")
      ->capture_default_str();
  app.add_option(
         "--farfield-flux", o.farfield_flux,
         "far-field faces: roe (Roe flux against the free stream, differentiable: converges on "
         "jets into air at rest) or riemann (boundary state from the 1D Riemann invariants)")
      ->check(CLI::IsMember({"roe", "riemann"}))
      ->capture_default_str();
  app.add_flag("--exact-jacobian", o.settings.exact_jacobian,
               "first-order Roe Jacobian by finite differences (dissipation included) instead of "
               "frozen dissipation");
  app.add_option(
         "--stationary-tolerance", o.settings.stationary_tolerance,
         "[-] also converged when every wall pressure (relative to p0) and the wall pressure force "
         "change by less than this per iteration, --stationary-iterations times in a row (0: off)")
      ->capture_default_str();
  app.add_option("--stationary-iterations", o.settings.stationary_iterations,
                 "consecutive iterations the stationarity criterion must hold")
      ->capture_default_str();
  app.add_option("--linear-tolerance", o.settings.linear_tolerance,
                 "[-] relative GMRES tolerance per nonlinear iteration")
      ->capture_default_str();
  app.add_option(
         "--matrix-free-linear-tolerance", o.settings.matrix_free_linear_tolerance,
         "[-] relative GMRES tolerance of the matrix-free (--matrix-free true) second-order steps")
      ->check(CLI::Range(1e-6, 0.5))
      ->capture_default_str();
  app.add_option("--gmres-max-iterations", o.settings.gmres_max_iterations,
                 "GMRES iteration limit per nonlinear iteration")
      ->capture_default_str();
  app.add_option("--gmres-restart", o.settings.gmres_restart,
                 "GMRES Krylov basis size before a restart")
      ->check(CLI::Range(1, 500))
      ->capture_default_str();
  app.add_option("--print-every", o.settings.print_every,
                 "residual line on stderr every N iterations (0: none)")
      ->capture_default_str();
  o.settings.print_every = 10;

  const std::string command = tfmb::cli::command_line(argc, argv);
  return tfmb::cli::run_main(app, argc, argv, [&] {
    tfmb::Logger logger("tfmb-flow", common.verbosity());
    if (!restart.empty())
      o.restart_file = restart;
    o.wall_temperature = wall_temperature;
    o.throat_area = throat_area;
    o.settings.threads = common.threads > 0 ? common.threads : 1;
    if (common.quiet)
      o.settings.print_every = 0;
    o.command_line = command;
    const tfmb::flow::RunResult r = tfmb::flow::run(o, logger);
    return r.report.converged ? 0 : 1;
  });
}
