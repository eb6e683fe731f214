// Revolute joint with the relative rotation phi as an extra unknown (DYMORE style,
// FORMULATION.md sec. 4.1): three translational constraints, two keeping the hinge axes parallel
// and one defining phi. Torsional spring, damper and actuator act directly on phi.
#include <string>

#include "joint_common.hpp"

namespace tfmb::beam::detail {
namespace {

class Revolute final : public Joint {
 public:
  Revolute(const Model& model, JointSpec spec) : Joint(std::move(spec)) {
    if (spec_.axis.norm() < 1e-12)
      throw std::invalid_argument("revolute joint '" + spec_.name + "': axis has zero length; give the hinge direction");
    const Eigen::Matrix3d e = frame_from_axis(spec_.axis);
    const Node& nb = model.nodes[spec_.node_b];
    frame_b_ = nb.frame.transpose() * e;
    planar_ = model.planar;
    if (planar_ && std::abs(std::abs(spec_.axis.normalized().z()) - 1.0) > 1e-12)
      throw std::invalid_argument("revolute joint '" + spec_.name + "': in a planar model the hinge axis must be z");
    if (spec_.node_a >= 0) {
      const Node& na = model.nodes[spec_.node_a];
      frame_a_ = na.frame.transpose() * e;
      if ((na.position - nb.position).norm() > 1e-9 * (1.0 + nb.position.norm()))
        throw std::invalid_argument("revolute joint '" + spec_.name + "': nodes " + std::to_string(spec_.node_a) +
                                    " and " + std::to_string(spec_.node_b) +
                                    " are not at the same point; a hinge joins two coincident nodes");
    } else {
      frame_a_ = e;
      ground_point_ = nb.position;
    }
  }
  int num_equations() const override {
    if (planar_) return spec_.prescribed ? 4 : 3;
    return spec_.prescribed ? 7 : 6;
  }
  int num_internal_dofs() const override { return 1; }

  void evaluate(const JointContext& ctx, const Eigen::VectorXd& lambda, JointEval& out) const override {
    using H = Hyper<13>;
    out = JointEval{};
    NodeVars<13> a, b;
    handle_vars<13>(ctx, spec_, ground_point_, a, b, out);
    const int iphi = static_cast<int>(out.dofs.size());
    out.dofs.push_back(first_internal_dof_);
    const int nv = iphi + 1;
    const H phi_var = H::variable(iphi, ctx.state.joint_dofs(first_internal_dof_local(ctx)));

    const Mat3<H> ea = a.frame * frame_a_.cast<H>();
    const Mat3<H> eb = b.frame * frame_b_.cast<H>();
    std::vector<H> phi;
    for (int i = 0; i < 3; ++i) phi.push_back(a.x(i) - b.x(i));
    phi.push_back(ea.col(2).dot(eb.col(0)));
    phi.push_back(ea.col(2).dot(eb.col(1)));
    phi.push_back(ea.col(1).dot(eb.col(0)) * cos(phi_var) - ea.col(0).dot(eb.col(0)) * sin(phi_var));
    if (spec_.prescribed) phi.push_back(phi_var - prescribed_angle(ctx.load_factor));

    out.force.setZero(nv);
    out.stiffness.setZero(nv, nv);
    if (planar_) phi = select(phi, spec_.prescribed ? std::vector<int>{0, 1, 5, 6} : std::vector<int>{0, 1, 5});
    fill_constraints<13>(phi, lambda, nv, out);
    const double angle = phi_var.v;
    if (spec_.spring_stiffness != 0.0) {
      out.force(iphi) += spec_.spring_stiffness * (angle - spec_.spring_rest_angle);
      out.stiffness(iphi, iphi) += spec_.spring_stiffness;
    }
    if (spec_.damping != 0.0 && ctx.joint_rates != nullptr) {
      out.force(iphi) += spec_.damping * (*ctx.joint_rates)(first_internal_dof_local(ctx));
      out.stiffness(iphi, iphi) += spec_.damping * ctx.rate_factor;
    }
  }

  std::vector<JointOutput> outputs(const JointContext& ctx, const Eigen::VectorXd& lambda) const override {
    const double angle = ctx.state.joint_dofs(first_internal_dof_local(ctx));
    std::vector<JointOutput> o{{"relative_rotation", angle, "rad"},
                               {"reaction_force_x", lambda(0), "N"},
                               {"reaction_force_y", lambda(1), "N"},
                               {"reaction_force_z", lambda(2), "N"},
                               {"spring_moment", spec_.spring_stiffness * (angle - spec_.spring_rest_angle), "N m"}};
    if (spec_.prescribed) o.push_back({"actuator_moment", lambda(lambda.size() - 1), "N m"});
    return o;
  }
  std::string equation_name(int i) const override {
    static const char* names[] = {"x", "y", "z", "axis tilt 1", "axis tilt 2", "angle", "actuator"};
    static const int planar_map[] = {0, 1, 5, 6};
    return "revolute joint '" + spec_.name + "' (" + names[planar_ ? planar_map[i] : i] + ")";
  }

 private:
  /// Joint dofs are stored after the 6 n nodal dofs in the global numbering.
  int first_internal_dof_local(const JointContext& ctx) const {
    return first_internal_dof_ - 6 * static_cast<int>(ctx.model.nodes.size());
  }
  /// Actuator angle: a table of (time or load factor, angle) if given, else angle x factor.
  double prescribed_angle(double factor) const {
    const auto& t = spec_.prescribed_table;
    if (t.empty()) return spec_.prescribed_angle * factor;
    if (factor <= t.front().first) return t.front().second;
    for (size_t i = 1; i < t.size(); ++i)
      if (factor <= t[i].first)
        return t[i - 1].second + (t[i].second - t[i - 1].second) * (factor - t[i - 1].first) / (t[i].first - t[i - 1].first);
    return t.back().second;
  }
  bool planar_ = false;
  Eigen::Matrix3d frame_a_, frame_b_;  // joint frame (e3 = hinge axis) in each body's material frame
  Eigen::Vector3d ground_point_ = Eigen::Vector3d::Zero();
};

}  // namespace

std::unique_ptr<Joint> make_revolute(const Model& model, const JointSpec& spec) {
  return std::make_unique<Revolute>(model, spec);
}

}  // namespace tfmb::beam::detail
