// Joints: holonomic constraints enforced by scaled Lagrange multipliers, plus the joint forces
// (springs, dampers, contact penalty) that act on the same variables.
//
// Each joint writes its constraint equations Phi and its potential once, templated on the scalar,
// and is evaluated with Hyper<N> over its local variables (per node: du(3), dtheta(3); then the
// joint's own unknowns), which yields the Jacobian B and the multiplier Hessian sum lambda_i
// d2 Phi_i exactly.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "tfmb-beam/model.hpp"
#include "tfmb-beam/state.hpp"

namespace tfmb::beam {

/// Everything a joint may read while it is evaluated.
struct JointContext {
  const Model& model;
  const State& state;
  double load_factor = 1.0;            // statics: load factor; dynamics: actuator/load time function
  const Eigen::VectorXd* joint_rates = nullptr;  // d/dt of joint_dofs (dynamics), or null
  const std::vector<Eigen::Vector3d>* node_velocity = nullptr;          // spatial [m/s]
  const std::vector<Eigen::Vector3d>* node_angular_velocity = nullptr;  // spatial [rad/s]
  double rate_factor = 0.0;            // d(rate)/d(increment) of the time integrator (gamma')
};

/// Local contributions of one joint, over its nv local variables.
struct JointEval {
  std::vector<int> dofs;             // global dof of each local variable
  std::vector<int> rotation_blocks;  // local index of each node's first rotation variable
  Eigen::VectorXd phi;               // constraint values (m)
  Eigen::MatrixXd jacobian;          // m x nv
  Eigen::MatrixXd hessian_lambda;    // nv x nv, sum_i lambda_i d2 Phi_i / dq2
  Eigen::VectorXd force;             // nv, joint forces (spring, damper, contact) as residual
  Eigen::MatrixXd stiffness;         // nv x nv, d force / dq (including rate_factor x damping)
};

/// Named outputs of a joint (relative rotation, contact force, ...).
struct JointOutput {
  std::string name;
  double value = 0.0;
  std::string units;
};

class Joint {
 public:
  explicit Joint(JointSpec spec) : spec_(std::move(spec)) {}
  virtual ~Joint() = default;
  const JointSpec& spec() const { return spec_; }
  virtual int num_equations() const = 0;
  virtual int num_internal_dofs() const { return 0; }
  /// Global index of the first internal dof and of the first multiplier (set by the assembly).
  void set_offsets(int first_internal_dof, int first_multiplier) {
    first_internal_dof_ = first_internal_dof;
    first_multiplier_ = first_multiplier;
  }
  int first_internal_dof() const { return first_internal_dof_; }
  int first_multiplier() const { return first_multiplier_; }
  /// Evaluate at `ctx.state`; `lambda` holds the actual (unscaled) multipliers of this joint.
  virtual void evaluate(const JointContext& ctx, const Eigen::VectorXd& lambda, JointEval& out) const = 0;
  virtual std::vector<JointOutput> outputs(const JointContext& ctx, const Eigen::VectorXd& lambda) const = 0;
  /// Human-readable name of local equation i, for messages.
  virtual std::string equation_name(int i) const;

 protected:
  JointSpec spec_;
  int first_internal_dof_ = -1;
  int first_multiplier_ = -1;
};

/// Creates the joint for a spec; throws std::invalid_argument with a clear message on bad data.
std::unique_ptr<Joint> make_joint(const Model& model, const JointSpec& spec);

}  // namespace tfmb::beam
