// Dynamic analysis: generalized-alpha for index-3 constrained systems (Arnold & Bruls 2007) in
// its Lie-group form (Bruls, Cardona & Arnold 2012), FORMULATION.md sec. 3.
//
// Nodal rotations are updated multiplicatively, Lambda_{n+1} = Lambda_n R(dTheta) with dTheta the
// material WM parameters of the step's rotation; angular velocities and accelerations are
// material. Equilibrium and constraints hold exactly at t_{n+1}; the alpha weighting lives in the
// auxiliary acceleration a. Newton corrections use the same spatial increments as the statics.
#pragma once

#include <functional>
#include <vector>

#include "tfmb-beam/assembly.hpp"
#include "tfmb-beam/inertia.hpp"

namespace tfmb::beam {

struct DynamicOptions {
  double time_step = 1e-3;    // [s]
  double end_time = 1.0;      // [s]
  double rho_infinity = 0.8;  // high-frequency spectral radius in [0, 1]
  int max_iterations = 20;
  int max_cutbacks = 8;     // halvings of the time step after a failed Newton iteration
  double tolerance = 1e-9;  // relative residual
  /// Load multiplier as a function of time (also drives prescribed joint rotations).
  std::function<double(double)> load_function = [](double) { return 1.0; };
  /// Called after every step with (time, state, solver) for output.
  std::function<void(double, const State&)> on_step;
  /// Start from rest with consistent accelerations (true) or zero accelerations (false).
  bool consistent_initial_acceleration = true;
};

struct DynamicResult {
  bool completed = false;
  double time = 0.0;
  int steps = 0;
  int iterations = 0;
  int cutbacks = 0;
  State state;
};

/// Kinematic state of the integrator (exposed for energy output and tests).
struct Motion {
  std::vector<Eigen::Vector3d> velocity;          // spatial [m/s]
  std::vector<Eigen::Vector3d> angular_velocity;  // material [rad/s]
  Eigen::VectorXd joint_rates;                    // [rad/s]
};

class DynamicSolver {
 public:
  /// The solver re-scales the assembly's constraint rows for the dynamic iteration matrix
  /// (hence the non-const reference); states passed to run() are converted.
  DynamicSolver(Assembly& assembly, DynamicOptions options);
  /// Integrates from `initial` (at rest unless initial velocities are set with set_velocity).
  DynamicResult run(const State& initial);
  void set_initial_velocity(const std::vector<Eigen::Vector3d>& velocity,
                            const std::vector<Eigen::Vector3d>& angular_velocity_material);
  /// Initial rates of the joint unknowns (e.g. revolute relative angles) [rad/s], with
  /// set_initial_velocity to continue an earlier run.
  void set_initial_joint_rates(const Eigen::VectorXd& rates) { init_joint_rates_ = rates; }
  const Motion& motion() const { return motion_; }
  /// Kinetic energy of `motion()` [J].
  double kinetic_energy() const;
  /// Potential energy: strain energy + joint springs - work of dead loads and gravity at `time`.
  double potential_energy(const State& state, double time) const;

 private:
  Eigen::VectorXd initial_velocity() const;

  Assembly& assembly_;
  DynamicOptions options_;
  MassModel mass_;
  Motion motion_;
  std::vector<Eigen::Vector3d> init_v_, init_w_;
  Eigen::VectorXd init_joint_rates_;
};

}  // namespace tfmb::beam
