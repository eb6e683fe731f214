#include "tfmb-beam/static_solver.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

#include "tfmb-beam/errors.hpp"
#include "tfmb-beam/linear_solver.hpp"
#include "tfmb-beam/rotation_wm.hpp"

namespace tfmb::beam {

namespace {

/// Newton at a fixed load factor with corrections scaled to turn no node by more than
/// `max_rotation` [rad]. `determinant_signs` (if given) receives sign(det K) at the start and at
/// the last factorisation.
bool newton_capped(const Assembly& assembly, State& state, double load_factor,
                   const StaticOptions& options, double max_rotation, int& iterations,
                   std::pair<int, int>* determinant_signs) {
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
    if (determinant_signs) {
      const int sign = solver.determinant_sign();
      if (it == 0)
        determinant_signs->first = sign;
      determinant_signs->second = sign;
    }
    // Damped Newton: a correction that turns a node by more than max_rotation_increment is
    // scaled down (the first iterate of a large load step overshoots badly in rotation).
    double max_rot = 0.0;
    for (int i = 0; i < assembly.num_nodes(); ++i) max_rot = std::max(max_rot, dx.segment<3>(6 * i + 3).norm());
    if (max_rot > max_rotation)
      dx *= max_rotation / max_rot;
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

}  // namespace

bool newton_static(const Assembly& assembly, State& state, double load_factor,
                   const StaticOptions& options, int& iterations) {
  if (options.full_steps_first && std::isfinite(options.max_rotation_increment)) {
    // Full Newton first: with the exact tangent it converges the end-moment roll-up to four
    // turns in one step, as Simo & Vu-Quoc (1986, Part II) report. A full step can also jump to
    // another equilibrium branch past a limit point; that shows as a change of sign of det K
    // between the start and the solution (an odd number of eigenvalues crossed zero), and such a
    // solution is refused in favour of the capped corrections below.
    State trial = state;
    std::pair<int, int> signs{0, 0};
    if (newton_capped(assembly, trial, load_factor, options,
                      std::numeric_limits<double>::infinity(), iterations, &signs) &&
        signs.first == signs.second) {
      state = std::move(trial);
      return true;
    }
  }
  return newton_capped(assembly, state, load_factor, options, options.max_rotation_increment,
                       iterations, nullptr);
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

/// Appends converged states to a load path (PathPoint rows).
class PathRecorder {
 public:
  PathRecorder(const Assembly& assembly, const PathMonitor& monitor, const State& initial,
               std::vector<PathPoint>& path)
      : assembly_(assembly), monitor_(monitor), path_(path), last_(initial.position) {
    if (monitor_.node >= assembly.num_nodes())
      throw std::invalid_argument("path monitor: node " + std::to_string(monitor_.node) +
                                  " out of range");
    if (monitor_.node >= 0 && !(monitor_.direction.norm() > 0.0))
      throw std::invalid_argument("path monitor: zero direction");
    path_.clear();
    add(0.0, initial, 0);
  }

  void add(double load_factor, const State& state, int iterations) {
    PathPoint p;
    p.load_factor = load_factor;
    double step2 = 0.0;
    for (int i = 0; i < assembly_.num_nodes(); ++i) {
      step2 += (state.position[i] - last_[i]).squaredNorm();
      p.max_displacement = std::max(
          p.max_displacement, (state.position[i] - assembly_.model().nodes[i].position).norm());
    }
    p.arc_length = (path_.empty() ? 0.0 : path_.back().arc_length) + std::sqrt(step2);
    if (monitor_.node >= 0) {
      p.node_displacement =
          state.position[monitor_.node] - assembly_.model().nodes[monitor_.node].position;
      p.characteristic_displacement = p.node_displacement.dot(monitor_.direction.normalized());
    } else {
      p.characteristic_displacement = p.max_displacement;
    }
    p.iterations = iterations;
    path_.push_back(p);
    last_ = state.position;
  }

 private:
  const Assembly& assembly_;
  PathMonitor monitor_;
  std::vector<PathPoint>& path_;
  std::vector<Eigen::Vector3d> last_;
};

}  // namespace

LimitPoints find_limit_points(const std::vector<PathPoint>& path) {
  LimitPoints lp;
  for (std::size_t i = 1; i + 1 < path.size(); ++i) {
    const double dl0 = path[i].load_factor - path[i - 1].load_factor;
    const double dl1 = path[i + 1].load_factor - path[i].load_factor;
    if (dl0 * dl1 < 0.0)
      lp.load.push_back(static_cast<int>(i));
    const double du0 =
        path[i].characteristic_displacement - path[i - 1].characteristic_displacement;
    const double du1 =
        path[i + 1].characteristic_displacement - path[i].characteristic_displacement;
    if (du0 * du1 < 0.0)
      lp.displacement.push_back(static_cast<int>(i));
  }
  return lp;
}

StaticResult solve_static(const Assembly& assembly, const State& initial, const StaticOptions& options) {
  StaticResult res;
  res.state = initial;
  PathRecorder path(assembly, options.monitor, initial, res.path);
  int step_iterations = 0;
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
    step_iterations += iters;
    if (ok) {
      last_change = difference(assembly, res.state, trial);
      last_step = target - lf;
      res.state = std::move(trial);
      lf = target;
      res.load_factor = lf;
      ++res.steps;
      cut = 0;
      path.add(lf, res.state, step_iterations);
      step_iterations = 0;
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

StaticResult solve_arc_length(const Assembly& assembly, const State& initial, const ArcLengthOptions& options) {
  StaticResult res;
  res.state = initial;
  PathRecorder path(assembly, options.monitor, initial, res.path);
  const int n = assembly.size();
  const int nn = assembly.num_nodes();
  NewtonLinearSolver solver([&](int i) { return assembly.dof_name(i); });
  // Translational nodal unknowns measure the arc (Crisfield 1981, cylindrical form).
  Eigen::VectorXd mask = Eigen::VectorXd::Zero(n);
  for (int i = 0; i < nn; ++i) mask.segment<3>(6 * i).setOnes();
  auto dot_t = [&](const Eigen::VectorXd& a, const Eigen::VectorXd& b) { return a.cwiseProduct(mask).dot(b); };
  Eigen::VectorXd r, r1;
  Triplets k;
  double scale = 0.0;
  double lambda = 0.0, arc = 0.0, first_arc = 0.0;
  Eigen::VectorXd prev_du;  // last converged step's increment (direction of travel)
  double prev_dl = 1.0;     // its load-factor increment
  int cut = 0;              // consecutive halvings
  int attempt_iterations = 0;
  // Reference load vector F = -dR/dlambda at a state (exact: loads are linear in lambda).
  auto load_vector = [&](const State& s, double lf) {
    assembly.assemble(s, lf, r, nullptr);
    assembly.assemble(s, lf + 1.0, r1, nullptr);
    return Eigen::VectorXd(r - r1);
  };
  auto refuse = [&] {
    ++res.cutbacks;
    arc *= 0.5;
    return ++cut <= options.max_cutbacks;
  };
  while (res.steps < options.max_steps) {
    State trial = res.state;
    // Predictor along the tangent K uf = F (solve(-r) gives -K^-1 r).
    assembly.assemble(trial, lambda, r, &k, &scale);
    Eigen::VectorXd f = load_vector(trial, lambda);
    Eigen::VectorXd uf = solver.solve(n, k, -f, assembly.step_limit());
    const double uf_norm = std::sqrt(dot_t(uf, uf));
    if (!(uf_norm > 0.0))
      throw ModelError("arc length: the load moves no node (zero load vector)");
    if (first_arc == 0.0)
      arc = first_arc = std::abs(options.initial_load_increment) * uf_norm;
    // Direction of travel (Feng, Peric & Owen 1996): the tangent's sign is that of its dot product
    // with the previous increment, so that past a limit point in load the load factor decreases
    // and past one in displacement the displacement turns back. At a point where the tangent is
    // orthogonal to the previous increment, the load-factor sign is kept.
    double dl = arc / uf_norm;
    if (prev_du.size() > 0) {
      const double c = dot_t(prev_du, uf);
      if (c < 0.0 || (c == 0.0 && prev_dl < 0.0))
        dl = -dl;
    }
    Eigen::VectorXd du = dl * uf;
    assembly.apply_increment(trial, du);
    double lam = lambda + dl;
    bool ok = false;
    int it = 0;
    for (; it < options.max_iterations; ++it) {
      assembly.assemble(trial, lam, r, &k, &scale);
      ++res.iterations;
      ++attempt_iterations;
      if (!r.allFinite()) break;
      if (it > 0 && r.norm() <= options.tolerance * std::max(scale, 1e-300)) {
        ok = true;
        break;
      }
      Eigen::VectorXd ur;
      try {
        ur = solver.solve(n, k, r, assembly.step_limit());
      } catch (const ModelError&) {
        break;
      }
      f = load_vector(trial, lam);
      uf = solver.solve_again(f);
      // ||du + ur + dlam uf||^2 = arc^2 on the translations (Crisfield 1981 eq. 11).
      const Eigen::VectorXd base = du + ur;
      const double a1 = dot_t(uf, uf), a2 = 2.0 * dot_t(base, uf), a3 = dot_t(base, base) - arc * arc;
      const double disc = a2 * a2 - 4.0 * a1 * a3;
      if (disc < 0.0) break;
      const double s1 = (-a2 + std::sqrt(disc)) / (2.0 * a1), s2 = (-a2 - std::sqrt(disc)) / (2.0 * a1);
      // The root that keeps the increment closest in direction to the current one (Crisfield 1981).
      const double c1 = dot_t(base + s1 * uf, du), c2 = dot_t(base + s2 * uf, du);
      const double dlam = c1 >= c2 ? s1 : s2;
      const Eigen::VectorXd dx = ur + dlam * uf;
      assembly.apply_increment(trial, dx);
      du += dx;
      lam += dlam;
      // Increment criterion as in newton_static (round-off floor of stiff constraints).
      double xmax = 1.0;
      for (const auto& x : trial.position) xmax = std::max(xmax, x.cwiseAbs().maxCoeff());
      const double floor = 64.0 * std::numeric_limits<double>::epsilon() * xmax * std::sqrt(static_cast<double>(n));
      if (it > 0 && std::sqrt(dot_t(dx, dx)) <= 1e-8 * std::sqrt(dot_t(du, du)) + floor &&
          std::abs(dlam) <= 1e-8 * std::abs(lam - lambda) + 1e-14 * std::abs(lam)) {
        ok = true;
        ++it;
        break;
      }
    }
    // A converged step that turns back on the previous one has left the branch (typically onto
    // the unloading path or across a loop): refuse it and retry with a shorter arc.
    if (ok && prev_du.size() > 0) {
      const double cos_turn =
          dot_t(prev_du, du) / std::max(std::sqrt(dot_t(prev_du, prev_du) * dot_t(du, du)), 1e-300);
      if (cos_turn < std::cos(options.max_turn))
        ok = false;
    }
    if (!ok) {
      if (!refuse())
        return res;
      continue;
    }
    if (lam > options.final_load_factor && lambda < options.final_load_factor) {
      // Crossed the target: land on it exactly with a load-controlled Newton from the last state.
      State landing = res.state;
      int its = 0;
      if (newton_static(assembly, landing, options.final_load_factor, StaticOptions{}, its)) {
        res.iterations += its;
        attempt_iterations += its;
        trial = std::move(landing);
        lam = options.final_load_factor;
      }
    }
    prev_du = du;
    prev_dl = lam - lambda;
    lambda = lam;
    res.state = std::move(trial);
    res.load_factor = lambda;
    ++res.steps;
    path.add(lambda, res.state, attempt_iterations);
    attempt_iterations = 0;
    if (options.on_step) options.on_step(lambda, res.state);
    // Step adaptation (Crisfield 1981): the arc scales with sqrt(desired / used iterations),
    // bounded per step and overall; after a cut-back the arc grows again only on easy steps.
    const double growth =
        std::sqrt(static_cast<double>(options.desired_iterations) / std::max(it, 1));
    arc *= std::clamp(growth, 0.5, cut > 0 ? 1.0 : options.max_growth);
    arc = std::min(arc, options.max_arc_factor * first_arc);
    cut = 0;
    if (lambda >= options.final_load_factor ||
        res.path.back().max_displacement >= options.max_displacement) {
      res.converged = true;
      return res;
    }
  }
  return res;
}

std::vector<State> solve_at_load_factors(const Assembly& assembly, const State& initial,
                                         const std::vector<double>& load_factors, const StaticOptions& options) {
  std::vector<State> states;
  State state = initial;
  double reached = 0.0;
  for (double target : load_factors) {
    double step = target - reached;
    int halvings = 0;
    while (reached < target) {
      const double next = std::min(target, reached + step);
      State trial = state;
      int iterations = 0;
      if (newton_static(assembly, trial, next, options, iterations)) {
        state = trial;
        reached = next;
      } else {
        if (++halvings > options.max_cutbacks) return states;
        step *= 0.5;
      }
    }
    states.push_back(state);
  }
  return states;
}

}  // namespace tfmb::beam
