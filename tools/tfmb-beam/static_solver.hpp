// Nonlinear static analysis: Newton-Raphson with load stepping and automatic cut-back
// (FORMULATION.md sec. 3, "Statics").
#pragma once

#include <functional>
#include <vector>

#include "tfmb-beam/assembly.hpp"

namespace tfmb::beam {

struct StaticOptions {
  int initial_steps = 10;          // load steps to reach load factor 1 if nothing fails
  int max_steps = 1000;            // including cut-back retries
  int max_iterations = 30;         // Newton iterations per step
  int max_cutbacks = 12;           // halvings of a step before giving up
  double tolerance = 1e-10;        // ||residual|| <= tolerance * force scale, or
  /// ||correction|| <= this * ||increment of the step||: with quadratic convergence the state is
  /// then converged to ~this^2 relative.
  double increment_tolerance = 1e-8;
  double final_load_factor = 1.0;
  /// Start each step from the previous step's change scaled to the new step (secant predictor);
  /// off by default: on the strongly nonlinear benchmarks it did not save iterations.
  bool secant_predictor = false;
  /// Largest nodal rotation per Newton correction [rad]; larger corrections are scaled down.
  double max_rotation_increment = 0.25;
  /// Called after every converged step with (load factor, state).
  std::function<void(double, const State&)> on_step;
};

struct StaticResult {
  bool converged = false;
  double load_factor = 0.0;       // last converged load factor
  int steps = 0;                  // converged steps
  int iterations = 0;             // total Newton iterations
  int cutbacks = 0;
  State state;                    // last converged state
};

/// Solves from `initial` (usually assembly.initial_state()); never throws on non-convergence
/// (result.converged = false with the last converged state), throws ModelError for mechanisms.
StaticResult solve_static(const Assembly& assembly, const State& initial, const StaticOptions& options = {});

/// Converged states at the given increasing load factors, reached one after the other from
/// `initial`; a level Newton does not reach directly is approached in halved sub-steps (up to
/// options.max_cutbacks halvings). Returns fewer states than levels if a level cannot be reached.
std::vector<State> solve_at_load_factors(const Assembly& assembly, const State& initial,
                                         const std::vector<double>& load_factors, const StaticOptions& options = {});

struct ArcLengthOptions {
  double initial_load_increment = 0.05;  // first step's load-factor increment (sets the arc length)
  double final_load_factor = 1.0;        // stop once the load factor reaches this ...
  double max_displacement = 1e300;       // ... or any nodal displacement exceeds this [m]
  int max_steps = 200;
  int max_iterations = 20;
  int desired_iterations = 5;            // the arc length adapts towards this
  double tolerance = 1e-9;               // relative residual
  std::function<void(double, const State&)> on_step;
};

/// Arc-length continuation (Crisfield's cylindrical arc length on the nodal translations) for
/// paths with limit points (snap-through), where load control fails.
StaticResult solve_arc_length(const Assembly& assembly, const State& initial, const ArcLengthOptions& options);

/// One Newton solve at a fixed load factor; returns true on convergence. Updates `state`.
bool newton_static(const Assembly& assembly, State& state, double load_factor, const StaticOptions& options,
                   int& iterations);

}  // namespace tfmb::beam
