// Time-accurate runs by dual time stepping: each physical time step (second-order backward
// difference, FlowSolver::begin_time_step) is converged in pseudo time by the steady solver's
// own Newton-Krylov iteration, and time averages of the fields and wall traces, the RMS of the
// wall pressure and a history of the wall force are gathered over the statistics window. For
// flows that do not settle (separation, base flow), the mean is what a coupled run needs.
#pragma once

#include <array>
#include <vector>

#include "solver.hpp"

namespace tfmb::flow {

// The limiter of a second-order physical step's inner iterations. live: as in a steady solve,
// live until the inner residual stalls, then frozen where it stalled. predicted: evaluated once
// per step at the extrapolated state 2 U^n - U^(n-1) and held for the step
// (FlowSolver::hold_limiter_at_predicted_state), the step's iterations Newton-Krylov throughout.
enum class InnerLimiter { live, predicted };

// The inner Newton steps' GMRES tolerance with the predicted limiter: the inner residual is
// measured per volume, and a looser solve leaves its error in the smallest cells (nasa-2dcd
// SMOKE NPR 2.412: 1,210 inner iterations for 40 steps at 1e-2, 265 at 3e-3, 153 at 1e-3).
inline constexpr double kPredictedLimiterLinearTolerance = 1e-3;

struct TimeAccurateSettings {
  double time_step = 0.0;     // physical time step [s]
  int time_steps = 0;         // number of physical steps
  int statistics_start = 1;   // first step (1-based) that enters the averages
  int inner_iterations = 40;  // pseudo-time iterations per physical step
  // inner convergence: density residual down by this factor from its largest value in the step
  double inner_residual_drop = 1e-3;
  InnerLimiter inner_limiter = InnerLimiter::live;
  // GMRES tolerance of each inner Newton-Krylov step, fixed; 0: by the limiter, the steady
  // solver's Eisenstat-Walker forcing with the live one, kPredictedLimiterLinearTolerance with
  // the predicted one (see run_time_accurate)
  double inner_linear_tolerance = 0.0;
  // the mean counts as converged when the wall pressure means of the first and second halves of
  // the statistics window differ by less than this, relative to the reference pressure
  double statistics_tolerance = 5e-3;
  double reference_pressure = 1.0;  // [Pa]
  double cfl_start = 5.0;           // CFL of the first inner iteration of the first step
  double cfl_max = 1e4;
  int print_every = 0;  // progress line every N physical steps (0: none)
};

struct TimeHistoryRecord {
  double time = 0.0;  // [s] at the end of the step
  int inner_iterations = 0;
  double inner_residual_drop = 0.0;  // reached in the step
  Vec2 wall_force{};                 // pressure force on all wall curves [N/m] or [N/rad]
  State residual{};                  // RMS residual per equation after the inner iterations
};

struct TimeAccurateResult {
  // time averages over the statistics window, in the numbering of the input mesh
  std::vector<State> mean_primitive;
  std::vector<double> mean_nu_tilde;              // empty without SA
  std::vector<double> mean_k, mean_omega;         // empty without SST
  std::vector<WallTrace> mean_traces;             // per wall curve given
  std::vector<std::vector<double>> pressure_rms;  // per wall curve, per trace point [Pa]
  int averaged_steps = 0;
  // largest |mean over the second half - mean over the first half| of the wall pressure,
  // relative to the reference pressure
  double mean_change = 0.0;
  bool mean_converged = false;
  int unconverged_steps = 0;  // steps whose inner iterations stopped short of the drop
  long iterations = 0;        // inner iterations, all steps
  long linear_iterations = 0;
  long residual_evaluations = 0;
  double residual_seconds = 0.0;
  double wall_time = 0.0;  // [s]
  std::vector<TimeHistoryRecord> history;
};

// Advances `solver` from its current state by settings.time_steps physical steps.
TimeAccurateResult run_time_accurate(FlowSolver& solver, const TimeAccurateSettings& settings,
                                     const std::vector<int>& wall_curves);

}  // namespace tfmb::flow
