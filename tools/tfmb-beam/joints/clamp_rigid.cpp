// Clamp (node fixed to the ground) and rigid connection between two nodes.
#include "joint_common.hpp"

namespace tfmb::beam::detail {
namespace {

class Clamp final : public Joint {
 public:
  Clamp(const Model& model, JointSpec spec) : Joint(std::move(spec)) {
    if (model.planar) keep_ = {0, 1, 5};
  }
  int num_equations() const override { return keep_.empty() ? 6 : static_cast<int>(keep_.size()); }
  void evaluate(const JointContext& ctx, const Eigen::VectorXd& lambda, JointEval& out) const override {
    using H = Hyper<6>;
    const int node = spec_.node_b;
    out = JointEval{};
    push_node_dofs(node, out);
    const NodeVars<6> v = node_vars<6>(ctx.model, ctx.state, node, 0);
    std::vector<H> phi(6);
    // Position and rotation parameters held at their reference values (x0, c = 0).
    for (int i = 0; i < 3; ++i) {
      phi[i] = v.x(i) - ctx.model.nodes[node].position(i);
      phi[3 + i] = v.param(i);
    }
    out.force.setZero(6);
    out.stiffness.setZero(6, 6);
    fill_constraints<6>(select(phi, keep_), lambda, 6, out);
  }
  std::vector<JointOutput> outputs(const JointContext&, const Eigen::VectorXd& lambda) const override {
    Eigen::VectorXd full = Eigen::VectorXd::Zero(6);
    if (keep_.empty()) full = lambda;
    else for (size_t i = 0; i < keep_.size(); ++i) full(keep_[i]) = lambda(static_cast<Eigen::Index>(i));
    return {{"reaction_force_x", -full(0), "N"}, {"reaction_force_y", -full(1), "N"},
            {"reaction_force_z", -full(2), "N"}, {"reaction_moment_x", -full(3), "N m"},
            {"reaction_moment_y", -full(4), "N m"}, {"reaction_moment_z", -full(5), "N m"}};
  }
  std::string equation_name(int i) const override {
    static const char* names[] = {"x", "y", "z", "rotation x", "rotation y", "rotation z"};
    return std::string("clamp of node ") + std::to_string(spec_.node_b) + " (" + names[keep_.empty() ? i : keep_[i]] + ")";
  }

 private:
  std::vector<int> keep_;
};

/// Planar guide: z and the rotation parameters about x and y held at zero.
class Planar final : public Joint {
 public:
  using Joint::Joint;
  int num_equations() const override { return 3; }
  void evaluate(const JointContext& ctx, const Eigen::VectorXd& lambda, JointEval& out) const override {
    using H = Hyper<6>;
    const int node = spec_.node_b;
    out = JointEval{};
    push_node_dofs(node, out);
    const NodeVars<6> v = node_vars<6>(ctx.model, ctx.state, node, 0);
    std::vector<H> phi{v.x(2) - ctx.model.nodes[node].position(2), v.param(0), v.param(1)};
    out.force.setZero(6);
    out.stiffness.setZero(6, 6);
    fill_constraints<6>(phi, lambda, 6, out);
  }
  std::vector<JointOutput> outputs(const JointContext&, const Eigen::VectorXd&) const override { return {}; }
  std::string equation_name(int i) const override {
    static const char* names[] = {"z", "rotation x", "rotation y"};
    return "planar guide of node " + std::to_string(spec_.node_b) + " (" + names[i] + ")";
  }
};

class Rigid final : public Joint {
 public:
  Rigid(const Model& model, JointSpec spec) : Joint(std::move(spec)) {
    offset_ = model.nodes[spec_.node_b].position - model.nodes[spec_.node_a].position;
    if (model.planar) keep_ = {0, 1, 5};
  }
  int num_equations() const override { return keep_.empty() ? 6 : static_cast<int>(keep_.size()); }
  void evaluate(const JointContext& ctx, const Eigen::VectorXd& lambda, JointEval& out) const override {
    using H = Hyper<12>;
    out = JointEval{};
    push_node_dofs(spec_.node_a, out);
    push_node_dofs(spec_.node_b, out);
    const NodeVars<12> a = node_vars<12>(ctx.model, ctx.state, spec_.node_a, 0);
    const NodeVars<12> b = node_vars<12>(ctx.model, ctx.state, spec_.node_b, 6);
    // x_B = x_A + R_A (x0_B - x0_A) and R_B = R_A (rotations from the reference frames).
    const Vec3<H> dp = b.x - a.x - a.rotation * offset_.cast<H>();
    const Vec3<H> dr = wm_compose<H>(b.param, wm_inverse<H>(a.param));
    std::vector<H> phi(6);
    for (int i = 0; i < 3; ++i) {
      phi[i] = dp(i);
      phi[3 + i] = dr(i);
    }
    out.force.setZero(12);
    out.stiffness.setZero(12, 12);
    fill_constraints<12>(select(phi, keep_), lambda, 12, out);
  }
  std::vector<JointOutput> outputs(const JointContext&, const Eigen::VectorXd& lambda) const override {
    return {{"reaction_force_x", lambda(0), "N"}, {"reaction_force_y", lambda(1), "N"}};
  }

 private:
  std::vector<int> keep_;
  Eigen::Vector3d offset_;
};

}  // namespace

std::unique_ptr<Joint> make_clamp(const Model& model, const JointSpec& spec) {
  return std::make_unique<Clamp>(model, spec);
}
std::unique_ptr<Joint> make_planar(const Model&, const JointSpec& spec) { return std::make_unique<Planar>(spec); }
std::unique_ptr<Joint> make_rigid(const Model& model, const JointSpec& spec) {
  return std::make_unique<Rigid>(model, spec);
}

}  // namespace tfmb::beam::detail
