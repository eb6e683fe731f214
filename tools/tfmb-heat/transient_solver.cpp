#include "tfmb-heat/transient_solver.hpp"

#include "tfmb-heat/steady_solver.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace tfmb::heat {

TransientResult solve_transient(const ThermalProblem& problem,
                                const Eigen::VectorXd& initial_temperature,
                                const TransientSettings& settings) {
  if (!(settings.end_time > 0.0) || !(settings.initial_step > 0.0) ||
      !(settings.min_step > 0.0) || !(settings.max_step >= settings.min_step)) {
    throw std::invalid_argument("transient: end time and steps must be positive, max >= min step");
  }
  if (settings.adaptive && !(settings.target_temperature_change > 0.0)) {
    throw std::invalid_argument("transient: target temperature change must be positive");
  }
  std::vector<double> outputs = settings.output_times;
  if (!std::is_sorted(outputs.begin(), outputs.end())) {
    throw std::invalid_argument("transient: output times must be increasing");
  }
  if (outputs.empty() || outputs.back() < settings.end_time) outputs.push_back(settings.end_time);

  const Assembler assembler(problem, true);
  if (initial_temperature.size() != static_cast<Eigen::Index>(assembler.node_count())) {
    throw std::invalid_argument("transient: initial temperature has " +
                                std::to_string(initial_temperature.size()) + " values for " +
                                std::to_string(assembler.node_count()) + " nodes");
  }
  assembler.check_temperature_range(assembler.to_dofs(initial_temperature));

  TransientResult result;
  NewtonWorkspace workspace;
  Eigen::VectorXd t_now = assembler.to_dofs(initial_temperature);
  Eigen::VectorXd t_previous = t_now;
  Eigen::VectorXd history(t_now.size()), t_new;
  double time = 0.0, dt = std::min(settings.initial_step, settings.max_step), dt_previous = 0.0;
  std::size_t next_output = 0;
  // A zero output time is the initial condition itself.
  while (next_output < outputs.size() && outputs[next_output] <= 0.0) {
    result.times.push_back(0.0);
    result.temperatures.push_back(initial_temperature);
    ++next_output;
  }
  while (next_output < outputs.size()) {
    double step = std::min(dt, outputs[next_output] - time);
    // Variable-step BDF2 is zero-stable for step ratios below 1 + sqrt(2); keep them <= 2.
    if (settings.scheme == TimeScheme::bdf2 && result.accepted_steps > 0) {
      step = std::min(step, 2.0 * dt_previous);
    }
    const bool lands_on_output = step >= outputs[next_output] - time;
    TimeTerm term;
    if (settings.scheme == TimeScheme::bdf2 && result.accepted_steps > 0) {
      // Variable-step BDF2: dT/dt = [(1+2w)/(1+w) T - (1+w) T_n + w^2/(1+w) T_{n-1}] / dt,
      // w = dt / dt_previous. Hairer & Wanner (1996) Solving ODEs II, sec. III.5 (eq. 5.5 form).
      const double w = step / dt_previous;
      term.rate_factor = (1.0 + 2.0 * w) / ((1.0 + w) * step);
      history = (-(1.0 + w) * t_now + (w * w / (1.0 + w)) * t_previous) / step;
    } else {
      term.rate_factor = 1.0 / step;  // backward Euler
      history = -t_now / step;
    }
    term.history = &history;
    t_new = t_now;
    const NewtonReport report = newton_solve(assembler, term, settings.newton, t_new, workspace);
    result.newton_iterations += report.iterations;
    const double change = (t_new - t_now).lpNorm<Eigen::Infinity>();
    const bool too_large = settings.adaptive && change > 2.0 * settings.target_temperature_change;
    if (!report.converged || too_large) {
      ++result.rejected_steps;
      dt = 0.5 * step;
      if (dt < settings.min_step) {
        throw std::runtime_error("transient: step fell below the minimum step " +
                                 std::to_string(settings.min_step) + " s at t = " +
                                 std::to_string(time) + " s");
      }
      continue;
    }
    ++result.accepted_steps;
    time = lands_on_output ? outputs[next_output] : time + step;
    t_previous = t_now;
    t_now = t_new;
    dt_previous = step;
    if (lands_on_output) {
      assembler.check_temperature_range(t_now);
      result.times.push_back(time);
      result.temperatures.push_back(assembler.to_nodes(t_now));
      ++next_output;
    }
    if (settings.adaptive) {
      // Steer the largest nodal change towards the target.
      const double ratio = change > 0.0 ? 0.9 * settings.target_temperature_change / change : 2.0;
      dt = std::clamp(std::max(dt, step) * std::clamp(ratio, 0.5, 2.0), settings.min_step,
                      settings.max_step);
    }
  }
  return result;
}

}  // namespace tfmb::heat
