// tfmb-flow: steady 2D compressible flow (Euler, laminar Navier-Stokes or Spalart-Allmaras RANS,
// planar or axisymmetric) on a mixed triangle/quad flow mesh.
//
// Sample runs:
//   tfmb-flow flowmesh.h5 --p0 5.5e5 --T0 294 --ambient-pressure 101330 -o flow.h5
//   tfmb-flow flowmesh.h5 --p0 5.5e5 --T0 294 --restart flow_prev.h5 -o flow.h5
//   tfmb-flow flowmesh.h5 --p0 2e5 --T0 300 --model laminar --wall-temperature 400 -o flow.h5
//   tfmb-flow flowmesh.h5 --p0 2.44e5 --T0 294 --model sa --restart flow.h5 --time-step 2e-6
//     --time-steps 400 --statistics-start 201 -o flow_mean.h5      (time-accurate, averaged)
#include <algorithm>
#include <iostream>

#include "run.hpp"
#include "tfmb/common/cli.hpp"
#include "tfmb/common/errors.hpp"
#include "tfmb/common/options.hpp"

int main(int argc, char** argv) {
  CLI::App app{"Steady compressible flow on a flow mesh (tfmb/flowmesh) -> flow file (tfmb/flow).",
               "tfmb-flow"};
  // A later option overrides an earlier one, so that a workflow can append to a case's options
  // (the two-way loop sets --stationary-tolerance from the coupling residual).
  app.option_defaults()->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
  tfmb::cli::CommonOptions common;
  tfmb::cli::add_common_options(app, common);
  tfmb::flow::RunOptions o;
  // Defaults of the tool where they differ from the library's (RunOptions, SolverSettings),
  // which in-process callers and tests rely on; set before declaring, so --help shows them.
  // On by default: second order started from the initial state diverged where the first-order
  // start converges (NPARC 0.75 on 240 x 60 and 480 x 120, tools/tfmb-flow/README.md).
  o.first_order_start = true;
  // Internal flows start from the quasi-1D nozzle flow of their duct: NPARC 0.75 converged in
  // 58 and 73 iterations on 240 x 60 and 480 x 120 cells instead of 99 and 124 from gas at rest
  // (tools/tfmb-flow/README.md, "Quasi-one-dimensional start").
  o.initial_state = "auto";
  o.settings.print_every = 10;  // the library solver is silent; the tool reports progress
  std::filesystem::path restart;
  tfmb::cli::OptionTable table(app);
  // (no CLI::ExistingFile: a missing input is a bad input, exit 3 from its reader, as in every
  // stage, not a usage error)
  table.add("mesh", o.mesh_file, "", "flow mesh (tfmb/flowmesh)")->required();
  table.add_output(o.output, "flow file (tfmb/flow)");
  table.add("--restart", restart, "",
            "start from this flow file (same mesh topology, e.g. before a wall deformation)");
  table.add("--threads", o.settings.threads, "1",
            "OpenMP threads of the solver (0 counts as 1); results are deterministic for a given "
            "thread count",
            CLI::NonNegativeNumber);
  table.add("--p0", o.stagnation_pressure, "Pa",
            "inflow total pressure (needed with a stagnation inflow boundary)");
  table.add("--T0", o.stagnation_temperature, "K",
            "inflow total temperature (needed with a stagnation inflow boundary)");
  table.add("--ambient-pressure", o.ambient_pressure, "Pa",
            "outflow and far-field static pressure");
  table.add("--ambient-temperature", o.ambient_temperature, "K", "far-field static temperature");
  table.add("--freestream-mach", o.freestream_mach, "1", "far-field Mach number along +x");
  table.add("--inflow-angle", o.inflow_angle, "deg", "inflow direction from +x");
  table.add("--gamma", o.gamma, "1", "ratio of specific heats");
  table.add("--gas-constant", o.gas_constant, "J/(kg K)", "specific gas constant");
  table.add("--model", o.model, "",
            "euler, laminar (Sutherland viscosity, Pr 0.72), sa (Spalart-Allmaras RANS with ft2, "
            "SA-neg for negative nu_tilde, Pr_t 0.9), sa-noft2, sst (k-omega SST-2003, Menter, "
            "Kuntz and Langtry 2003, as NASA TMR defines it; k and omega solved segregated) or "
            "sst-v (TMR's SST-V: Menter 1994 with the vorticity in mu_t and the production)",
            CLI::IsMember({"euler", "laminar", "sa", "sa-noft2", "sst", "sst-v"}));
  table.add("--heat-transfer-dt", o.heat_transfer_dt, "K",
            "viscous runs with adiabatic walls: after converging, a probe run with the walls this "
            "much below the adiabatic wall temperature gives the heat transfer coefficient (0: "
            "skip)");
  table.add("--inflow-ramp", o.inflow_ramp, "1",
            "iterations over which the inflow total pressure rises from the free stream's total "
            "pressure to --p0 (-1: 50 for a jet into a far field above the free stream's total "
            "pressure, else 0)");
  table.add("--inflow-ramp-hold-mach", o.settings.inflow_ramp_hold_mach, "1",
            "the inflow ramp holds while the largest Mach number at the inflow's nodes is above "
            "this (0: never), so that the valve opens no faster than the duct fills",
            CLI::NonNegativeNumber);
  table.add("--initial-state", o.initial_state, "",
            "start state without --restart: uniform (the free stream; an internal flow from its "
            "inflow total conditions at Mach 0.2), quasi-1d (an internal flow, inflow at the "
            "smallest x and no far field: the quasi-one-dimensional nozzle flow of the duct's "
            "sections, choked throat and normal shock included) or auto (quasi-1d where it "
            "applies, else uniform)",
            CLI::IsMember({"uniform", "quasi-1d", "auto"}));
  table.add("--wall-temperature", o.wall_temperature, "K",
            "isothermal no-slip walls (laminar; default adiabatic)");
  table.add("--throat-area", o.throat_area, "m or m^2",
            "throat height per unit depth (planar) or area (axisymmetric) for the discharge "
            "coefficient (default: none computed)");
  table.add("--order", o.settings.order, "1", "spatial order of the convective fluxes, 1 or 2",
            tfmb::cli::range(1, 2));
  table.add("--limiter-coefficient", o.settings.venkat_wang, "1",
            "Venkatakrishnan-Wang epsilon as a fraction of each variable's range (smaller: "
            "stronger limiting at shocks; larger: smoother, more accurate boundary layers)");
  table.add("--wall-aligned-aspect-ratio", o.settings.wall_aligned_aspect_ratio, "1",
            "second order: at nodes whose neighbour distances differ by more than this factor and "
            "whose nearest boundary is a wall, gradients and reconstruction use wall-aligned "
            "vectors (needed on curved walls with thin wall layers; 0: Cartesian everywhere)",
            CLI::NonNegativeNumber);
  table.add_flag("--first-order-start,!--no-first-order-start", o.first_order_start,
                 "with --order 2 and no --restart: converge at first order first, then continue "
                 "at second order from that state (a restart from a first-order run, in one "
                 "call)");
  table.add("--second-order-cfl-start", o.second_order_cfl_start, "1",
            "with the first-order start: the second-order stage's initial CFL number and the "
            "base of its SER law (default: --cfl-start)",
            CLI::PositiveNumber);
  table.add("--first-order-start-drop", o.first_order_start_drop, "1",
            "with the first-order start: end the first-order stage once its density residual "
            "has fallen by this factor (or by --residual-drop or stationarity, if first)",
            tfmb::cli::range(0.0, 1.0));
  table.add("--matrix-free", o.matrix_free, "",
            "second order: true: each pseudo-time step solves with the Jacobian of the "
            "second-order residual applied matrix-free (Newton-Krylov), preconditioned by ILU "
            "of the first-order Jacobian; false: the first-order Jacobian alone (defect "
            "correction, cheaper per iteration but it converges linearly and caps the CFL on "
            "stretched wall layers); auto: defect correction while the limiter is live, "
            "Newton-Krylov from the iteration on which it is frozen (--limiter-freeze-drop, "
            "--limiter-stall-iterations)",
            CLI::IsMember({"false", "true", "auto"}));
  table.add_flag("--restart-fallback,!--no-restart-fallback", o.restart_fallback,
                 "a steady solve from --restart that does not converge is solved again from the "
                 "start state, as without --restart (logged)");
  table.add("--restart-limiter", o.restart_limiter, "",
            "second order from --restart: live: the limiter evaluated every iteration; "
            "frozen: held at the restart state's values from the first iteration (with "
            "--matrix-free auto: Newton-Krylov from there), for a converged second-order "
            "state restarted after a small change such as a wall deformation",
            CLI::IsMember({"live", "frozen"}));
  table.add("--turbulence-coupling", o.turbulence_coupling, "",
            "SA: segregated (one implicit nu_tilde step after each mean-flow step, eddy "
            "viscosity lagged), coupled (mean flow and nu_tilde in one Newton step, 5x5 "
            "blocks with their cross terms; with --matrix-free true the Krylov operator holds "
            "every cross term) or auto (segregated until the density residual has fallen by "
            "--coupling-switch-drop, coupled from then on)",
            CLI::IsMember({"segregated", "coupled", "auto"}));
  table.add("--turbulence-step-limit", o.turbulence_step_limit, "",
            "coupled SA steps: where nu_tilde would change by more than its scale "
            "|nu_tilde| + nu, node (the whole node's update is relaxed, mean flow too) or "
            "nu-tilde (nu_tilde's own update only; the mean flow takes its step)",
            CLI::IsMember({"node", "nu-tilde"}));
  table.add("--turbulence-update-limit", o.settings.max_turbulence_update, "1",
            "largest change of nu_tilde per node and iteration relative to |nu_tilde| + nu "
            "(SST: of k relative to k + its free-stream value); nu_tilde grows at most by the "
            "factor 1 + this per iteration",
            CLI::PositiveNumber);
  table.add("--turbulence-jacobian", o.turbulence_jacobian, "",
            "SA: linearisation of the nu_tilde equation in the implicit operator: exact (the "
            "diffusion with d(nu + nu_tilde)/d nu_tilde and the whole source derivative) or "
            "m-matrix (positive diffusion coefficients and the stabilising part of the "
            "source only: diagonally dominant, but a Picard rather than a Newton step)",
            CLI::IsMember({"exact", "m-matrix"}));
  table.add("--limiter-freeze-drop", o.settings.limiter_freeze_drop, "1",
            "second order: freeze the limiter once the density residual has fallen by this "
            "factor (0: only after --limiter-stall-iterations without a new minimum); the "
            "frozen limiter is a fixed, valid scheme and the Newton steps then see the "
            "residual they drive to zero",
            tfmb::cli::range(0.0, 1.0));
  table.add("--eisenstat-walker", o.settings.eisenstat_walker, "",
            "matrix-free steps: GMRES tolerance by Eisenstat-Walker forcing (tighter as the "
            "residual falls faster, down to 1e-3; --matrix-free-linear-tolerance the "
            "loosest) instead of the fixed tolerance");
  table.add("--newton-cfl-follows-drop", o.settings.newton_cfl_follows_drop, "",
            "second order, once the limiter is frozen and with every equation in the Newton "
            "step (inviscid, laminar or coupled turbulence): the CFL ceiling and number rise by "
            "the factor the density residual has fallen since then (pseudo-transient "
            "continuation toward Newton's steps; false: the ceiling stays)");
  table.add("--limiter-rise-iterations", o.settings.limiter_rise_iterations, "1",
            "second order: also freeze the limiter when the density residual has risen in this "
            "many iterations in a row at the CFL ceiling (0: never)",
            CLI::NonNegativeNumber);
  table.add("--limiter-stall-iterations", o.settings.limiter_stall_iterations, "1",
            "second order: freeze the limiter when the density residual has not reached a "
            "new minimum for this many iterations (0: never; a chattering limiter)",
            CLI::NonNegativeNumber);
  table.add("--line-search-halvings", o.settings.line_search_halvings, "1",
            "halve a defect-correction or first-order step after which the pseudo-time "
            "residual V/dt (u - u_before) + R(u) (density) is above --line-search-rise times "
            "the residual it was taken from, at most this many times (one residual evaluation "
            "each; the CFL number is cut by the fraction kept; 0: never)",
            tfmb::cli::range(0, 20));
  table.add("--line-search-rise", o.settings.line_search_rise, "1",
            "with --line-search-halvings: the largest accepted pseudo-time residual relative to "
            "the residual before the step",
            tfmb::cli::range(0.1, 100.0));
  table.add("--held-limiter-max-drop", o.settings.held_limiter_max_drop, "1",
            "with --restart-limiter frozen: release the held limiter when the restart "
            "state's density residual is above this fraction of the run's reference (a "
            "large change since the restart file)",
            tfmb::cli::range(0.0, 1.0));
  table.add("--node-ordering", o.node_ordering, "",
            "internal node order of the implicit system: rcm (reverse Cuthill-McKee) or lines "
            "(RCM with the wall-normal lines of stretched cells kept contiguous, so that the "
            "ILU solves along them exactly)",
            CLI::IsMember({"rcm", "lines"}));
  table.add("--ilu-partitions", o.settings.ilu_partitions, "1",
            "independent row ranges of the block ILU preconditioner (couplings between them "
            "dropped), factorised and applied in parallel; the same value gives the same result "
            "on any number of threads",
            tfmb::cli::range(1, 64));
  table.add("--ilu-fill", o.settings.ilu_fill_level, "1",
            "level of fill of the block ILU preconditioner (0: ILU(0), the pattern of the "
            "first-order Jacobian; k: also the fill-in of level <= k)",
            tfmb::cli::range(0, 8));
  table.add("--multigrid-levels", o.settings.multigrid_levels, "1",
            "levels of the aggregation multigrid preconditioner, the fine one included (double "
            "pairwise aggregation, block ILU smoothing, one V(1,1)-cycle per GMRES iteration); "
            "1: the block ILU alone",
            tfmb::cli::range(1, 8));
  table.add("--multigrid-post-smoother", o.multigrid_post_smoother, "",
            "the multigrid's smoothing step after each coarse correction: ilu (the block ILU "
            "again, the stronger one) or jacobi (block Jacobi: for operators on which an ILU "
            "step does not reduce the residual and the cycle stalls GMRES, e.g. nasa-2dcd NPR "
            "8.91 with SA)",
            CLI::IsMember({"ilu", "jacobi"}));
  table.add("--coupling-switch-drop", o.settings.coupling_switch_drop, "1",
            "--turbulence-coupling auto: density residual drop from which the steps are "
            "coupled",
            CLI::PositiveNumber);
  table.add("--time-step", o.time.time_step, "s",
            "time-accurate run (dual time stepping, BDF2) with this physical time step "
            "from the restart or initial state; flow.h5 then holds time averages and the "
            "wall pressure RMS (0: steady)",
            CLI::NonNegativeNumber);
  table.add("--time-steps", o.time.time_steps, "1", "number of physical time steps",
            CLI::NonNegativeNumber);
  table.add("--statistics-start", o.time.statistics_start, "1",
            "first physical step (1-based) that enters the time averages", CLI::PositiveNumber);
  table.add("--inner-iterations", o.time.inner_iterations, "1",
            "pseudo-time iterations per physical time step (limit)", CLI::PositiveNumber);
  table.add("--inner-residual-drop", o.time.inner_residual_drop, "1",
            "a physical step is converged when its density residual fell by this factor",
            CLI::PositiveNumber);
  table.add("--inner-limiter", o.inner_limiter, "",
            "time-accurate second order: live: as in a steady solve, live until the inner "
            "residual stalls; predicted: evaluated once per physical step at the state "
            "extrapolated to the new time level (2 U^n - U^(n-1)) and held for the step's "
            "Newton-Krylov iterations",
            CLI::IsMember({"live", "predicted"}));
  table.add("--inner-linear-tolerance", o.time.inner_linear_tolerance, "1",
            "time-accurate runs: GMRES tolerance of each inner Newton-Krylov step, fixed (0: "
            "the steady solver's forcing with --inner-limiter live, 1e-3 with predicted)",
            CLI::NonNegativeNumber);
  table.add("--statistics-tolerance", o.time.statistics_tolerance, "1",
            "the time average counts as converged when the wall pressure means of the "
            "window's two halves differ by less than this, relative to p0",
            CLI::PositiveNumber);
  table.add("--entropy-fix", o.settings.entropy_fix, "1",
            "Harten entropy-fix width as a fraction of the sound speed");
  table.add("--max-iterations", o.settings.max_iterations, "1", "nonlinear iteration limit");
  table.add("--residual-drop", o.settings.residual_drop, "1",
            "converged when the density residual fell by this factor");
  table.add("--cfl-start", o.settings.cfl_start, "1", "initial CFL number");
  table.add("--cfl-max", o.settings.cfl_max, "1", "largest CFL number of the ramp");
  table.add("--cfl-stall-iterations", o.settings.cfl_stall_iterations, "1",
            "halve the CFL ceiling after this many iterations without a new residual minimum "
            "(0: never)");
  table.add("--farfield-flux", o.farfield_flux, "",
            "far-field faces: roe (Roe flux against the free stream, differentiable: converges on "
            "jets into air at rest) or riemann (boundary state from the 1D Riemann invariants)",
            CLI::IsMember({"roe", "riemann"}));
  table.add("--roe-jacobian", o.roe_jacobian, "",
            "Roe flux in the assembled Jacobian: frozen (its dissipation matrix held fixed), "
            "exact-first-order (its exact derivative, dissipation matrix included, in the steps "
            "of the first-order residual: --order 1 and the first-order start; frozen in "
            "second-order steps) or exact (exact in every step); a failed linear solve with "
            "the exact one switches to the frozen one",
            CLI::IsMember({"frozen", "exact-first-order", "exact"}));
  table.add_flag("--exact-jacobian", o.exact_jacobian, "the same as --roe-jacobian exact");
  table.add("--stationary-tolerance", o.settings.stationary_tolerance, "1",
            "also converged when every wall pressure (relative to p0) and the wall pressure force "
            "change by less than this per iteration, --stationary-iterations times in a row (0: "
            "off)");
  table.add("--stationary-iterations", o.settings.stationary_iterations, "1",
            "consecutive iterations the stationarity criterion must hold");
  table.add("--linear-tolerance", o.settings.linear_tolerance, "1",
            "relative GMRES tolerance per nonlinear iteration");
  table.add("--matrix-free-linear-tolerance", o.settings.matrix_free_linear_tolerance, "1",
            "relative GMRES tolerance of the matrix-free (--matrix-free true) second-order steps",
            tfmb::cli::range(1e-6, 0.5));
  table.add("--gmres-max-iterations", o.settings.gmres_max_iterations, "1",
            "GMRES iteration limit per nonlinear iteration");
  table.add("--gmres-restart", o.settings.gmres_restart, "1",
            "GMRES Krylov basis size before a restart (0: none at first order, 20 at second)",
            tfmb::cli::range(0, 500));
  table.add("--print-every", o.settings.print_every, "1",
            "residual line on stderr every N iterations (0: none; -q: none)");

  const std::string command = tfmb::cli::command_line(argc, argv);
  return tfmb::cli::run_main(app, argc, argv, [&] {
    tfmb::Logger logger("tfmb-flow", common.verbosity());
    if (!restart.empty())
      o.restart_file = restart;
    o.settings.threads = std::max(o.settings.threads, 1);
    if (common.quiet)
      o.settings.print_every = 0;
    o.command_line = command;
    o.settings_toml = table.settings_toml();
    const tfmb::flow::RunResult r = tfmb::flow::run(o, logger);
    return r.report.converged ? 0 : 1;
  });
}
