// Lower pairs (spherical, cylindrical, prismatic, screw, planar) as holonomic constraints between
// two nodes that coincide in the reference configuration, or a node and the ground. Joint frame
// e1, e2, e3 with e3 = `axis`, carried by each body (e_A on node_a, e_B on node_b); d = x_B - x_A.
// Constraints (Bauchau, Flexible Multibody Dynamics, ch. on joints, in the form of
// FORMULATION.md sec. 4.1):
//   spherical    d = 0                                                  (3)
//   planar pair  e3A.d = 0,  e3A.e1B = e3A.e2B = 0                       (3)
//   cylindrical  e1A.d = e2A.d = 0,  e3A.e1B = e3A.e2B = 0               (4)
//   prismatic    cylindrical + e2A.e1B = 0 (no rotation about e3)        (5)
//   screw        cylindrical + (e2A.e1B) cos(phi) - (e1A.e1B) sin(phi) = 0 (phi the relative
//                rotation, an extra unknown as in the revolute joint) + e3A.d - lead phi = 0 (6)
// Reactions: the constraint force and moment the joint applies to node_b, -B_b^T lambda.
// Planar models: the prismatic pair with its two in-plane equations (lateral offset and relative
// turn held), and the pin in a slot, the prismatic pair's lateral equation alone (sliding along
// the axis and turning both free: a hinge whose pin runs in a slot, or a roller support).
#include <cmath>
#include <string>

#include "joint_common.hpp"

namespace tfmb::beam::detail {
namespace {

const char* kind_name(JointKind k) {
  switch (k) {
    case JointKind::spherical: return "spherical";
    case JointKind::cylindrical: return "cylindrical";
    case JointKind::prismatic: return "prismatic";
    case JointKind::screw: return "screw";
    case JointKind::planar_pair: return "planar";
    case JointKind::pin_in_slot:
      return "pin-in-slot";
    default: return "lower pair";
  }
}

class LowerPair final : public Joint {
 public:
  LowerPair(const Model& model, JointSpec spec) : Joint(std::move(spec)) {
    const std::string what = std::string(kind_name(spec_.kind)) + " joint '" + spec_.name + "'";
    if (spec_.axis.norm() < 1e-12) throw std::invalid_argument(what + ": axis has zero length");
    if (spec_.kind == JointKind::screw && !std::isfinite(spec_.screw_lead))
      throw std::invalid_argument(what + ": screw_lead must be finite [m/rad]");
    Eigen::Matrix3d e = frame_from_axis(spec_.axis);
    if (model.planar) {
      // In the x-y plane only the slider is a new pair (a spherical or cylindrical joint is a
      // revolute one there). Frame e2 = z, so e1A.d (in-plane lateral) and e3A.e1B (in-plane
      // rotation) are its in-plane equations; the planar guides hold the rest. The pin in a
      // slot keeps the lateral one only.
      if (spec_.kind != JointKind::prismatic && spec_.kind != JointKind::pin_in_slot)
        throw std::invalid_argument(what +
                                    ": in a planar model only the prismatic pair and the pin in a "
                                    "slot are available (use a revolute joint)");
      if (std::abs(spec_.axis.z()) > 1e-12 * spec_.axis.norm())
        throw std::invalid_argument(what + ": in a planar model the sliding axis must lie in the x-y plane");
      e.col(2) = spec_.axis.normalized();
      e.col(1) = Eigen::Vector3d::UnitZ();
      e.col(0) = e.col(1).cross(e.col(2));
      keep_ = spec_.kind == JointKind::pin_in_slot ? std::vector<int>{0} : std::vector<int>{0, 2};
    } else if (spec_.kind == JointKind::pin_in_slot) {
      throw std::invalid_argument(
          what + ": the pin in a slot is a planar joint (in 3D use a cylindrical or planar pair)");
    }
    const Node& nb = model.nodes[spec_.node_b];
    frame_b_ = nb.frame.transpose() * e;
    if (spec_.node_a >= 0) {
      const Node& na = model.nodes[spec_.node_a];
      frame_a_ = na.frame.transpose() * e;
      if ((na.position - nb.position).norm() > 1e-9 * (1.0 + nb.position.norm()))
        throw std::invalid_argument(what + ": nodes " + std::to_string(spec_.node_a) + " and " +
                                    std::to_string(spec_.node_b) + " are not at the same point");
    } else {
      frame_a_ = e;
      ground_point_ = nb.position;
    }
  }
  int num_equations() const override {
    if (!keep_.empty()) return static_cast<int>(keep_.size());
    switch (spec_.kind) {
      case JointKind::spherical:
      case JointKind::planar_pair: return 3;
      case JointKind::cylindrical: return 4;
      case JointKind::prismatic: return 5;
      default: return 6;  // screw
    }
  }
  int num_internal_dofs() const override { return spec_.kind == JointKind::screw ? 1 : 0; }

  void evaluate(const JointContext& ctx, const Eigen::VectorXd& lambda, JointEval& out) const override {
    using H = Hyper<13>;
    out = JointEval{};
    NodeVars<13> a, b;
    handle_vars<13>(ctx, spec_, ground_point_, a, b, out);
    H phi_var(0.0);
    if (spec_.kind == JointKind::screw) {
      const int iphi = static_cast<int>(out.dofs.size());
      out.dofs.push_back(first_internal_dof_);
      phi_var = H::variable(iphi, ctx.state.joint_dofs(first_internal_dof_ - 6 * static_cast<int>(ctx.model.nodes.size())));
    }
    const int nv = static_cast<int>(out.dofs.size());
    const Mat3<H> ea = a.frame * frame_a_.cast<H>();
    const Mat3<H> eb = b.frame * frame_b_.cast<H>();
    const Vec3<H> d = b.x - a.x;
    std::vector<H> phi;
    switch (spec_.kind) {
      case JointKind::spherical:
        for (int i = 0; i < 3; ++i) phi.push_back(d(i));
        break;
      case JointKind::planar_pair:
        phi = {ea.col(2).dot(d), ea.col(2).dot(eb.col(0)), ea.col(2).dot(eb.col(1))};
        break;
      default:
        phi = {ea.col(0).dot(d), ea.col(1).dot(d), ea.col(2).dot(eb.col(0)), ea.col(2).dot(eb.col(1))};
        if (spec_.kind == JointKind::prismatic) phi.push_back(ea.col(1).dot(eb.col(0)));
        if (spec_.kind == JointKind::screw) {
          phi.push_back(ea.col(1).dot(eb.col(0)) * cos(phi_var) - ea.col(0).dot(eb.col(0)) * sin(phi_var));
          phi.push_back(ea.col(2).dot(d) - spec_.screw_lead * phi_var);
        }
    }
    out.force.setZero(nv);
    out.stiffness.setZero(nv, nv);
    fill_constraints<13>(select(phi, keep_), lambda, nv, out);
  }

  std::vector<JointOutput> outputs(const JointContext& ctx, const Eigen::VectorXd& lambda) const override {
    JointEval e;
    evaluate(ctx, lambda, e);
    // Force and moment on node_b: -B_b^T lambda (node_b's block is the last node block).
    const int b0 = spec_.node_a < 0 ? 0 : 6;
    const Eigen::VectorXd fb = -e.jacobian.middleCols(b0, 6).transpose() * lambda;
    std::vector<JointOutput> o{{"reaction_force_x", fb(0), "N"},   {"reaction_force_y", fb(1), "N"},
                               {"reaction_force_z", fb(2), "N"},   {"reaction_moment_x", fb(3), "N m"},
                               {"reaction_moment_y", fb(4), "N m"}, {"reaction_moment_z", fb(5), "N m"}};
    // Relative motion along/about the axis, for the kinds that allow it.
    const Eigen::Matrix3d ra = spec_.node_a < 0 ? Eigen::Matrix3d::Identity() : current_rotation(ctx.state, spec_.node_a);
    const Eigen::Matrix3d fa = spec_.node_a < 0 ? frame_a_ : Eigen::Matrix3d(ra * ctx.model.nodes[spec_.node_a].frame * frame_a_);
    const Eigen::Matrix3d fb_frame = current_rotation(ctx.state, spec_.node_b) * ctx.model.nodes[spec_.node_b].frame * frame_b_;
    const Eigen::Vector3d xa = spec_.node_a < 0 ? ground_point_ : ctx.state.position[spec_.node_a];
    const Eigen::Vector3d d = ctx.state.position[spec_.node_b] - xa;
    if (spec_.kind != JointKind::spherical) {
      if (spec_.kind == JointKind::screw)
        o.push_back({"relative_rotation", ctx.state.joint_dofs(first_internal_dof_ - 6 * static_cast<int>(ctx.model.nodes.size())), "rad"});
      else if (spec_.kind == JointKind::pin_in_slot)  // in-plane turn about z = e2 (e1 = e2 x e3)
        o.push_back({"relative_rotation",
                     std::atan2(fa.col(0).dot(fb_frame.col(2)), fa.col(2).dot(fb_frame.col(2))),
                     "rad"});
      else if (spec_.kind != JointKind::prismatic)
        o.push_back({"relative_rotation", std::atan2(fa.col(1).dot(fb_frame.col(0)), fa.col(0).dot(fb_frame.col(0))), "rad"});
      if (spec_.kind != JointKind::planar_pair) o.push_back({"sliding", fa.col(2).dot(d), "m"});
    }
    return o;
  }
  std::string equation_name(int i) const override {
    return std::string(kind_name(spec_.kind)) + " joint '" + spec_.name + "' (equation " + std::to_string(i) + ")";
  }

 private:
  Eigen::Matrix3d frame_a_, frame_b_;  // joint frame (e3 = axis) in each body's material frame
  Eigen::Vector3d ground_point_ = Eigen::Vector3d::Zero();
  std::vector<int> keep_;  // planar models: the in-plane equations
};

}  // namespace

std::unique_ptr<Joint> make_lower_pair(const Model& model, const JointSpec& spec) {
  return std::make_unique<LowerPair>(model, spec);
}

}  // namespace tfmb::beam::detail
