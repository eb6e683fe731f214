#pragma once
// Implicit transient conduction: backward Euler or variable-step BDF2, Newton at every step.
//
// Step control (stated): after an accepted step with largest nodal change dT_max, the next
// step is dt * clamp(0.9 * target / dT_max, 0.5, 2), limited to [min_step, max_step]; a step
// whose dT_max exceeds 2 * target, or whose Newton iteration fails, is rejected and retried
// with half the step. Steps are shortened to land exactly on output times.
#include "tfmb-heat/assembly.hpp"

#include <vector>

namespace tfmb::heat {

enum class TimeScheme { backward_euler, bdf2 };

struct TransientSettings {
  TimeScheme scheme = TimeScheme::bdf2;
  double end_time = 1.0;      // [s]
  double initial_step = 1e-3; // [s]
  double min_step = 1e-9;     // [s]; a rejection below it throws std::runtime_error
  double max_step = 1e300;    // [s]
  bool adaptive = true;       // false: constant initial_step
  double target_temperature_change = 2.0;  // [K] per step, for the adaptive control
  std::vector<double> output_times;        // [s], increasing, in (0, end_time]
  NewtonSettings newton;
};

struct TransientResult {
  std::vector<double> times;                  // [s] output times reached
  std::vector<Eigen::VectorXd> temperatures;  // [K] per node at those times
  int accepted_steps = 0;
  int rejected_steps = 0;
  int newton_iterations = 0;
};

/// Integrates from the nodal initial temperature [K] at t = 0 to end_time.
TransientResult solve_transient(const ThermalProblem& problem,
                                const Eigen::VectorXd& initial_temperature,
                                const TransientSettings& settings);

}  // namespace tfmb::heat
