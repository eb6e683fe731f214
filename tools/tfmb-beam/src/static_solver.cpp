#include "tfmb/beam/static_solver.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "tfmb/beam/errors.hpp"
#include "tfmb/beam/linear_solver.hpp"
#include "tfmb/beam/rotation_wm.hpp"

namespace tfmb::beam {

bool newton_static(const Assembly& assembly, State& state, double load_factor, const StaticOptions& options,
                   int& iterations) {
  NewtonLinearSolver solver([&](int i) { return assembly.dof_name(i); });
  Eigen::VectorXd r;
  Triplets k;
  double scale = 0.0;
  const State start = state;
  const int nq = assembly.num_node_dofs() + assembly.num_joint_dofs();
  Eigen::VectorXd accumulated = Eigen::VectorXd::Zero(nq);
  for (int it = 0; it < options.max_iterations; ++it) {
    assembly.assemble(state, load_factor, r, &k, &scale);
    ++iterations;
    if (!r.allFinite()) break;
    if (r.norm() <= options.tolerance * std::max(scale, 1e-300) && it > 0) return true;
    Eigen::VectorXd dx;
    try {
      dx = solver.solve(assembly.size(), k, r, assembly.step_limit());
    } catch (const ModelError&) {
      // Singular at the start of a step: the model itself is singular (mechanism). Singular
      // after a few iterations: Newton wandered off; cut the step back.
      if (it == 0) throw;
      break;
    }
    // Damped Newton: a correction that turns a node by more than max_rotation_increment is
    // scaled down (the first iterate of a large load step overshoots badly in rotation).
    double max_rot = 0.0;
    for (int i = 0; i < assembly.num_nodes(); ++i) max_rot = std::max(max_rot, dx.segment<3>(6 * i + 3).norm());
    if (max_rot > options.max_rotation_increment) dx *= options.max_rotation_increment / max_rot;
    assembly.apply_increment(state, dx);
    accumulated += dx.head(nq);
    // Increment criterion: with quadratic convergence a correction 1e-10 times the step's total
    // increment means the residual is at round-off, which for stiff constraints (s Phi ~ s eps)
    // can exceed a force-relative residual tolerance.
    // Floor: corrections below the round-off of the coordinates themselves.
    double xmax = 1.0;
    for (const auto& x : state.position) xmax = std::max(xmax, x.cwiseAbs().maxCoeff());
    const double floor = 64.0 * std::numeric_limits<double>::epsilon() * xmax * std::sqrt(static_cast<double>(nq));
    if (it > 0 && dx.head(nq).norm() <= options.increment_tolerance * accumulated.norm() + floor) return true;
  }
  state = start;
  return false;
}

namespace {

/// The change from `a` to `b` as an increment vector (spatial rotation parameters).
Eigen::VectorXd difference(const Assembly& assembly, const State& a, const State& b) {
  Eigen::VectorXd d(assembly.size());
  const int nn = assembly.num_nodes();
  for (int i = 0; i < nn; ++i) {
    d.segment<3>(6 * i) = b.position[i] - a.position[i];
    d.segment<3>(6 * i + 3) = wm_compose<double>(b.rotation[i], wm_inverse<double>(a.rotation[i]));
  }
  d.segment(6 * nn, assembly.num_joint_dofs()) = b.joint_dofs - a.joint_dofs;
  d.tail(assembly.num_multipliers()) = b.multipliers - a.multipliers;
  return d;
}

}  // namespace

StaticResult solve_static(const Assembly& assembly, const State& initial, const StaticOptions& options) {
  StaticResult res;
  res.state = initial;
  double step = options.final_load_factor / std::max(options.initial_steps, 1);
  double lf = 0.0;
  int cut = 0;
  int easy = 0;
  // Secant predictor: the last converged step's change, scaled to the new step length. It starts
  // Newton near the solution path instead of at the (overshooting) linear response.
  Eigen::VectorXd last_change;
  double last_step = 0.0;
  for (int attempt = 0; attempt < options.max_steps && lf < options.final_load_factor * (1 - 1e-14); ++attempt) {
    const double target = std::min(lf + step, options.final_load_factor);
    State trial = res.state;
    if (options.secant_predictor && last_change.size() > 0 && last_step > 0.0) assembly.apply_increment(trial, ((target - lf) / last_step) * last_change);
    int iters = 0;
    bool ok = newton_static(assembly, trial, target, options, iters);
    if (!ok && options.secant_predictor && last_change.size() > 0) {
      // Retry the same step without the predictor before cutting back.
      trial = res.state;
      int more = 0;
      ok = newton_static(assembly, trial, target, options, more);
      iters += more;
    }
    res.iterations += iters;
    if (ok) {
      last_change = difference(assembly, res.state, trial);
      last_step = target - lf;
      res.state = std::move(trial);
      lf = target;
      res.load_factor = lf;
      ++res.steps;
      cut = 0;
      if (options.on_step) options.on_step(lf, res.state);
      // Grow the step again after easy convergence.
      if (iters <= 6 && ++easy >= 2) {
        step *= 1.5;
        easy = 0;
      }
    } else {
      ++res.cutbacks;
      easy = 0;
      if (++cut > options.max_cutbacks) return res;
      step *= 0.5;
    }
  }
  res.converged = lf >= options.final_load_factor * (1 - 1e-14);
  return res;
}

}  // namespace tfmb::beam
