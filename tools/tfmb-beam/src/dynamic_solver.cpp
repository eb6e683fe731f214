#include "tfmb/beam/dynamic_solver.hpp"

#include <cmath>
#include <limits>

#include "tfmb/beam/errors.hpp"
#include "tfmb/beam/linear_solver.hpp"
#include "tfmb/beam/rotation_wm.hpp"

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

}  // namespace

DynamicSolver::DynamicSolver(Assembly& assembly, DynamicOptions options)
    : assembly_(assembly), options_(std::move(options)), mass_(build_mass(assembly.model())) {
  if (!(options_.time_step > 0.0)) throw ModelError("dynamic analysis: time_step must be > 0 [s]");
  motion_.velocity.assign(assembly.num_nodes(), Eigen::Vector3d::Zero());
  motion_.angular_velocity.assign(assembly.num_nodes(), Eigen::Vector3d::Zero());
  motion_.joint_rates.setZero(assembly.num_joint_dofs());
  if (options_.rho_infinity < 0.0 || options_.rho_infinity > 1.0)
    throw ModelError("dynamic analysis: rho_infinity must be in [0, 1], got " + std::to_string(options_.rho_infinity));
}

void DynamicSolver::set_initial_velocity(const std::vector<Eigen::Vector3d>& velocity,
                                         const std::vector<Eigen::Vector3d>& angular_velocity_material) {
  init_v_ = velocity;
  init_w_ = angular_velocity_material;
}

double DynamicSolver::kinetic_energy() const {
  const int nn = assembly_.num_nodes();
  double t = 0.0;
  for (int c = 0; c < 3; ++c) {
    Eigen::VectorXd v(nn);
    for (int i = 0; i < nn; ++i) v(i) = motion_.velocity[i](c);
    t += 0.5 * v.dot(mass_.mass_scalar * v);
  }
  for (int i = 0; i < nn; ++i)
    t += 0.5 * motion_.angular_velocity[i].dot(mass_.nodal_inertia[i] * motion_.angular_velocity[i]);
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
        if (o.name == "strain_energy") u += o.value;
  }
  // Dead loads: potential -F . (x - x0) with F the consistent nodal forces at the reference.
  Eigen::VectorXd r;
  const State ref = assembly_.initial_state();
  assembly_.assemble(ref, options_.load_function(time), r, nullptr);
  for (size_t i = 0; i < m.nodes.size(); ++i)
    u += r.segment<3>(6 * i).dot(state.position[i] - m.nodes[i].position);
  return u;
}

DynamicResult DynamicSolver::run(const State& initial) {
  const AlphaParameters ap = alpha_parameters(options_.rho_infinity);
  double h = options_.time_step;
  const int nn = assembly_.num_nodes();
  const int nj = assembly_.num_joint_dofs();
  const int nq = 6 * nn + nj;
  const Model& model = assembly_.model();
  // beta' and gamma' of FORMULATION.md sec. 3: d(acceleration)/d(increment), d(velocity)/d(increment).
  double bpp = (1.0 - ap.alpha_m) / ((1.0 - ap.alpha_f) * h * h * ap.beta);
  double gp = ap.gamma / (h * ap.beta);

  DynamicResult res;
  res.state = initial;
  State& st = res.state;
  Eigen::VectorXd vel = Eigen::VectorXd::Zero(nq), acc = Eigen::VectorXd::Zero(nq), aux = Eigen::VectorXd::Zero(nq);
  for (int i = 0; i < nn && !init_v_.empty(); ++i) {
    vel.segment<3>(6 * i) = init_v_[i];
    vel.segment<3>(6 * i + 3) = init_w_[i];
  }
  if (init_joint_rates_.size() == nj) vel.tail(nj) = init_joint_rates_;
  NewtonLinearSolver solver([&](int i) { return assembly_.dof_name(i); });

  // Inertia forces (spatial, spin-conjugate for rotations) and their iteration matrix.
  auto add_inertia = [&](const State& s, const Eigen::VectorXd& v, const Eigen::VectorXd& a, Eigen::VectorXd& r,
                         Triplets* k) {
    for (int c = 0; c < 3; ++c) {
      Eigen::VectorXd ac(nn);
      for (int i = 0; i < nn; ++i) ac(i) = a(6 * i + c);
      const Eigen::VectorXd f = mass_.mass_scalar * ac;
      for (int i = 0; i < nn; ++i) r(6 * i + c) += f(i);
    }
    if (k)
      for (int o = 0; o < mass_.mass_scalar.outerSize(); ++o)
        for (Eigen::SparseMatrix<double>::InnerIterator it(mass_.mass_scalar, o); it; ++it)
          for (int c = 0; c < 3; ++c) k->emplace_back(6 * it.row() + c, 6 * it.col() + c, bpp * it.value());
    for (int i = 0; i < nn; ++i) {
      const Eigen::Matrix3d& j = mass_.nodal_inertia[i];
      if (j.isZero()) continue;
      const Eigen::Matrix3d fr = assembly_.frame(s, i);
      const Eigen::Vector3d w = v.segment<3>(6 * i + 3);
      const Eigen::Vector3d wd = a.segment<3>(6 * i + 3);
      // Euler's equations in the material frame, pushed forward: Lambda (J Omega_dot + Omega x J Omega).
      r.segment<3>(6 * i + 3) += fr * (j * wd + w.cross(j * w));
      if (k) {
        const Eigen::Matrix3d kk =
            fr * (bpp * j + gp * (skew<double>(w) * j - skew<double>(Eigen::Vector3d(j * w)))) * fr.transpose();
        for (int p = 0; p < 3; ++p)
          for (int q = 0; q < 3; ++q) k->emplace_back(6 * i + 3 + p, 6 * i + 3 + q, kk(p, q));
      }
    }
  };

  // Constraint scaling for the dynamic iteration matrix (Bottasso et al. 2008): the stiffness
  // scale plus beta' times the mass scale. Existing multipliers are re-expressed in the new scale.
  double mass_diag = 0.0;
  for (int i = 0; i < nn; ++i) mass_diag += mass_.mass_scalar.coeff(i, i);
  mass_diag /= std::max(nn, 1);
  const double old_scale = assembly_.constraint_scale();
  const double scale = assembly_.typical_stiffness() + bpp * mass_diag;
  assembly_.set_constraint_scale(scale);
  st.multipliers *= old_scale / scale;

  motion_.velocity.assign(nn, Eigen::Vector3d::Zero());
  motion_.angular_velocity.assign(nn, Eigen::Vector3d::Zero());
  motion_.joint_rates = vel.tail(nj);
  for (int i = 0; i < nn; ++i) {
    motion_.velocity[i] = vel.segment<3>(6 * i);
    motion_.angular_velocity[i] = vel.segment<3>(6 * i + 3);
  }
  double t = 0.0;

  if (options_.consistent_initial_acceleration) {
    // M a0 + B^T lambda0 = -g, B a0 = 0 (start at rest or with constant velocity).
    Eigen::VectorXd r;
    Triplets k, ks;
    State s0 = st;
    s0.multipliers.setZero();
    assembly_.assemble(s0, options_.load_function(0.0), r, &k);
    for (const auto& tr : k)
      if (tr.row() >= nq || tr.col() >= nq) ks.push_back(tr);
    Eigen::VectorXd rr = Eigen::VectorXd::Zero(assembly_.size());
    rr.head(nq) = r.head(nq);
    // Mass matrix in place of the tangent's node block.
    for (int o = 0; o < mass_.mass_scalar.outerSize(); ++o)
      for (Eigen::SparseMatrix<double>::InnerIterator it(mass_.mass_scalar, o); it; ++it)
        for (int c = 0; c < 3; ++c) ks.emplace_back(6 * it.row() + c, 6 * it.col() + c, it.value());
    for (int i = 0; i < nn; ++i) {
      const Eigen::Matrix3d fr = assembly_.frame(st, i);
      const Eigen::Matrix3d jj = fr * mass_.nodal_inertia[i] * fr.transpose();
      for (int p = 0; p < 3; ++p)
        for (int q = 0; q < 3; ++q) ks.emplace_back(6 * i + 3 + p, 6 * i + 3 + q, jj(p, q));
    }
    // Tiny regularisation on massless unknowns (joint angles) keeps the saddle system regular.
    for (int i = 6 * nn; i < nq; ++i) ks.emplace_back(i, i, 1e-12 * mass_diag);
    try {
      const Eigen::VectorXd sol = solver.solve(assembly_.size(), ks, rr);
      acc = sol.head(nq);
      for (int i = 0; i < nn; ++i)
        acc.segment<3>(6 * i + 3) = assembly_.frame(st, i).transpose() * acc.segment<3>(6 * i + 3);
      st.multipliers = s0.multipliers + sol.tail(assembly_.num_multipliers());
      aux = acc;
    } catch (const ModelError&) {
      acc.setZero();
      aux.setZero();
    }
  }

  Eigen::VectorXd r;
  Triplets k;
  // Step-size control: a step whose Newton iteration fails is retried with half the step (contact
  // onset, stiff friction); after four good steps the step grows back towards the nominal one.
  const double nominal_h = h;
  int cuts = 0, easy = 0;
  while (t < options_.end_time * (1.0 - 1e-12)) {
    h = std::min(nominal_h / std::pow(2.0, cuts), options_.end_time - t);
    bpp = (1.0 - ap.alpha_m) / ((1.0 - ap.alpha_f) * h * h * ap.beta);
    gp = ap.gamma / (h * ap.beta);
    const double t1 = t + h;
    const double lf = options_.load_function(t1);
    const State s_n = st;
    // Predictor: unchanged acceleration.
    Eigen::VectorXd acc1 = acc;
    Eigen::VectorXd aux1 = ((1.0 - ap.alpha_f) * acc1 + ap.alpha_f * acc - ap.alpha_m * aux) / (1.0 - ap.alpha_m);
    Eigen::VectorXd dq = h * vel + h * h * (0.5 - ap.beta) * aux + h * h * ap.beta * aux1;
    for (int i = 0; i < nn; ++i) {
      st.position[i] = s_n.position[i] + dq.segment<3>(6 * i);
      // Lambda_{n+1} = Lambda_n R(dTheta): in terms of the rotation from the reference frame,
      // R(c_{n+1}) = R(c_n) R(Lambda0 dTheta).
      const Eigen::Vector3d spatial = model.nodes[i].frame * dq.segment<3>(6 * i + 3);
      st.rotation[i] = wm_compose<double>(spatial, s_n.rotation[i]);
    }
    st.joint_dofs = s_n.joint_dofs + dq.tail(nj);
    bool converged = false;
    Eigen::VectorXd vel1;
    for (int it = 0; it < options_.max_iterations; ++it) {
      // Increments over the step from the current iterate.
      for (int i = 0; i < nn; ++i) {
        dq.segment<3>(6 * i) = st.position[i] - s_n.position[i];
        const Eigen::Vector3d p = wm_compose<double>(st.rotation[i], wm_inverse<double>(s_n.rotation[i]));
        // R(p) = R(c_n)^T R(c_{n+1}), so Lambda_n^T Lambda_{n+1} = R(Lambda0^T p): material increment.
        dq.segment<3>(6 * i + 3) = model.nodes[i].frame.transpose() * p;
      }
      dq.tail(nj) = st.joint_dofs - s_n.joint_dofs;
      aux1 = (dq - h * vel - h * h * (0.5 - ap.beta) * aux) / (h * h * ap.beta);
      vel1 = vel + h * (1.0 - ap.gamma) * aux + h * ap.gamma * aux1;
      acc1 = ((1.0 - ap.alpha_m) * aux1 + ap.alpha_m * aux - ap.alpha_f * acc) / (1.0 - ap.alpha_f);

      for (int i = 0; i < nn; ++i) {
        motion_.velocity[i] = vel1.segment<3>(6 * i);
        motion_.angular_velocity[i] = vel1.segment<3>(6 * i + 3);
      }
      motion_.joint_rates = vel1.tail(nj);
      std::vector<Eigen::Vector3d> omega_spatial(nn);
      for (int i = 0; i < nn; ++i) omega_spatial[i] = assembly_.frame(st, i) * motion_.angular_velocity[i];
      RateInfo rates{&motion_.joint_rates, &motion_.velocity, &omega_spatial, gp};
      double fscale = 0.0;
      assembly_.assemble(st, lf, r, &k, &fscale, &rates);
      Eigen::VectorXd rin = Eigen::VectorXd::Zero(r.size());
      add_inertia(st, vel1, acc1, rin, &k);
      r += rin;
      ++res.iterations;
      const double scale_all = fscale + rin.norm();
      if (!r.allFinite()) break;
      if (it > 0 && r.norm() <= options_.tolerance * std::max(scale_all, 1e-300)) {
        converged = true;
        break;
      }
      Eigen::VectorXd dx;
      try {
        dx = solver.solve(assembly_.size(), k, r, assembly_.step_limit());
      } catch (const ModelError&) {
        if (it == 0) throw;
        break;
      }
      assembly_.apply_increment(st, dx);
      // Increment criterion relative to the step's motion (see newton_static).
      double xmax = 1.0;
      for (const auto& x : st.position) xmax = std::max(xmax, x.cwiseAbs().maxCoeff());
      const double floor = 64.0 * std::numeric_limits<double>::epsilon() * xmax * std::sqrt(static_cast<double>(nq));
      if (it > 0 && dx.head(nq).norm() <= 1e-10 * dq.norm() + floor) {
        converged = true;
        // Recompute the kinematic quantities for the accepted iterate on the next pass.
        for (int i = 0; i < nn; ++i) {
          dq.segment<3>(6 * i) = st.position[i] - s_n.position[i];
          const Eigen::Vector3d p = wm_compose<double>(st.rotation[i], wm_inverse<double>(s_n.rotation[i]));
          dq.segment<3>(6 * i + 3) = model.nodes[i].frame.transpose() * p;
        }
        dq.tail(nj) = st.joint_dofs - s_n.joint_dofs;
        aux1 = (dq - h * vel - h * h * (0.5 - ap.beta) * aux) / (h * h * ap.beta);
        vel1 = vel + h * (1.0 - ap.gamma) * aux + h * ap.gamma * aux1;
        acc1 = ((1.0 - ap.alpha_m) * aux1 + ap.alpha_m * aux - ap.alpha_f * acc) / (1.0 - ap.alpha_f);
        break;
      }
    }
    if (!converged) {
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
    vel = vel1;
    acc = acc1;
    aux = aux1;
    t = t1;
    for (int i = 0; i < nn; ++i) {
      motion_.velocity[i] = vel.segment<3>(6 * i);
      motion_.angular_velocity[i] = vel.segment<3>(6 * i + 3);
    }
    motion_.joint_rates = vel.tail(nj);
    ++res.steps;
    if (cuts > 0 && ++easy >= 4) {
      --cuts;
      easy = 0;
    }
    res.time = t;
    if (options_.on_step) options_.on_step(t, st);
  }
  res.completed = true;
  return res;
}

}  // namespace tfmb::beam
