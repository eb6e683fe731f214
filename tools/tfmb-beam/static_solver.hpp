// Nonlinear static analysis: Newton-Raphson with load stepping and automatic cut-back
// (FORMULATION.md sec. 3, "Statics").
#pragma once

#include <functional>
#include <vector>

#include "tfmb-beam/assembly.hpp"

namespace tfmb::beam {

/// One converged state on the load path of a static solve (row 0: the initial state).
struct PathPoint {
  double load_factor = 0.0;
  /// Length of the path so far in the nodal translations, sum of ||du|| over the steps [m]
  /// (the arc-length solver's arc measure, Crisfield 1981 cylindrical form).
  double arc_length = 0.0;
  double max_displacement = 0.0;  // largest nodal displacement ||x - X|| [m]
  /// Displacement of the monitored node (PathMonitor) [m]; zero without one.
  Eigen::Vector3d node_displacement = Eigen::Vector3d::Zero();
  /// The characteristic displacement whose turning points are limit points in displacement:
  /// node_displacement . direction with a monitored node, else max_displacement [m].
  double characteristic_displacement = 0.0;
  int iterations = 0;  // Newton iterations of the step (cut-back attempts included)
};

/// A node whose displacement is written on the path (e.g. the load point), and the direction
/// along which its displacement is the characteristic one (e.g. the load's).
struct PathMonitor {
  int node = -1;  // -1: none
  Eigen::Vector3d direction = Eigen::Vector3d::UnitY();
};

/// Rows of a path that are limit points. Row i (0 < i < n - 1) is a limit point in load if the
/// load-factor increments before and after it have opposite signs, and in displacement if the
/// characteristic displacement's increments do (a snap-back); Crisfield (1991) sec. 9.1.
struct LimitPoints {
  std::vector<int> load;
  std::vector<int> displacement;
};
LimitPoints find_limit_points(const std::vector<PathPoint>& path);

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
  /// Try each solve with full (uncapped) Newton corrections first and fall back to the capped
  /// ones only if that fails: with the exact tangent, full steps converge the end-moment roll-up
  /// (one to four turns) in one load step, where the cap needs 41 to 240 iterations.
  bool full_steps_first = true;
  /// Called after every converged step with (load factor, state).
  std::function<void(double, const State&)> on_step;
  PathMonitor monitor;
};

struct StaticResult {
  bool converged = false;
  double load_factor = 0.0;       // last converged load factor
  int steps = 0;                  // converged steps
  int iterations = 0;             // total Newton iterations
  int cutbacks = 0;
  State state;                    // last converged state
  std::vector<PathPoint> path;    // initial state, then every converged step
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
  int max_steps = 500;                   // converged steps
  int max_iterations = 20;
  int desired_iterations = 5;   // the arc length adapts towards this (Crisfield 1981)
  double max_growth = 2.0;      // largest growth of the arc per step ...
  double max_arc_factor = 4.0;  // ... and of the arc over the first step's
  int max_cutbacks = 16;        // consecutive halvings of the arc before giving up
  /// A converged step whose increment turns back on the previous one by more than this angle
  /// [rad] has jumped to another branch (or doubled back): it is refused and the arc halved.
  double max_turn = 0.5 * 3.14159265358979323846;
  double tolerance = 1e-9;               // relative residual
  std::function<void(double, const State&)> on_step;
  PathMonitor monitor;
};

/// Arc-length continuation (Crisfield's cylindrical arc length on the nodal translations) for
/// paths with limit points in load (snap-through) and in displacement (snap-back), where load
/// control fails. The predictor keeps the direction of travel: its sign is that of the dot product
/// of the tangent with the previous step's increment (Feng, Peric & Owen 1996); the corrector root
/// is the one closest in direction to the current increment (Crisfield 1981); the arc is halved on
/// a failed or turned-back step and adapts to the Newton iterations of easy ones.
StaticResult solve_arc_length(const Assembly& assembly, const State& initial, const ArcLengthOptions& options);

/// One Newton solve at a fixed load factor; returns true on convergence. Updates `state`.
bool newton_static(const Assembly& assembly, State& state, double load_factor, const StaticOptions& options,
                   int& iterations);

}  // namespace tfmb::beam
