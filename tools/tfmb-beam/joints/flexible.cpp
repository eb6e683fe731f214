// Flexible joint (bushing) between handle k = node_a (or the ground) and handle l = node_b: no
// constraint, only the elastic energy of flexible_joint.hpp acting on the two nodes.
#include <string>

#include "joint_common.hpp"
#include "tfmb-beam/flexible_joint.hpp"

namespace tfmb::beam::detail {
namespace {

class Flexible final : public Joint {
 public:
  Flexible(const Model& model, JointSpec spec) : Joint(std::move(spec)) {
    if (!spec_.flexible_law) throw std::invalid_argument("flexible joint '" + spec_.name + "': no stiffness/measure data");
    const FlexibleJointLaw& law = *spec_.flexible_law;
    if (!law.stiffness.allFinite())
      throw std::invalid_argument("flexible joint '" + spec_.name + "': stiffness matrix has non-finite entries");
    const Eigen::Matrix3d b = law.frame;
    if (!((b.transpose() * b - Eigen::Matrix3d::Identity()).norm() < 1e-9) || !(b.determinant() > 0.0))
      throw std::invalid_argument("flexible joint '" + spec_.name + "': joint frame is not a right-handed orthonormal frame");
    if (law.measure == FlexibleMeasure::proposed) {
      try {
        check_measure_functions(law.functions);
      } catch (const std::invalid_argument& e) {
        throw std::invalid_argument("flexible joint '" + spec_.name + "': " + e.what());
      }
    }
    const Eigen::Vector3d xb = model.nodes[spec_.node_b].position;
    if (spec_.node_a >= 0 && (model.nodes[spec_.node_a].position - xb).norm() > 1e-9 * (1.0 + xb.norm()))
      throw std::invalid_argument("flexible joint '" + spec_.name + "': nodes " + std::to_string(spec_.node_a) + " and " +
                                  std::to_string(spec_.node_b) +
                                  " are not at the same point; the joint's handles coincide in the reference configuration");
    ground_point_ = xb;
  }
  int num_equations() const override { return 0; }

  void evaluate(const JointContext& ctx, const Eigen::VectorXd&, JointEval& out) const override {
    out = JointEval{};
    const FlexibleJointResponse r = response(ctx.state);
    const bool ground = spec_.node_a < 0;
    if (!ground) push_node_dofs(spec_.node_a, out);
    push_node_dofs(spec_.node_b, out);
    const int nv = static_cast<int>(out.dofs.size());
    const int first = ground ? 6 : 0;  // local block of the 12 joint variables used
    out.phi.resize(0);
    out.jacobian.setZero(0, nv);
    out.hessian_lambda.setZero(nv, nv);
    out.force = r.force.segment(first, nv);
    out.stiffness = r.tangent.block(first, first, nv, nv);
  }

  std::vector<JointOutput> outputs(const JointContext& ctx, const Eigen::VectorXd&) const override {
    const FlexibleJointResponse r = response(ctx.state);
    std::vector<JointOutput> o;
    const char* axes[] = {"1", "2", "3"};
    for (int i = 0; i < 3; ++i) o.push_back({std::string("stretch_") + axes[i], r.measures(i), "m"});
    for (int i = 0; i < 3; ++i) o.push_back({std::string("wryness_") + axes[i], r.measures(3 + i), "1"});
    o.push_back({"strain_energy", r.energy, "J"});
    // Force and moment the joint applies to handle l (node_b), spatial components.
    const char* keys[] = {"reaction_force_x", "reaction_force_y", "reaction_force_z",
                          "reaction_moment_x", "reaction_moment_y", "reaction_moment_z"};
    for (int i = 0; i < 6; ++i) o.push_back({keys[i], -r.force(6 + i), i < 3 ? "N" : "N m"});
    return o;
  }
  std::string equation_name(int i) const override { return "flexible joint '" + spec_.name + "' " + std::to_string(i); }

 private:
  FlexibleJointResponse response(const State& state) const {
    HandleState k, l;
    if (spec_.node_a >= 0) {
      k.position = state.position[spec_.node_a];
      k.rotation = state.rotation[spec_.node_a];
    } else {
      k.position = ground_point_;
    }
    l.position = state.position[spec_.node_b];
    l.rotation = state.rotation[spec_.node_b];
    return evaluate_flexible_joint(*spec_.flexible_law, k, l);
  }
  Eigen::Vector3d ground_point_ = Eigen::Vector3d::Zero();
};

}  // namespace

std::unique_ptr<Joint> make_flexible(const Model& model, const JointSpec& spec) {
  return std::make_unique<Flexible>(model, spec);
}

}  // namespace tfmb::beam::detail
