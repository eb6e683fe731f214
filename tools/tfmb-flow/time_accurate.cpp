#include "time_accurate.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace tfmb::flow {

namespace {

// sum += value, element by element (sum sized on first use; nothing for an empty value)
void accumulate(std::vector<double>& sum, const std::vector<double>& value) {
  if (value.empty())
    return;
  if (sum.empty())
    sum.assign(value.size(), 0.0);
  for (std::size_t i = 0; i < value.size(); ++i)
    sum[i] += value[i];
}

std::vector<double> scaled(const std::vector<double>& v, double factor) {
  std::vector<double> out(v.size());
  for (std::size_t i = 0; i < v.size(); ++i)
    out[i] = v[i] * factor;
  return out;
}

// Sums of the wall traces of one curve over some steps. The pressure is summed as its deviation
// from the first sample (shifted data): the variance as E[p^2] - E[p]^2 of the raw values loses
// every digit of a fluctuation below 1e-8 p in the cancellation.
struct TraceSums {
  std::vector<double> pressure_shift;
  std::vector<double> pressure, temperature, shear, heat_flux, pressure_squared;
  std::vector<double> pressure_first_half, pressure_second_half;
  int steps_first_half = 0, steps_second_half = 0;

  void add(const WallTrace& t, bool second_half) {
    const std::size_t n = t.pressure.size();
    if (pressure.empty()) {
      for (auto* v : {&pressure, &temperature, &shear, &heat_flux, &pressure_squared,
                      &pressure_first_half, &pressure_second_half})
        v->assign(n, 0.0);
      pressure_shift = t.pressure;
    }
    for (std::size_t k = 0; k < n; ++k) {
      const double dp = t.pressure[k] - pressure_shift[k];
      pressure[k] += dp;
      temperature[k] += t.temperature[k];
      shear[k] += t.shear_stress[k];
      heat_flux[k] += t.heat_flux[k];
      pressure_squared[k] += dp * dp;
      (second_half ? pressure_second_half : pressure_first_half)[k] += dp;
    }
    ++(second_half ? steps_second_half : steps_first_half);
  }
};

Vec2 wall_pressure_force(FlowSolver& solver, const std::vector<int>& wall_curves) {
  Vec2 f{};
  for (int b : wall_curves)
    f = f + solver.boundary_integral(b).force;
  return f;
}

}  // namespace

TimeAccurateResult run_time_accurate(FlowSolver& solver, const TimeAccurateSettings& s,
                                     const std::vector<int>& wall_curves) {
  if (!(s.time_step > 0.0) || s.time_steps < 1)
    throw std::invalid_argument("flow: time-accurate run needs a time step > 0 and >= 1 step");
  if (s.statistics_start < 1 || s.statistics_start > s.time_steps) {
    throw std::invalid_argument("flow: statistics start " + std::to_string(s.statistics_start) +
                                " outside the steps 1.." + std::to_string(s.time_steps));
  }
  using clock = std::chrono::steady_clock;
  const auto start = clock::now();
  TimeAccurateResult result;
  const int window = s.time_steps - s.statistics_start + 1;
  const int second_half_start = s.statistics_start + window / 2;
  std::vector<State> sum_w;
  std::vector<double> sum_nu, sum_k, sum_omega;  // turbulence variables (SA or SST)
  std::vector<TraceSums> sums(wall_curves.size());
  std::vector<WallTrace> last_traces(wall_curves.size());
  double cfl = s.cfl_start;
  const bool predicted = s.inner_limiter == InnerLimiter::predicted;
  if (s.inner_linear_tolerance > 0.0 || predicted) {
    solver.set_newton_linear_tolerance(s.inner_linear_tolerance > 0.0
                                           ? s.inner_linear_tolerance
                                           : kPredictedLimiterLinearTolerance);
  }
  for (int step = 1; step <= s.time_steps; ++step) {
    // Phase 1: converge the physical step in pseudo time. With the limiter live, the inner
    // iterations can chatter: nasa-2dcd SMOKE at NPR 2.412 (5e-6 s steps) took 32 inner
    // iterations a step, 25 of them defect corrections waiting for the stall rule to freeze the
    // limiter at the lip corners; held at the predicted state, Newton-Krylov takes 4, if its
    // GMRES solves to 1e-3: at 0.4 (the steady solver's forcing) each step's first update raised
    // the residual per volume 165-fold in a 5.5e-9 m^2 wall cell at the lip (0.0511, 0.0234) m,
    // where the looser solve had left its error. On the case mesh, where the live limiter takes
    // 11-12 cheap defect corrections a step, the predicted one's Newton-Krylov steps cost 1.3-1.5
    // times as much time (tools/tfmb-flow/README.md, Time-accurate mode).
    solver.begin_time_step(s.time_step);
    if (predicted)
      solver.hold_limiter_at_predicted_state();
    solver.set_inner_iteration_control(s.inner_iterations, s.inner_residual_drop, cfl, 0);
    const SolveReport inner = solver.solve();
    // the next step starts where this one's CFL ramp ended: the physical time term keeps the
    // inner problem well conditioned, so the ramp need not start over
    cfl = std::clamp(inner.final_cfl, s.cfl_start, s.cfl_max);
    result.iterations += inner.iterations;
    result.linear_iterations += inner.linear_iterations;
    result.residual_evaluations += inner.residual_evaluations;
    result.residual_seconds += inner.residual_seconds;
    if (!inner.converged)
      ++result.unconverged_steps;
    TimeHistoryRecord rec;
    rec.time = step * s.time_step;
    rec.inner_iterations = inner.iterations;
    rec.inner_residual_drop = inner.residual_drop;
    rec.wall_force = wall_pressure_force(solver, wall_curves);
    if (!inner.history.empty())
      rec.residual = inner.history.back().residual;
    result.history.push_back(rec);

    // Phase 2: statistics.
    if (step >= s.statistics_start) {
      const bool second_half = step >= second_half_start;
      const auto w = solver.primitive();
      if (sum_w.empty())
        sum_w.assign(w.size(), State{});
      for (std::size_t i = 0; i < w.size(); ++i) {
        for (int v = 0; v < 4; ++v)
          sum_w[i][v] += w[i][v];
      }
      accumulate(sum_nu, solver.nu_tilde());
      accumulate(sum_k, solver.sst_k());
      accumulate(sum_omega, solver.sst_omega());
      last_traces = solver.wall_traces(wall_curves);
      for (std::size_t c = 0; c < wall_curves.size(); ++c)
        sums[c].add(last_traces[c], second_half);
      ++result.averaged_steps;
    }
    if (s.print_every > 0 && (step % s.print_every == 0 || step == 1 || step == s.time_steps)) {
      std::fprintf(stderr,
                   "step %5d/%d  t %.4e s  inner %3d (drop %.1e%s)  cfl %.1e  wall force "
                   "(%.5e, %.5e)\n",
                   step, s.time_steps, rec.time, inner.iterations, inner.residual_drop,
                   inner.converged ? "" : ", not reached", cfl, rec.wall_force.x, rec.wall_force.y);
    }
  }

  // Phase 3: means, RMS and the convergence of the mean.
  const double inv = 1.0 / result.averaged_steps;
  result.mean_primitive.resize(sum_w.size());
  for (std::size_t i = 0; i < sum_w.size(); ++i) {
    for (int v = 0; v < 4; ++v)
      result.mean_primitive[i][v] = sum_w[i][v] * inv;
  }
  result.mean_nu_tilde = scaled(sum_nu, inv);
  result.mean_k = scaled(sum_k, inv);
  result.mean_omega = scaled(sum_omega, inv);
  for (std::size_t c = 0; c < wall_curves.size(); ++c) {
    const TraceSums& t = sums[c];
    WallTrace mean = last_traces[c];  // nodes and coordinates
    std::vector<double> rms(t.pressure.size());
    for (std::size_t k = 0; k < t.pressure.size(); ++k) {
      const double mean_dp = t.pressure[k] * inv;
      mean.pressure[k] = t.pressure_shift[k] + mean_dp;
      mean.temperature[k] = t.temperature[k] * inv;
      mean.shear_stress[k] = t.shear[k] * inv;
      mean.heat_flux[k] = t.heat_flux[k] * inv;
      rms[k] = std::sqrt(std::max(t.pressure_squared[k] * inv - mean_dp * mean_dp, 0.0));
      if (t.steps_first_half > 0 && t.steps_second_half > 0) {
        const double change = std::abs(t.pressure_second_half[k] / t.steps_second_half -
                                       t.pressure_first_half[k] / t.steps_first_half);
        result.mean_change = std::max(result.mean_change, change / s.reference_pressure);
      }
    }
    result.mean_traces.push_back(std::move(mean));
    result.pressure_rms.push_back(std::move(rms));
  }
  // a window too short to split has no evidence of a converged mean
  result.mean_converged = window >= 2 && result.mean_change < s.statistics_tolerance;
  result.wall_time = std::chrono::duration<double>(clock::now() - start).count();
  return result;
}

}  // namespace tfmb::flow
