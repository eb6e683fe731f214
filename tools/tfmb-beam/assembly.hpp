// Global assembly of the beam/joint system.
//
// Unknown vector: per node (du_x, du_y, du_z, dtheta_x, dtheta_y, dtheta_z) at 6 i, then the joint
// unknowns (e.g. revolute angles), then the scaled Lagrange multipliers mu. The actual
// multipliers are lambda = s mu with s the constraint scale; the constraint rows are s Phi and the
// multiplier columns s B^T, which keeps the saddle-point matrix balanced (Bottasso, Dopico &
// Trainelli 2008; FORMULATION.md sec. 3).
#pragma once

#include <Eigen/Sparse>
#include <memory>
#include <string>
#include <vector>

#include "tfmb-beam/beam_element.hpp"
#include "tfmb-beam/joints.hpp"
#include "tfmb-beam/model.hpp"
#include "tfmb-beam/state.hpp"

namespace tfmb::beam {

using Triplets = std::vector<Eigen::Triplet<double>>;

/// Optional velocity information for joints with dampers or friction (dynamics).
struct RateInfo {
  const Eigen::VectorXd* joint_rates = nullptr;
  const std::vector<Eigen::Vector3d>* node_velocity = nullptr;
  const std::vector<Eigen::Vector3d>* node_angular_velocity = nullptr;
  double rate_factor = 0.0;
};

class Assembly {
 public:
  explicit Assembly(const Model& model);

  const Model& model() const { return model_; }
  int num_nodes() const { return static_cast<int>(model_.nodes.size()); }
  int num_node_dofs() const { return 6 * num_nodes(); }
  int num_joint_dofs() const { return num_joint_dofs_; }
  int num_multipliers() const { return num_multipliers_; }
  int size() const { return num_node_dofs() + num_joint_dofs_ + num_multipliers_; }
  const std::vector<std::unique_ptr<Joint>>& joints() const { return joints_; }

  /// Reference state: zero displacement and rotation, zero joint unknowns and multipliers.
  State initial_state() const;
  /// Current section frame of a node.
  Eigen::Matrix3d frame(const State& state, int node) const;

  double constraint_scale() const { return constraint_scale_; }
  void set_constraint_scale(double s) { constraint_scale_ = s; }
  /// A scale of the element stiffness (mean diagonal of the nodal tangent at the reference).
  double typical_stiffness() const;

  /// Residual (internal - external + constraint forces; constraint rows s Phi) at `load_factor`
  /// and, if `tangent` is given, its Jacobian with respect to the increment. External loads are
  /// multiplied by `load_factor`. `force_scale` (if given) receives a norm of the force terms for
  /// relative convergence tests.
  void assemble(const State& state, double load_factor, Eigen::VectorXd& residual, Triplets* tangent,
                double* force_scale = nullptr, const RateInfo* rates = nullptr) const;

  /// state <- state (+) increment (additive on positions and joint unknowns, multiplicative on
  /// rotations: R <- R(dtheta) R, rescaled by the WM composition).
  void apply_increment(State& state, const Eigen::VectorXd& increment) const;

  /// Per element, per Gauss point sectional strains and stress resultants at `state`.
  void element_results(const State& state, std::vector<ElementResult>& results) const;
  double strain_energy(const State& state) const;
  /// Actual multipliers of joint j.
  Eigen::VectorXd joint_multipliers(const State& state, int j) const;
  std::vector<JointOutput> joint_outputs(const State& state, int j, double load_factor = 1.0) const;

  /// Largest sensible Newton correction: 1e6 times the model's extent (and at least 1e6), for
  /// singularity detection.
  double step_limit() const { return step_limit_; }

  /// Name of global unknown i ("node 12 rotation z", "revolute joint 'h' angle", ...).
  std::string dof_name(int i) const;

 private:
  ElementState element_state(const State& state, int e) const;
  const Model& model_;
  std::vector<ElementGeometry> geometry_;
  std::vector<ElementLoads> element_loads_;
  std::vector<std::unique_ptr<Joint>> joints_;
  int num_joint_dofs_ = 0;
  int num_multipliers_ = 0;
  double constraint_scale_ = 1.0;
  double step_limit_ = 1e6;
};

}  // namespace tfmb::beam
