// Steady compressible flow solver on median-dual cells: second-order Roe fluxes with limited
// least-squares reconstruction, implicit pseudo-time stepping with local time steps, a
// switched-evolution-relaxation CFL ramp (Mulder and van Leer 1985) and a first-order
// Jacobian solved by ILU(0)-preconditioned GMRES.
#pragma once

#include <array>
#include <functional>
#include <string>
#include <vector>

#include "bc.hpp"
#include "flux_viscous.hpp"
#include "gas.hpp"
#include "gradient_lsq.hpp"
#include "linear_solver.hpp"
#include "mesh_dual.hpp"
#include "multigrid.hpp"
#include "scalar_ilu.hpp"
#include "turbulence_sst.hpp"

namespace tfmb::flow {

enum class TurbulenceCoupling { segregated, coupled, automatic };

// The turbulence model of a turbulent run (SolverSettings::turbulent).
enum class TurbulenceModel { spalart_allmaras, sst };

// How the second-order pseudo-time steps are solved (SolverSettings::matrix_free).
enum class MatrixFree {
  off,  // defect correction: the first-order Jacobian alone
  on,   // Jacobian-free Newton-Krylov from the first second-order step
  // defect correction while the limiter is live, Newton-Krylov once it is frozen (see
  // SolverSettings::matrix_free)
  after_limiter_freeze,
};

enum class RoeJacobian { frozen, exact_first_order, exact };

struct SolverSettings {
  int order = 2;             // 1 or 2 (spatial accuracy of the convective fluxes)
  double entropy_fix = 0.1;  // Harten delta as a fraction of the sound speed
  bool limiter = true;       // Venkatakrishnan limiter on the reconstruction
  double venkat_k = 5.0;     // limiter smoothness constant K (mesh-size based epsilon)
  // When > 0, use Wang's epsilon = venkat_wang * (global range of each variable) instead of
  // the mesh-size based (K h)^3; keeps smooth boundary layers unlimited.
  double venkat_wang = 0.1;
  // Second order: measure the reconstruction at the nodes of stretched wall layers in the
  // wall-aligned frame (wall_aligned_stencil) where a node's neighbour distances differ by more
  // than this factor; 0: Cartesian everywhere.
  double wall_aligned_aspect_ratio = 4.0;
  // Second order: solve each pseudo-time step with the operator V/dt + dR/du of the
  // second-order residual applied matrix-free (residual differences), preconditioned by ILU(0)
  // of the first-order Jacobian (Jacobian-free Newton-Krylov, Knoll and Keyes 2004, J. Comput.
  // Phys. 193:357). false: the first-order Jacobian itself (defect correction), whose mismatch
  // with the second-order residual caps the CFL number on stretched wall layers.
  // after_limiter_freeze: defect correction while the limiter is live, then Newton-Krylov from
  // the iteration on which it is frozen (limiter_freeze_drop, limiter_stall_iterations; without
  // a limiter, on which those criteria are met). A live limiter is not differentiable: on a shock
  // it chatters, and Newton steps through it stalled or diverged (NPARC 0.75: drop 0.34 after 540
  // iterations), while defect correction, robust there, converges only linearly once the limiter is
  // frozen (NPARC 0.75 240 x 60: 70 more iterations for 5 orders; Newton-Krylov: 18).
  MatrixFree matrix_free = MatrixFree::after_limiter_freeze;
  // Freeze the limiter once the density residual has dropped by this factor (0: never), or when
  // it has not reached a new minimum for limiter_stall_iterations; stops limiter chatter from
  // stalling convergence near shocks (the frozen limiter is a fixed, valid scheme).
  double limiter_freeze_drop = 0.0;
  int limiter_stall_iterations = 25;
  // ... or when the density residual has risen in each of this many iterations in a row at the
  // CFL ceiling (0: never). Defect correction at a large CFL number is a fixed-point iteration
  // x <- x - J1^-1 R2(x); a steady rise there is a mode it amplifies (TMR plate: 6 % per
  // iteration at the leading edge from CFL 1e7), which no further iteration of it removes.
  int limiter_rise_iterations = 0;
  // A restart's limiter held from the start (hold_limiter(true)) is released at the first iteration
  // when the state's density residual is more than this fraction of the run's reference: the state
  // is then far from the one the limiter belongs to, and Newton steps through it fail. Measured on
  // configuration 2's coupling iterates (56k nodes): the held limiter converged restarts that
  // started at drops 2.5e-3 to 1.5e-2 (in 32-60 iterations instead of 83-2000) and failed after
  // 19-22 iterations at 0.15-0.63 (the first iterates after the largest wall motion).
  double held_limiter_max_drop = 5e-2;
  State reference_state{1.0, 1.0, 1.0, 1.0};  // rho, |u|, |u|, p scales for the limiter
  double cfl_start = 5.0;
  double cfl_max = 1e4;
  double cfl_growth = 2.0;    // largest CFL increase per iteration
  double ser_exponent = 1.0;  // CFL = cfl_start * (R_max / R_n)^ser_exponent
  // Besides SER, multiply the CFL by this factor after every update taken whole (no
  // relaxation) that did not raise the density residual by more than cfl_adaptive_residual_rise;
  // otherwise multiply by 0.7. The larger of the two laws wins. 0 or 1: SER only.
  double cfl_adaptive_growth = 1.5;
  double cfl_adaptive_residual_rise = 2.0;
  // Halve the CFL ceiling whenever the density residual has not reached a new minimum for this
  // many iterations (0: never). At large CFL the frozen-dissipation Jacobian is not the true
  // one, and on a jet into air at rest the Newton-like iteration can settle into a limit cycle
  // (residual oscillating at a constant level, updates taken whole) that no relaxation sees.
  int cfl_stall_iterations = 20;
  // Once the limiter is frozen (MatrixFree::after_limiter_freeze), raise the CFL ceiling, and
  // the SER value, by the factor the density residual has fallen since the Newton-Krylov phase
  // began, so that the pseudo-time term vanishes as the residual does and the last steps are
  // Newton's (pseudo-transient continuation, Kelley and Keyes 1998, SIAM J. Numer. Anal. 35:508:
  // dt_n grows as 1 / |R_n|). The growth per iteration stays bounded by cfl_growth. The ceiling
  // is there for the transient with a live limiter (cut by the stall rules above); NPARC 0.75
  // 240 x 60 otherwise finished its Newton phase at CFL 5e3, 2-4 times its residual each step.
  // Not with a segregated turbulence step: that step lags the mean flow's Newton step and needs
  // its pseudo-time term (nasa-2dcd NPR 8.91, the case's settings: CFL 5e8 after 50 iterations,
  // then GMRES at its 80-iteration limit and the residual creeping at 2-4).
  bool newton_cfl_follows_drop = true;
  // Start-up: raise the total pressure of every stagnation inflow linearly from
  // inflow_ramp_start_pressure to its value over this many iterations (0: none), as a valve
  // opening would. A nozzle started from air at rest with the full pressure ratio at the inflow
  // face sees a shock-tube transient that the implicit pseudo-time march crosses badly.
  int inflow_ramp_iterations = 0;
  double inflow_ramp_start_pressure = 0.0;  // [Pa]
  // ... and the ramp holds (does not rise this iteration) while the largest Mach number at a
  // stagnation inflow's nodes is above this (0: never). A valve opened faster than the duct
  // fills chokes the inflow face: the gas enters at Mach 1, runs supersonic into the duct, and
  // the normal shock that ends it then crawls out through the inflow in pseudo time (nasa-2dcd
  // NPR 8.91 with a 35-iteration ramp: inflow Mach above 1 from iteration 11, the shock at the
  // inflow face at iteration 66, where the 50-iteration ramp had reached a steady state). It
  // holds for at most inflow_ramp_iterations iterations in all.
  double inflow_ramp_hold_mach = 0.0;
  int max_iterations = 500;
  double residual_drop = 1e-8;  // converged when the density residual fell by this factor
  // The residual drop counts only at the CFL ceiling: a start-up stage (the first-order start)
  // that may end at a loose drop must not end inside its transient, where the residual dips
  // while a shock still travels (NPARC 0.75: a drop of 6e-3 at CFL 960, iteration 12).
  bool residual_drop_at_cfl_ceiling = false;
  // When > 0, also converged when the pressure at every wall node and the pressure force on the
  // walls change by less than this (relative to the reference pressure and to the force) per
  // iteration, stationary_iterations times in a row: what a coupled run needs from the flow.
  double stationary_tolerance = 0.0;
  int stationary_iterations = 10;
  // Reference density residual for the drop (0: the largest residual of this run). A restart
  // passes the reference of the run it continues, so a converged state stays converged.
  double residual_reference = 0.0;
  double linear_tolerance = 0.02;  // relative, per nonlinear iteration
  // The same for the matrix-free second-order steps, an inexact Newton method (Dembo, Eisenstat
  // and Steihaug 1982): each GMRES iteration there costs a residual evaluation, and solving to
  // 0.4 instead of 0.02 cut the total residual evaluations 2-6 fold on nasa-2dcd at equal
  // nonlinear iteration counts within 25 % (tools/tfmb-flow/README.md). Must stay below the 0.5
  // that a step needs to count toward stationarity.
  double matrix_free_linear_tolerance = 0.4;
  // Matrix-free steps: Eisenstat-Walker forcing (the tolerance above as its ceiling, this as its
  // floor) instead of the fixed tolerance
  bool eisenstat_walker = true;
  double eisenstat_walker_min = 1e-3;
  // GMRES basis size before a restart in the assembled solves; 0: the whole basis up to
  // gmres_max_iterations at first order (a first-order run and the first-order start), 20 in the
  // second-order defect-correction steps (see linear_step). The Newton-Krylov steps always keep
  // the whole basis.
  int gmres_restart = 0;
  // ILU(0) partitions (independent row ranges, see BlockIlu0): 2 lets two threads share the
  // preconditioner; the same value gives the same result on any number of threads.
  int ilu_partitions = 2;
  // Level of fill of the block ILU preconditioner (0: ILU(0); see BlockIlu0)
  int ilu_fill_level = 0;
  // Levels of the aggregation multigrid preconditioner (see AggregationMultigrid), the fine one
  // included; 1: the block ILU alone
  int multigrid_levels = 1;
  // ... and its smoothing step after each coarse correction
  AggregationMultigrid::PostSmoother multigrid_post_smoother =
      AggregationMultigrid::PostSmoother::ilu;
  int gmres_max_iterations = 80;
  // A step after which the density residual norm is more than this factor above the one before
  // it is taken back: the state before the step, the CFL number cut tenfold (0: never; see
  // take_back_jumped_step)
  double step_residual_jump = 100.0;
  // Line search on the pseudo-time residual (FlowSolver::shorten_rising_step): a
  // defect-correction or first-order step after which the density row of V/dt (u - u_before) +
  // R(u) is more than line_search_rise times the residual it was taken from is halved, at most
  // line_search_halvings times (0: never)
  int line_search_halvings = 0;
  double line_search_rise = 1.0;
  double max_relative_update = 0.5;  // largest relative change of rho or p per node and iteration
  // SA: largest change of nu_tilde per node and iteration relative to |nu_tilde| + nu (k-omega
  // SST: of k relative to k + its free-stream value), so nu_tilde grows at most by the factor
  // 1 + max_turbulence_update per iteration.
  double max_turbulence_update = 1.0;
  // ... and what that limit relaxes: the whole node (mean flow too), or nu_tilde's own update
  // only (FlowSolver::turbulence_relaxation). nu_tilde alone lets the mean flow take whole steps
  // where nu_tilde moves fast (the plume's shear layers); with the RCM ordering it froze the
  // nodes at Back-Massier-Gier's exit corner (README, "Coupled SA Newton step").
  bool limit_turbulence_alone = false;
  // Fraction of nodes whose update may be relaxed without slowing the CFL ramp.
  double relaxed_fraction_tolerated = 0.002;
  // Jacobian of the Roe flux in the assembled operator: the dissipation matrix held fixed, or
  // the exact derivative of the first-order flux (forward AD, |A_Roe|'s own dependence
  // included) in every step or only in the steps of the first-order residual (--order 1 and the
  // first-order start), where it is that residual's Newton Jacobian. Frozen by default: an
  // exact first-order iteration costs about 1.56 times a frozen one, more than it saves in
  // iterations on most benchmarks, and as the operator of second-order defect correction it
  // diverged at NPARC's shock (README, Roe Jacobian). A failed linear solve with the exact one
  // switches to the frozen one.
  RoeJacobian roe_jacobian = RoeJacobian::frozen;
  int print_every = 0;  // residual line on stderr every N iterations (0: silent)
  // Called after every iteration with its number, after any residual line (the tool's progress
  // display); reads nothing of the solution and changes nothing.
  std::function<void(int iteration)> on_iteration;
  bool viscous = false;
  ViscousModel viscosity;
  // Spalart-Allmaras RANS (needs viscous): the nu_tilde equation is solved segregated, one
  // implicit step (first-order upwind convection, same local time step) after each mean-flow
  // update, with the eddy viscosity lagged by one iteration in the mean-flow equations.
  bool turbulent = false;
  // Coupled: mean flow and nu_tilde in one Newton step, a 5x5 block system per node (the
  // segregated step lags the eddy viscosity by an iteration and never sees how the mean flow
  // responds to nu_tilde). With matrix_free the Krylov operator is the exact derivative of the
  // whole residual; the preconditioner is the first-order Jacobian with its cross blocks (mean
  // flow against nu_tilde through mu_t; nu_tilde against the mean flow through the convecting
  // velocity and the vorticity).
  // Automatic: segregated steps through the start-up transient (the coupled step's nu_tilde
  // limit relaxes whole nodes there and holds the CFL down), coupled from the iteration on
  // which the density residual has fallen by coupling_switch_drop.
  TurbulenceCoupling turbulence_coupling = TurbulenceCoupling::segregated;
  double coupling_switch_drop = 1e-2;
  // Spalart-Allmaras (the settings sa_* below) or Menter's k-omega SST (turbulence_sst.hpp):
  // SST's k and omega are solved segregated, one implicit step of each after the mean-flow step
  // (the coupled block system is SA's only so far).
  TurbulenceModel turbulence_model = TurbulenceModel::spalart_allmaras;
  sst::Variant sst_variant = sst::Variant::sst2003;
  bool sa_exact_jacobian = true;     // SA: the whole linearisation (else its M-matrix part)
  bool sa_ft2 = true;                // the ft2 term of standard SA (TMR "SA"); false: SA-noft2
  double sa_freestream_ratio = 3.0;  // nu_tilde / nu entering at inflow and far field (TMR)
  int threads = 1;                   // OpenMP threads used inside solve() and residual()
  // Renumber the nodes internally (reverse Cuthill-McKee): a banded matrix makes ILU(0) a much
  // stronger preconditioner. Node ids at the interface stay those of the mesh given.
  bool renumber = true;
  // With renumber: the lines of strongly coupled nodes (wall-normal columns of stretched
  // boundary-layer cells, strong_coupling_lines) kept contiguous in the RCM order, so that the
  // incomplete factorisation solves along them exactly.
  bool renumber_lines = false;
};

struct IterationRecord {
  int iteration = 0;
  State residual{};  // RMS of residual / volume per equation
  double cfl = 0.0;
  double relaxation = 1.0;  // smallest fraction of the Newton update applied at a node
  int linear_iterations = 0;
  double linear_residual = 0.0;
  // RMS of d nu_tilde / dt [m^2/s^2] (SA) or of dk/dt [m^2/s^3] (SST); 0 when laminar
  double turbulence_residual = 0.0;
  double wall_time = 0.0;            // since the start of solve() [s]
};

// The settings of the first-order start ahead of a second-order run with `second`
// (tfmb-flow --first-order-start): first order, ended once the density residual has fallen by
// `drop` (or by second.residual_drop, if smaller) at the CFL ceiling. The stage only has to get
// past the start-up transient, so it keeps at most the default ceiling and, for `auto`
// turbulence coupling, segregated SA steps: with a ceiling of 1e7 its end-at-the-ceiling rule let
// it converge outright (Back-Massier-Gier 321 x 81: 83 first-order iterations, drop 1e-10;
// nasa-2dcd NPR 8.91: 108, 1.7e-7), and coupled first-order steps took 67 iterations on BMG
// where segregated ones took 20, with the same second-order stage after either.
SolverSettings first_order_start_settings(const SolverSettings& second, double drop);

// The count of iterations in a row whose density residual rose at the CFL ceiling (within half
// of it), after an iteration with `residual` against `previous`: one more than `count` for a rise
// there, else 0 (SolverSettings::limiter_rise_iterations).
int rises_at_ceiling(int count, double residual, double previous, double cfl, double ceiling);

// Whether a pseudo-time march has diverged: with the CFL number below its start value and the
// density residual kRise times its best, kIterations iterations in a row (defect-correction
// steps only). A first-order start's shock transient does that for a few iterations and
// recovers by itself (NPARC 0.75, 240 x 60: 4 iterations at CFL 2-5, 200 times its best).
class DivergedMarch {
 public:
  static constexpr double kRise = 10.0;
  static constexpr int kIterations = 10;
  // This iteration's figures; true once the march has diverged (the count then starts afresh).
  bool diverged(bool newton_step, double cfl, double cfl_start, double residual, double best) {
    const bool running_away = !newton_step && cfl < cfl_start && residual > kRise * best;
    iterations_ = running_away ? iterations_ + 1 : 0;
    if (iterations_ < kIterations)
      return false;
    iterations_ = 0;
    return true;
  }

 private:
  int iterations_ = 0;  // in a row running away
};

struct SolveReport {
  bool converged = false;
  bool converged_by_stationarity = false;  // (rather than by the residual drop)
  double wall_pressure_change = 0.0;       // last iteration's largest relative wall-pressure change
  double wall_force_change = 0.0;  // last iteration's relative change of the wall pressure force
  int iterations = 0;
  long linear_iterations = 0;
  int backoffs = 0;          // CFL back-offs after non-physical states (and taken-back steps)
  int steps_taken_back = 0;  // steps whose residual jumped (take_back_jumped_step)
  int steps_shortened = 0;   // steps the line search halved (shorten_rising_step)
  int step_halvings = 0;     // ... and the halvings in all
  int coupled_from = 0;  // automatic coupling: first coupled iteration (0: none)
  // inflow ramp: the iteration at which it reached the full pressure (0: no ramp, or not
  // reached), and the iterations it held (SolverSettings::inflow_ramp_hold_mach)
  int inflow_ramp_end = 0;
  int inflow_ramp_held = 0;
  int newton_from = 0;  // MatrixFree::after_limiter_freeze: first Newton-Krylov iteration (0: none)
  int newton_fallbacks = 0;  // ... and its Newton phases abandoned for defect correction
  int best_state_restarts = 0;  // returns to the best state after the march diverged
  // exact Roe Jacobian: the iteration whose failed linear solve switched to the frozen one (0:
  // none)
  int roe_jacobian_frozen_from = 0;
  // A run that did not converge: why it stopped, where the density residual per volume was
  // largest at the end, and where the last update was relaxed most (and by how much).
  std::string stop_reason;
  Vec2 worst_residual_at{};
  // ... and where each equation's residual per volume is largest (density, x and y momentum,
  // energy, nu_tilde; for SST's k: where the density's is), for the log to say where the
  // equation furthest from converged stands
  std::array<Vec2, 5> largest_residual_at{};
  Vec2 least_relaxed_at{};
  double least_relaxation = 1.0;
  double residual_drop = 1.0;       // final density residual / reference density residual
  double residual_reference = 0.0;  // the reference used (RMS of residual/volume)
  double wall_time = 0.0;           // [s]
  double final_cfl = 0.0;           // CFL number of the last iteration
  // residual evaluations (one per nonlinear iteration, one per matrix-free product) and the
  // time spent in them: the cost per node of the scheme itself
  long residual_evaluations = 0;
  double residual_seconds = 0.0;
  std::vector<IterationRecord> history;
};

// Integrated boundary fluxes over one boundary curve, out of the domain; per unit depth
// (planar) or per radian (axisymmetric).
struct BoundaryIntegral {
  double mass_flow = 0.0;    // [kg/s]
  Vec2 force{};              // momentum flux plus pressure force on the boundary [N]
  double energy_flow = 0.0;  // [W]
};

// Quantities along one boundary curve, at its nodes in curve order.
struct WallTrace {
  std::vector<int> node;
  std::vector<double> s;            // arc length from the curve's first node [m]
  std::vector<double> x, y;         // [m]
  std::vector<double> pressure;     // [Pa]
  std::vector<double> temperature;  // [K]
  // Tangential traction of the fluid on the wall along the curve direction [Pa] (0 if inviscid).
  std::vector<double> shear_stress;
  // Heat flux from the fluid into the wall [W/m^2] (0 if inviscid).
  std::vector<double> heat_flux;
  // Unit normal leaving the fluid (into the wall) at each node: the sum of the node's outward
  // boundary dual-face normals on this curve, normalised.
  std::vector<Vec2> normal;
};

class FlowSolver {
 public:
  // bcs[b] applies to mesh.boundaries[b]. Node ids and per-node arrays at this interface use the
  // numbering of `mesh`; dual() is in the solver's internal numbering.
  FlowSolver(const Mesh& mesh, Geometry geometry, const PerfectGas& gas,
             std::vector<BoundaryCondition> bcs, const SolverSettings& settings);

  void set_uniform(const State& w);
  void set_primitive(const std::vector<State>& w);
  std::vector<State> primitive() const;
  // Spalart-Allmaras working variable nu_tilde [m^2/s] per node (empty without SA), the eddy
  // viscosity [Pa s] and the wall distance [m] it uses.
  void set_nu_tilde(const std::vector<double>& nu_tilde);
  std::vector<double> nu_tilde() const;
  std::vector<double> eddy_viscosity();
  std::vector<double> wall_distance() const;
  // SST's k [m^2/s^2] and omega [1/s] per node (empty unless SST); set_sst() keeps the wall
  // values (k = 0, omega from the wall condition) whatever is given there.
  void set_sst(const std::vector<double>& k, const std::vector<double>& omega);
  std::vector<double> sst_k() const;
  std::vector<double> sst_omega() const;
  std::vector<State> conservative() const;
  const std::vector<Vec2>& node_coords() const { return coords_external_; }
  std::vector<double> node_area() const;  // planar dual-cell areas [m^2]

  SolveReport solve();

  // Turns every adiabatic no-slip wall into an isothermal one at the current wall temperature
  // minus `below` [K], node by node: the probe run of the heat transfer coefficient
  // h = (q_probe - q_adiabatic) / below (see run.cpp).
  void make_walls_isothermal(double below);
  // The next solve() starts with the limiter frozen at the current state's values (those of the
  // state the previous solve ended in, or, after set_primitive(), evaluated once on the new
  // state), instead of letting it move: for a small change of a converged state, such as the
  // probe's wall temperature or a restart on a slightly deformed mesh, a linearisation about
  // that state. With --matrix-free auto the run then starts with Newton-Krylov steps.
  // release_if_far: a restart's hold, let go at the first iteration if the state is far from
  // converged (held_limiter_max_drop); the probe's hold is kept whatever its first residual (the
  // wall temperature step raises it, and a limiter let go there gave negative h).
  void hold_limiter(bool release_if_far = false) {
    hold_limiter_ = true;
    release_held_limiter_ = release_if_far;
  }
  void set_residual_reference(double reference) { settings_.residual_reference = reference; }
  void set_residual_drop(double drop) { settings_.residual_drop = drop; }
  // Dual time stepping (Jameson 1991, AIAA 91-1596): from this call on, the residual holds the
  // physical time derivative V dU/dt by the second-order backward difference
  // (3 U - 4 U^n + U^(n-1)) / (2 dt), the first step by the first-order one (U - U^n) / dt,
  // with U^n the current state; solve() then converges one physical step in pseudo time.
  // Call once per physical step, after the previous one has converged.
  void begin_time_step(double dt);
  // Iteration control of the pseudo-time (inner) solve of a physical time step: iteration
  // limit, density residual drop relative to the step's largest residual, starting CFL and
  // progress lines; no stationarity criterion, no inflow ramp.
  void set_inner_iteration_control(int max_iterations, double residual_drop, double cfl_start,
                                   int print_every);
  // The GMRES tolerance of every Newton-Krylov step from here on, fixed (no Eisenstat-Walker
  // forcing): the inner steps of a physical time step.
  void set_newton_linear_tolerance(double tolerance) {
    settings_.matrix_free_linear_tolerance = tolerance;
    settings_.eisenstat_walker = false;
  }
  // Time-accurate runs, after begin_time_step(): the next solve() holds the limiter evaluated
  // at the second-order extrapolation of the state to the new time level,
  // U* = 2 U^n - U^(n-1) (U^n on a first-order backward-difference step, and where U* is not
  // physical), and starts
  // from U^n, with Newton-Krylov steps (--matrix-free auto) from its first iteration. The
  // limiter's lag is then O(dt^2), like BDF2's own error, and the inner iteration has no live
  // limiter to chatter (see run_time_accurate()).
  void hold_limiter_at_predicted_state();
  double time_step() const { return time_dt_; }
  void set_inflow_ramp(int iterations) { settings_.inflow_ramp_iterations = iterations; }
  // The CFL number the next solve() starts from, and the base of its SER law
  void set_cfl_start(double cfl) { settings_.cfl_start = cfl; }

  // Checks of the implicit operator (tests): y = J x for the steady residual at the current
  // state, x and y per node of the mesh given, 4 unknowns per node (5 with
  // SA: nu_tilde last, its row scaled as in the coupled system). `assembled`: the first-order
  // matrix that preconditions the Newton steps (cross blocks included); otherwise the
  // difference quotient of the residual, the Krylov operator of --matrix-free.
  std::vector<double> jacobian_product(const std::vector<double>& x, bool assembled);

  // Residual R(U) (flux balance, positive = net outflow) for the current state; per node.
  std::vector<State> residual();
  BoundaryIntegral boundary_integral(int curve);
  WallTrace wall_trace(int curve);
  std::vector<WallTrace> wall_traces(const std::vector<int>& curves);  // same, several at once

  const DualMesh& dual() const { return dual_; }
  // settings.renumber_lines: the lines kept contiguous and the nodes on them
  int ordering_lines() const { return ordering_lines_; }
  int ordering_line_nodes() const { return ordering_line_nodes_; }
  const PerfectGas& gas() const { return gas_; }

 private:
  void compute_residual(bool update_limiter);  // evaluate_residual, counted and timed
  void evaluate_residual(bool update_limiter);
  bool exact_roe_jacobian_by_settings() const;
  void assemble_jacobian(const std::vector<double>& diag_scale);
  // V a0 / dt of the physical time derivative at node i (0 for a steady solve)
  double physical_time_diagonal(int i) const {
    return time_dt_ > 0.0 ? dual_.volume[i] * time_a_[0] / time_dt_ : 0.0;
  }
  void add_physical_time_derivative();
  void apply_strong_conditions(std::vector<State>& u) const;
  WallTrace trace_of(int curve) const;  // from the current w_ and grad_
  bool physical(const std::vector<State>& u) const;
  void update_eddy_viscosity();
  double wall_temperature_at(int bc, int node) const;
  double turbulence_step(double cfl);  // segregated; returns the RMS of d nu_tilde / dt
  // Residual of the nu_tilde equation, sa_res_ = -V d nu_tilde/dt (net outflow sign, as res_;
  // on no-slip walls nu_tilde itself, whose strong value is 0), and with `jacobian` its scalar
  // Jacobian in sa_diag_ / sa_offdiag_ (settings_.sa_exact_jacobian: the whole derivative;
  // otherwise an M-matrix: upwind convection, the positive diffusion coefficients, the
  // stabilising part of the source), the diagonal starting from diag_scale (V/dt) when given;
  // for the coupled system also the cross terms sa_cross_diag_ / sa_cross_offdiag_.
  void turbulence_residual(bool jacobian, const std::vector<double>* diag_scale);
  double turbulence_residual_norm() const;  // RMS of sa_res_ / V off the walls
  // Inflow of turbulence through a boundary face (inflow, far field, or backflow through an
  // outflow; not walls, symmetry or slip walls): the face's inward normal velocity times its
  // area (negative), 0 where none enters; `outside` the state whose free-stream turbulence
  // enters (the far field's, else the node's own)
  double turbulence_inflow(const BoundaryFace& face, State& outside) const;
  // The coupled 5x5 system: mean-flow blocks of jac_, the nu_tilde row of sa_diag_ and
  // sa_offdiag_ scaled by sa_row_scale_, and the cross blocks: mean-flow rows against
  // nu_tilde through mu_t in the viscous fluxes, the nu_tilde row against the mean flow
  // through the convecting velocity.
  void assemble_coupled_jacobian();
  // assemble_jacobian()'s edge and boundary fluxes and the pseudo-time diagonal
  void assemble_first_order_fluxes(const std::vector<double>& diag_scale);
  // thin-shear viscous flux Jacobian of edge e against its two nodes' conservative states (and
  // d f_e / d mu_t in edge_flux_eddy_slope_ when coupled)
  void viscous_edge_jacobian(int e, Block& left, Block& right);
  const BlockSparseMatrix& system_matrix() const {
    return turbulence_coupled_ ? jac_coupled_ : jac_;
  }
  void set_freestream_nu_tilde();
  // SST (solver_sst.cpp): the wall condition's distances, the free-stream start, mu_t, and the
  // segregated implicit step of k and omega (returns the RMS of dk/dt)
  bool sst() const {
    return settings_.turbulent && settings_.turbulence_model == TurbulenceModel::sst;
  }
  void init_sst();
  void set_freestream_sst();
  void apply_sst_wall_values();
  void update_sst_eddy_viscosity();
  double sst_step(double cfl);
  // The turbulence variables for the march's returns to an earlier state: nu_tilde (SA) or k
  // then omega (SST); empty when laminar
  std::vector<double> turbulence_snapshot() const;
  void restore_turbulence(const std::vector<double>& snapshot);
  State residual_norm() const;
  // y = (V/dt + dR/du) x of the current residual, see SolverSettings::matrix_free
  LinearOperator matrix_free_operator(const std::vector<double>& diag_scale);

  // solve()'s pseudo-time loop in phases, in the order they run (solver.cpp); SolveLoop holds
  // the loop's running variables
  struct SolveLoop;
  void start_run(SolveLoop& s);
  bool newton_krylov_step(const SolveLoop& s) const;  // this step's kind
  // the turbulence equation has its own step after the mean flow's (not in the Newton system)
  bool segregated_turbulence_step(const SolveLoop& s) const;
  void switch_turbulence_coupling(SolveLoop& s);
  void ramp_inflow(SolveLoop& s);
  double largest_inflow_mach() const;
  void back_off_to_good_state(SolveLoop& s);
  void release_held_limiter_if_far(const SolveLoop& s);
  bool right_after_comparable_step(const SolveLoop& s, double before) const;
  bool right_after_comparable_step(const SolveLoop& s) const;
  double pseudo_time_residual_norm(const SolveLoop& s) const;
  void shorten_rising_step(SolveLoop& s);
  bool take_back_jumped_step(SolveLoop& s);  // true: went back to the state before the step
  bool track_residual(SolveLoop& s);  // true: went back to the best state
  void cut_cfl_ceiling_on_stall(SolveLoop& s);
  void freeze_limiter(SolveLoop& s);
  bool abandon_failed_newton_phase(SolveLoop& s);  // true: went back to the phase's start
  void update_cfl(SolveLoop& s);
  void begin_record(SolveLoop& s);
  bool wall_stationary(SolveLoop& s);
  bool check_convergence(SolveLoop& s);  // true: converged
  void linear_step(SolveLoop& s);
  int assembled_solve_restart() const;
  // the block ILU or, with multigrid_levels > 1, the aggregation multigrid of the system matrix
  void factorize_preconditioner();
  const Preconditioner& preconditioner() const;
  GmresResult newton_krylov_solve(SolveLoop& s);
  void relax_update(SolveLoop& s);
  double node_relaxation(int i, const double* du_i, bool coupled, State& un) const;
  double turbulence_relaxation(int i, double du_nu, double omega_i) const;
  void accept_or_reject_step(SolveLoop& s);
  void report_progress(SolveLoop& s);
  bool march_stopped(SolveLoop& s);  // true: the run gives up
  void finish_run(SolveLoop& s);
  // the node whose residual per volume in equation v (0-3: the mean flow's, 4: nu_tilde) is
  // largest, over the rows the residual norm counts
  int worst_residual_node(int v = 0) const;
  // whether residual_norm() counts equation v (0-3) of node i (not imposed there)
  bool residual_row_counted(int i, int v) const;

  Mesh mesh_;  // internal numbering
  std::vector<int> new_of_old_, old_of_new_;
  int ordering_lines_ = 0, ordering_line_nodes_ = 0;
  std::vector<Vec2> coords_external_;
  DualMesh dual_;
  PerfectGas gas_;
  std::vector<BoundaryCondition> bcs_;
  SolverSettings settings_;
  LsqGradient lsq_;
  // second-order reconstruction: its stencil vectors and gradient (the viscous terms keep the
  // Cartesian lsq_/grad_); recon_mapped_ false when they equal the Cartesian ones
  StencilGeometry recon_stencil_;
  LsqGradient recon_lsq_;
  bool recon_mapped_ = false;
  int recon_mapped_nodes_ = 0;
  std::vector<Vec2> recon_half_ij_,
      recon_half_ji_;  // per edge: half the vector from i to j, from j to i
  std::vector<std::array<double, 8>> recon_grad_;
  std::vector<State> venkat_eps_;
  std::vector<int> edge_pos_ij_, edge_pos_ji_;  // BSR positions of the off-diagonal blocks
  std::vector<int> wall_node_bc_;               // -1 or the no-slip bc index per node
  // Nodes on a far field whose free stream enters supersonically: every characteristic comes
  // from outside, so the node state is imposed strongly (conservative, per node; empty state
  // marks free nodes via fixed_node_).
  std::vector<char> fixed_node_;
  std::vector<State> fixed_u_;
  std::vector<int> assembled_rows_;  // nodes whose rows of the matrix-free operator are assembled

  bool turbulence_coupled_ = false;  // this iteration solves the coupled 5x5 system
  std::vector<State> u_, w_, res_, phi_, edge_flux_;
  // per boundary face: its flux and its spectral radius term (evaluate_residual)
  std::vector<State> face_flux_;
  std::vector<double> face_spectral_radius_;
  // The state and residuals the matrix-free operator differences against (its last call's)
  struct MatrixFreeBase {
    std::vector<State> u, res;
    std::vector<double> nu, sa_res, nu_scale;
  };
  MatrixFreeBase matrix_free_base_;
  std::vector<std::array<double, 8>> grad_;
  std::vector<double> nu_tilde_, eddy_viscosity_, wall_distance_;
  // SST: k, omega, and per no-slip node 60 / (beta1 d1^2) (omega_wall = that times nu)
  std::vector<double> sst_k_, sst_omega_, sst_wall_omega_scale_;
  ScalarIlu0 sst_ilu_;
  std::vector<double> sa_res_, sa_diag_, sa_offdiag_;
  // Coupled system only: d sa_res_i / d U_i (4 per node) and d sa_res_i / d U_j (4 per node
  // edge incidence) through the convecting velocity, and d f_e / d mu_t at each edge (f_e the
  // flux of edge e in res_, through the eddy viscosity in the viscous flux).
  std::vector<double> sa_cross_diag_, sa_cross_offdiag_;
  std::vector<State> edge_flux_eddy_slope_;
  std::vector<double> sa_nu_, sa_diffusivity_;  // scratch of turbulence_residual()
  // Scale of the nu_tilde rows in the coupled system: the reference density, so that the row
  // reads as the transport of rho nu_tilde beside the mass, momentum and energy rows.
  double sa_row_scale_ = 1.0;
  BlockSparseMatrix jac_coupled_;
  std::vector<double> spectral_radius_;  // sum over faces of (|V.n| + c|n|) per node
  BlockSparseMatrix jac_;
  BlockIlu0 ilu_;
  AggregationMultigrid multigrid_;
  ScalarIlu0 sa_ilu_;
  GmresWorkspace gmres_workspace_;
  bool limiter_frozen_ = false;
  // The Roe flux's exact derivative in this solve's assembled Jacobian (settings_.roe_jacobian
  // for its order); false from the first failed linear solve on (accept_or_reject_step).
  bool exact_roe_jacobian_ = false;
  bool hold_limiter_ = false;  // see hold_limiter()
  bool release_held_limiter_ = false;
  bool limiter_stale_ = true;  // phi_ not yet evaluated on the current state (set_primitive)
  long residual_evaluations_ = 0;  // since construction (see SolveReport)
  double residual_seconds_ = 0.0;
  // dual time stepping: dt, the backward-difference coefficients a0 U - a1 U^n + a2 U^(n-1),
  // the two previous time levels (internal numbering, conservative) and nu_tilde's
  double time_dt_ = 0.0;
  std::array<double, 3> time_a_{};
  std::vector<State> time_u_n_, time_u_nm1_;
  std::vector<double> time_nu_n_, time_nu_nm1_;  // SST: k then omega (turbulence_snapshot())
};

}  // namespace tfmb::flow
