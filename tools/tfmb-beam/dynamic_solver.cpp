#include "tfmb-beam/dynamic_solver.hpp"

#include <cmath>
#include <limits>

#include "tfmb-beam/errors.hpp"
#include "tfmb-beam/linear_solver.hpp"
#include "tfmb-beam/rotation_wm.hpp"

namespace tfmb::beam {
namespace {

struct AlphaParameters {
  double alpha_m, alpha_f, gamma, beta;
};

// Chung & Hulbert (1993) parameters from the spectral radius at infinity (FORMULATION.md sec. 3).
AlphaParameters alpha_parameters(double rho) {
  AlphaParameters p;
  p.alpha_m = (2.0 * rho - 1.0) / (rho + 1.0);
  p.alpha_f = rho / (rho + 1.0);
  p.gamma = 0.5 + p.alpha_f - p.alpha_m;
  p.beta = 0.25 * (p.gamma + 0.5) * (p.gamma + 0.5);
  return p;
}

// One generalized-alpha step size h: beta' and gamma' of FORMULATION.md sec. 3,
// d(acceleration)/d(increment) and d(velocity)/d(increment).
struct StepCoefficients {
  double h = 0.0;    // [s]
  double bpp = 0.0;  // beta' [1/s^2]
  double gp = 0.0;   // gamma' [1/s]
};

StepCoefficients step_coefficients(const AlphaParameters& ap, double h) {
  StepCoefficients c;
  c.h = h;
  c.bpp = (1.0 - ap.alpha_m) / ((1.0 - ap.alpha_f) * h * h * ap.beta);
  c.gp = ap.gamma / (h * ap.beta);
  return c;
}

// The generalized-alpha vectors over all unknowns (6 per node, then the joint unknowns): velocity,
// acceleration and the auxiliary acceleration a that carries the alpha weighting (FORMULATION.md
// sec. 3). Rotational entries are material.
struct AlphaVectors {
  Eigen::VectorXd velocity, acceleration, auxiliary;
};

// The integration of one DynamicSolver::run, phase by phase: start (initial rates, constraint
// scaling, initial accelerations), then per step the predictor and the Newton iteration, and the
// acceptance of a converged step. It works on the solver's assembly, mass and motion; the linear
// solver lives as long as the run so that it keeps its analysis of the matrix pattern.
class AlphaIntegration {
 public:
  AlphaIntegration(Assembly& assembly, const MassModel& mass, const DynamicOptions& options,
                   Motion& motion)
      : assembly_(assembly),
        mass_(mass),
        options_(options),
        motion_(motion),
        model_(assembly.model()),
        ap_(alpha_parameters(options.rho_infinity)),
        nn_(assembly.num_nodes()),
        nj_(assembly.num_joint_dofs()),
        nq_(6 * nn_ + nj_),
        solver_([&assembly](int i) { return assembly.dof_name(i); }),
        step_(step_coefficients(ap_, options.time_step)) {}

  // Starts from `state` with the given initial velocity (all unknowns, material rotation rates).
  void start(const Eigen::VectorXd& velocity, State& state) {
    now_.velocity = velocity;
    now_.acceleration = Eigen::VectorXd::Zero(nq_);
    now_.auxiliary = Eigen::VectorXd::Zero(nq_);
    scale_constraints(state);
    publish_motion(now_.velocity);
    if (options_.consistent_initial_acceleration)
      start_with_consistent_acceleration(state);
  }

  // One step from s_n (at t_{n+1} - h) to t_{n+1}: predictor, then Newton on `state`. Returns
  // whether Newton converged; counts its iterations.
  bool step(const State& s_n, State& state, double t1, double h, int& iterations) {
    step_ = step_coefficients(ap_, h);
    const double load_factor = options_.load_function(t1);
    predict(s_n, state);
    return iterate(s_n, state, load_factor, iterations);
  }

  // The converged step's vectors become those at t_n.
  void accept() {
    now_.velocity = next_.velocity;
    now_.acceleration = next_.acceleration;
    now_.auxiliary = next_.auxiliary;
    publish_motion(now_.velocity);
  }

 private:
  void scale_constraints(State& state);
  void start_with_consistent_acceleration(State& state);
  void predict(const State& s_n, State& state);
  bool iterate(const State& s_n, State& state, double load_factor, int& iterations);
  void update_step_vectors(const State& s_n, const State& state);
  double assemble_step(const State& state, double load_factor);
  void add_inertia(const State& s, const Eigen::VectorXd& v, const Eigen::VectorXd& a,
                   Eigen::VectorXd& r, Triplets& k) const;
  bool increment_converged(const State& state, const Eigen::VectorXd& dx) const;
  void publish_motion(const Eigen::VectorXd& velocity);

  Assembly& assembly_;
  const MassModel& mass_;
  const DynamicOptions& options_;
  Motion& motion_;
  const Model& model_;
  const AlphaParameters ap_;
  const int nn_, nj_, nq_;  // nodes, joint unknowns, all unknowns but the multipliers
  NewtonLinearSolver solver_;
  StepCoefficients step_;
  double mass_diag_ = 0.0;     // [kg] mean diagonal of the scalar mass matrix
  AlphaVectors now_;           // at t_n
  AlphaVectors next_;          // at t_{n+1}, from the current iterate
  Eigen::VectorXd increment_;  // dq: the step's motion from s_n to the current iterate
  Eigen::VectorXd residual_;
  Triplets tangent_;
};

// Constraint scaling for the dynamic iteration matrix (Bottasso et al. 2008): the stiffness
// scale plus beta' (of the nominal step) times the mass scale. Existing multipliers are
// re-expressed in the new scale.
void AlphaIntegration::scale_constraints(State& state) {
  for (int i = 0; i < nn_; ++i)
    mass_diag_ += mass_.mass_scalar.coeff(i, i);
  mass_diag_ /= std::max(nn_, 1);
  const double old_scale = assembly_.constraint_scale();
  const double scale = assembly_.typical_stiffness() + step_.bpp * mass_diag_;
  assembly_.set_constraint_scale(scale);
  state.multipliers *= old_scale / scale;
}

// Initial accelerations and multipliers in equilibrium with the initial loads:
// M a0 + B^T lambda0 = -g, B a0 = 0 (start at rest or with constant velocity). Left at zero if
// that system is singular.
void AlphaIntegration::start_with_consistent_acceleration(State& state) {
  Eigen::VectorXd r;
  Triplets k, ks;
  State s0 = state;
  s0.multipliers.setZero();
  assembly_.assemble(s0, options_.load_function(0.0), r, &k);
  for (const auto& tr : k)
    if (tr.row() >= nq_ || tr.col() >= nq_)
      ks.push_back(tr);
  Eigen::VectorXd rr = Eigen::VectorXd::Zero(assembly_.size());
  rr.head(nq_) = r.head(nq_);
  // Mass matrix in place of the tangent's node block.
  for (int o = 0; o < mass_.mass_scalar.outerSize(); ++o)
    for (Eigen::SparseMatrix<double>::InnerIterator it(mass_.mass_scalar, o); it; ++it)
      for (int c = 0; c < 3; ++c)
        ks.emplace_back(6 * it.row() + c, 6 * it.col() + c, it.value());
  for (int i = 0; i < nn_; ++i) {
    const Eigen::Matrix3d fr = assembly_.frame(state, i);
    const Eigen::Matrix3d jj = fr * mass_.nodal_inertia[i] * fr.transpose();
    for (int p = 0; p < 3; ++p)
      for (int q = 0; q < 3; ++q)
        ks.emplace_back(6 * i + 3 + p, 6 * i + 3 + q, jj(p, q));
  }
  // Tiny regularisation on massless unknowns (joint angles) keeps the saddle system regular.
  for (int i = 6 * nn_; i < nq_; ++i)
    ks.emplace_back(i, i, 1e-12 * mass_diag_);
  Eigen::VectorXd& acc = now_.acceleration;
  try {
    const Eigen::VectorXd sol = solver_.solve(assembly_.size(), ks, rr);
    acc = sol.head(nq_);
    for (int i = 0; i < nn_; ++i)
      acc.segment<3>(6 * i + 3) = assembly_.frame(state, i).transpose() * acc.segment<3>(6 * i + 3);
    state.multipliers = s0.multipliers + sol.tail(assembly_.num_multipliers());
    now_.auxiliary = acc;
  } catch (const ModelError&) {
    acc.setZero();
    now_.auxiliary.setZero();
  }
}

// Predictor: unchanged acceleration, the step's motion dq from the generalized-alpha update, and
// the state moved by it.
void AlphaIntegration::predict(const State& s_n, State& state) {
  const double h = step_.h;
  const Eigen::VectorXd& vel = now_.velocity;
  const Eigen::VectorXd& acc = now_.acceleration;
  const Eigen::VectorXd& aux = now_.auxiliary;
  const Eigen::VectorXd acc1 = acc;
  const Eigen::VectorXd aux1 =
      ((1.0 - ap_.alpha_f) * acc1 + ap_.alpha_f * acc - ap_.alpha_m * aux) / (1.0 - ap_.alpha_m);
  const Eigen::VectorXd dq = h * vel + h * h * (0.5 - ap_.beta) * aux + h * h * ap_.beta * aux1;
  for (int i = 0; i < nn_; ++i) {
    state.position[i] = s_n.position[i] + dq.segment<3>(6 * i);
    // Lambda_{n+1} = Lambda_n R(dTheta): in terms of the rotation from the reference frame,
    // R(c_{n+1}) = R(c_n) R(Lambda0 dTheta).
    const Eigen::Vector3d spatial = model_.nodes[i].frame * dq.segment<3>(6 * i + 3);
    state.rotation[i] = wm_compose<double>(spatial, s_n.rotation[i]);
  }
  state.joint_dofs = s_n.joint_dofs + dq.tail(nj_);
}

// The step's motion dq from s_n to the iterate and the generalized-alpha vectors at t_{n+1} it
// implies (FORMULATION.md sec. 3).
void AlphaIntegration::update_step_vectors(const State& s_n, const State& state) {
  const double h = step_.h;
  const Eigen::VectorXd& vel = now_.velocity;
  const Eigen::VectorXd& acc = now_.acceleration;
  const Eigen::VectorXd& aux = now_.auxiliary;
  Eigen::VectorXd& dq = increment_;
  dq.resize(nq_);
  for (int i = 0; i < nn_; ++i) {
    dq.segment<3>(6 * i) = state.position[i] - s_n.position[i];
    const Eigen::Vector3d p =
        wm_compose<double>(state.rotation[i], wm_inverse<double>(s_n.rotation[i]));
    // R(p) = R(c_n)^T R(c_{n+1}), so Lambda_n^T Lambda_{n+1} = R(Lambda0^T p): material increment.
    dq.segment<3>(6 * i + 3) = model_.nodes[i].frame.transpose() * p;
  }
  dq.tail(nj_) = state.joint_dofs - s_n.joint_dofs;
  next_.auxiliary = (dq - h * vel - h * h * (0.5 - ap_.beta) * aux) / (h * h * ap_.beta);
  next_.velocity = vel + h * (1.0 - ap_.gamma) * aux + h * ap_.gamma * next_.auxiliary;
  next_.acceleration =
      ((1.0 - ap_.alpha_m) * next_.auxiliary + ap_.alpha_m * aux - ap_.alpha_f * acc) /
      (1.0 - ap_.alpha_f);
}

// Newton on the step's equilibrium at t_{n+1}. Converged when the residual is small against the
// forces (not on the first iteration) or the correction small against the step's motion; a
// non-finite residual or a singular matrix after the first iteration fails the step (the caller
// cuts the time step), a singular first matrix is a model error.
bool AlphaIntegration::iterate(const State& s_n, State& state, double load_factor,
                               int& iterations) {
  for (int it = 0; it < options_.max_iterations; ++it) {
    // Increments over the step from the current iterate.
    update_step_vectors(s_n, state);
    publish_motion(next_.velocity);
    const double force_scale = assemble_step(state, load_factor);
    ++iterations;
    if (!residual_.allFinite())
      return false;
    if (it > 0 && residual_.norm() <= options_.tolerance * std::max(force_scale, 1e-300))
      return true;
    Eigen::VectorXd dx;
    try {
      dx = solver_.solve(assembly_.size(), tangent_, residual_, assembly_.step_limit());
    } catch (const ModelError&) {
      if (it == 0)
        throw;
      return false;
    }
    assembly_.apply_increment(state, dx);
    if (it > 0 && increment_converged(state, dx)) {
      // Recompute the kinematic quantities for the accepted iterate.
      update_step_vectors(s_n, state);
      return true;
    }
  }
  return false;
}

// Residual and iteration matrix at the iterate: the assembly's forces and constraints (with the
// rate terms of the joints at the iterate's velocities) plus inertia. Returns the force scale of
// the residual criterion.
double AlphaIntegration::assemble_step(const State& state, double load_factor) {
  std::vector<Eigen::Vector3d> omega_spatial(nn_);
  for (int i = 0; i < nn_; ++i)
    omega_spatial[i] = assembly_.frame(state, i) * motion_.angular_velocity[i];
  RateInfo rates{&motion_.joint_rates, &motion_.velocity, &omega_spatial, step_.gp};
  double fscale = 0.0;
  assembly_.assemble(state, load_factor, residual_, &tangent_, &fscale, &rates);
  Eigen::VectorXd rin = Eigen::VectorXd::Zero(residual_.size());
  add_inertia(state, next_.velocity, next_.acceleration, rin, tangent_);
  residual_ += rin;
  return fscale + rin.norm();
}

// Inertia forces (spatial, spin-conjugate for rotations) and their iteration matrix.
void AlphaIntegration::add_inertia(const State& s, const Eigen::VectorXd& v,
                                   const Eigen::VectorXd& a, Eigen::VectorXd& r,
                                   Triplets& k) const {
  const double bpp = step_.bpp, gp = step_.gp;
  for (int c = 0; c < 3; ++c) {
    Eigen::VectorXd ac(nn_);
    for (int i = 0; i < nn_; ++i)
      ac(i) = a(6 * i + c);
    const Eigen::VectorXd f = mass_.mass_scalar * ac;
    for (int i = 0; i < nn_; ++i)
      r(6 * i + c) += f(i);
  }
  for (int o = 0; o < mass_.mass_scalar.outerSize(); ++o)
    for (Eigen::SparseMatrix<double>::InnerIterator it(mass_.mass_scalar, o); it; ++it)
      for (int c = 0; c < 3; ++c)
        k.emplace_back(6 * it.row() + c, 6 * it.col() + c, bpp * it.value());
  for (int i = 0; i < nn_; ++i) {
    const Eigen::Matrix3d& j = mass_.nodal_inertia[i];
    if (j.isZero())
      continue;
    const Eigen::Matrix3d fr = assembly_.frame(s, i);
    const Eigen::Vector3d w = v.segment<3>(6 * i + 3);
    const Eigen::Vector3d wd = a.segment<3>(6 * i + 3);
    // Euler's equations in the material frame, pushed forward: Lambda (J Omega_dot + Omega x J
    // Omega).
    r.segment<3>(6 * i + 3) += fr * (j * wd + w.cross(j * w));
    const Eigen::Matrix3d kk =
        fr * (bpp * j + gp * (skew<double>(w) * j - skew<double>(Eigen::Vector3d(j * w)))) *
        fr.transpose();
    for (int p = 0; p < 3; ++p)
      for (int q = 0; q < 3; ++q)
        k.emplace_back(6 * i + 3 + p, 6 * i + 3 + q, kk(p, q));
  }
}

// Increment criterion relative to the step's motion (see newton_static), with a floor at the
// round-off of the positions.
bool AlphaIntegration::increment_converged(const State& state, const Eigen::VectorXd& dx) const {
  double xmax = 1.0;
  for (const auto& x : state.position)
    xmax = std::max(xmax, x.cwiseAbs().maxCoeff());
  const double floor =
      64.0 * std::numeric_limits<double>::epsilon() * xmax * std::sqrt(static_cast<double>(nq_));
  return dx.head(nq_).norm() <= 1e-10 * increment_.norm() + floor;
}

// The velocities of all unknowns as the solver's Motion (read by energy output and the joints'
// rate terms).
void AlphaIntegration::publish_motion(const Eigen::VectorXd& velocity) {
  motion_.velocity.resize(nn_);
  motion_.angular_velocity.resize(nn_);
  for (int i = 0; i < nn_; ++i) {
    motion_.velocity[i] = velocity.segment<3>(6 * i);
    motion_.angular_velocity[i] = velocity.segment<3>(6 * i + 3);
  }
  motion_.joint_rates = velocity.tail(nj_);
}

}  // namespace

DynamicSolver::DynamicSolver(Assembly& assembly, DynamicOptions options)
    : assembly_(assembly), options_(std::move(options)), mass_(build_mass(assembly.model())) {
  if (!(options_.time_step > 0.0))
    throw ModelError("dynamic analysis: time_step must be > 0 [s]");
  motion_.velocity.assign(assembly.num_nodes(), Eigen::Vector3d::Zero());
  motion_.angular_velocity.assign(assembly.num_nodes(), Eigen::Vector3d::Zero());
  motion_.joint_rates.setZero(assembly.num_joint_dofs());
  if (options_.rho_infinity < 0.0 || options_.rho_infinity > 1.0)
    throw ModelError("dynamic analysis: rho_infinity must be in [0, 1], got " +
                     std::to_string(options_.rho_infinity));
}

void DynamicSolver::set_initial_velocity(
    const std::vector<Eigen::Vector3d>& velocity,
    const std::vector<Eigen::Vector3d>& angular_velocity_material) {
  init_v_ = velocity;
  init_w_ = angular_velocity_material;
}

double DynamicSolver::kinetic_energy() const {
  const int nn = assembly_.num_nodes();
  double t = 0.0;
  for (int c = 0; c < 3; ++c) {
    Eigen::VectorXd v(nn);
    for (int i = 0; i < nn; ++i)
      v(i) = motion_.velocity[i](c);
    t += 0.5 * v.dot(mass_.mass_scalar * v);
  }
  for (int i = 0; i < nn; ++i)
    t +=
        0.5 * motion_.angular_velocity[i].dot(mass_.nodal_inertia[i] * motion_.angular_velocity[i]);
  return t;
}

double DynamicSolver::potential_energy(const State& state, double time) const {
  double u = assembly_.strain_energy(state);
  const Model& m = assembly_.model();
  for (size_t k = 0; k < assembly_.joints().size(); ++k) {
    const auto& j = assembly_.joints()[k];
    const JointSpec& s = j->spec();
    if (s.kind == JointKind::revolute && s.spring_stiffness != 0.0) {
      const double phi = state.joint_dofs(j->first_internal_dof() - assembly_.num_node_dofs());
      u += 0.5 * s.spring_stiffness * std::pow(phi - s.spring_rest_angle, 2);
    }
    if (s.kind == JointKind::flexible)
      for (const auto& o : assembly_.joint_outputs(state, static_cast<int>(k)))
        if (o.name == "strain_energy")
          u += o.value;
  }
  // Dead loads: potential -F . (x - x0) with F the consistent nodal forces at the reference.
  Eigen::VectorXd r;
  const State ref = assembly_.initial_state();
  assembly_.assemble(ref, options_.load_function(time), r, nullptr);
  for (size_t i = 0; i < m.nodes.size(); ++i)
    u += r.segment<3>(6 * i).dot(state.position[i] - m.nodes[i].position);
  return u;
}

// Initial velocity of all unknowns: the nodes' from set_initial_velocity, the joints' from
// set_initial_joint_rates; zero where not set.
Eigen::VectorXd DynamicSolver::initial_velocity() const {
  const int nn = assembly_.num_nodes();
  const int nj = assembly_.num_joint_dofs();
  Eigen::VectorXd vel = Eigen::VectorXd::Zero(6 * nn + nj);
  for (int i = 0; i < nn && !init_v_.empty(); ++i) {
    vel.segment<3>(6 * i) = init_v_[i];
    vel.segment<3>(6 * i + 3) = init_w_[i];
  }
  if (init_joint_rates_.size() == nj)
    vel.tail(nj) = init_joint_rates_;
  return vel;
}

// The time loop with step-size control: a step whose Newton iteration fails is retried with half
// the step (contact onset, stiff friction); after four good steps the step grows back towards the
// nominal one. Stops (not completed) when a step fails after max_cutbacks halvings.
DynamicResult DynamicSolver::run(const State& initial) {
  DynamicResult res;
  res.state = initial;
  State& st = res.state;
  AlphaIntegration integration(assembly_, mass_, options_, motion_);
  integration.start(initial_velocity(), st);
  double t = 0.0;
  const double nominal_h = options_.time_step;
  int cuts = 0, easy = 0;
  while (t < options_.end_time * (1.0 - 1e-12)) {
    const double h = std::min(nominal_h / std::pow(2.0, cuts), options_.end_time - t);
    const double t1 = t + h;
    const State s_n = st;
    if (!integration.step(s_n, st, t1, h, res.iterations)) {
      st = s_n;
      if (++cuts <= options_.max_cutbacks) {
        ++res.cutbacks;
        easy = 0;
        continue;
      }
      res.time = t;
      res.completed = false;
      return res;
    }
    integration.accept();
    t = t1;
    ++res.steps;
    if (cuts > 0 && ++easy >= 4) {
      --cuts;
      easy = 0;
    }
    res.time = t;
    if (options_.on_step)
      options_.on_step(t, st);
  }
  res.completed = true;
  return res;
}

}  // namespace tfmb::beam
