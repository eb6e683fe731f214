// Revolute joint with radial clearance (FORMULATION.md sec. 4.2): pin of radius Rp on body B in a
// hole of radius Rh on body A. The hinge axes stay parallel and the pin cannot slide along the axis
// (three constraints); in the hole plane the pin moves freely until the eccentricity e exceeds the
// radial clearance cr = Rh - Rp, then a penalty normal force F_n = K (e - cr) pushes it back
// (compliant-contact option (b) of FORMULATION.md with exponent 1). In dynamics a regularised
// Coulomb friction F_t = -mu F_n tanh(|v_t| / v_reg) v_t/|v_t| acts at the contact point.
#include <cmath>
#include <string>

#include "joint_common.hpp"

namespace tfmb::beam::detail {
namespace {

class Clearance final : public Joint {
 public:
  Clearance(const Model& model, JointSpec spec) : Joint(std::move(spec)) {
    const double cr = spec_.hole_radius - spec_.pin_radius;
    if (!(spec_.pin_radius > 0.0) || !(cr > 0.0))
      throw std::invalid_argument("clearance joint '" + spec_.name + "': need hole_radius > pin_radius > 0 (got " +
                                  std::to_string(spec_.hole_radius) + ", " + std::to_string(spec_.pin_radius) +
                                  "); use a revolute joint for zero clearance");
    if (!(spec_.contact_stiffness > 0.0))
      throw std::invalid_argument("clearance joint '" + spec_.name + "': contact_stiffness must be > 0 [N/m]");
    planar_ = model.planar;
    const Eigen::Matrix3d e = frame_from_axis(spec_.axis);
    const Node& nb = model.nodes[spec_.node_b];
    frame_b_ = nb.frame.transpose() * e;
    if (spec_.node_a >= 0) {
      frame_a_ = model.nodes[spec_.node_a].frame.transpose() * e;
    } else {
      frame_a_ = e;
      ground_point_ = nb.position;
    }
  }
  int num_equations() const override { return planar_ ? 0 : 3; }

  template <int N>
  struct Kinematics {
    Mat3<Hyper<N>> ea, eb;
    Vec3<Hyper<N>> d;  // pin-centre offset in the hole plane
    Vec3<Hyper<N>> xa, xb;
  };

  template <int N>
  Kinematics<N> kinematics(const JointContext& ctx, JointEval* out) const {
    Kinematics<N> k;
    NodeVars<N> a, b;
    if (spec_.node_a < 0) {
      a = ground_vars<N>(ground_point_);
      b = node_vars<N>(ctx.model, ctx.state, spec_.node_b, 0);
      if (out) push_node_dofs(spec_.node_b, *out);
    } else {
      a = node_vars<N>(ctx.model, ctx.state, spec_.node_a, 0);
      b = node_vars<N>(ctx.model, ctx.state, spec_.node_b, 6);
      if (out) {
        push_node_dofs(spec_.node_a, *out);
        push_node_dofs(spec_.node_b, *out);
      }
    }
    k.ea = a.frame * frame_a_.template cast<Hyper<N>>();
    k.eb = b.frame * frame_b_.template cast<Hyper<N>>();
    k.xa = a.x;
    k.xb = b.x;
    const Vec3<Hyper<N>> rel = b.x - a.x;
    const Vec3<Hyper<N>> e3 = k.ea.col(2);
    k.d = rel - e3 * e3.dot(rel);
    return k;
  }

  void evaluate(const JointContext& ctx, const Eigen::VectorXd& lambda, JointEval& out) const override {
    using H = Hyper<12>;
    out = JointEval{};
    const Kinematics<12> k = kinematics<12>(ctx, &out);
    const int nv = static_cast<int>(out.dofs.size());
    std::vector<H> phi{k.ea.col(2).dot(k.eb.col(0)), k.ea.col(2).dot(k.eb.col(1)),
                       k.ea.col(2).dot(k.xb - k.xa)};
    out.force.setZero(nv);
    out.stiffness.setZero(nv, nv);
    if (planar_) phi.clear();  // the planar guides already hold the axis and the axial motion
    fill_constraints<12>(phi, lambda, nv, out);
    const double cr = spec_.hole_radius - spec_.pin_radius;
    const H e2 = k.d.dot(k.d);
    if (std::sqrt(e2.v) <= cr) return;
    const H e = sqrt(e2);
    const H pen = e - cr;
    add_potential<12>(0.5 * spec_.contact_stiffness * pen * pen, nv, out);
    if (spec_.friction_coefficient > 0.0 && ctx.node_velocity != nullptr) add_friction(ctx, k, e.v, pen.v, out);
  }

  std::vector<JointOutput> outputs(const JointContext& ctx, const Eigen::VectorXd& lambda) const override {
    const Kinematics<12> k = kinematics<12>(ctx, nullptr);
    Eigen::Vector3d d;
    for (int i = 0; i < 3; ++i) d(i) = k.d(i).v;
    const double cr = spec_.hole_radius - spec_.pin_radius;
    const double ecc = d.norm();
    const double pen = std::max(ecc - cr, 0.0);
    return {{"eccentricity", ecc, "m"},
            {"gap", std::max(cr - ecc, 0.0), "m"},
            {"penetration", pen, "m"},
            {"contact_force", spec_.contact_stiffness * pen, "N"},
            {"axial_force", planar_ ? 0.0 : lambda(2), "N"}};
  }
  std::string equation_name(int i) const override {
    static const char* names[] = {"axis tilt 1", "axis tilt 2", "axial slide"};
    return "clearance joint '" + spec_.name + "' (" + names[i] + ")";
  }

 private:
  /// Regularised Coulomb friction at the contact point, evaluated at the current iterate (its
  /// dependence on positions is left out of the tangent; Newton still converges, more slowly).
  template <int N>
  void add_friction(const JointContext& ctx, const Kinematics<N>& k, double ecc, double pen, JointEval& out) const {
    Eigen::Vector3d d, e3;
    for (int i = 0; i < 3; ++i) {
      d(i) = k.d(i).v;
      e3(i) = k.ea(i, 2).v;
    }
    const Eigen::Vector3d n = d / ecc;
    const double fn = spec_.contact_stiffness * pen;
    const int nb = spec_.node_b;
    const Eigen::Vector3d vb = (*ctx.node_velocity)[nb] + (*ctx.node_angular_velocity)[nb].cross(spec_.pin_radius * n);
    Eigen::Vector3d va = Eigen::Vector3d::Zero();
    if (spec_.node_a >= 0)
      va = (*ctx.node_velocity)[spec_.node_a] +
           (*ctx.node_angular_velocity)[spec_.node_a].cross(spec_.hole_radius * n);
    Eigen::Vector3d vt = vb - va;
    vt -= n * n.dot(vt) + e3 * e3.dot(vt);
    const double speed = vt.norm();
    if (speed < 1e-14) return;
    const double vreg = spec_.friction_regularisation_speed;
    const Eigen::Vector3d ft = -spec_.friction_coefficient * fn * std::tanh(speed / vreg) * vt / speed;
    // Residual convention: force = internal - external, so applied forces enter with a minus sign.
    const int ob = spec_.node_a >= 0 ? 6 : 0;
    out.force.segment<3>(ob) -= ft;
    out.force.segment<3>(ob + 3) -= (spec_.pin_radius * n).cross(ft);
    if (spec_.node_a >= 0) {
      out.force.segment<3>(0) += ft;
      out.force.segment<3>(3) += (spec_.hole_radius * n).cross(ft);
    }
    // Viscous-like tangent of the regularised law near stick, d F_t / d v_t ~ mu F_n / v_reg.
    const double c = spec_.friction_coefficient * fn / vreg * (1.0 - std::pow(std::tanh(speed / vreg), 2));
    const Eigen::Matrix3d pt = Eigen::Matrix3d::Identity() - n * n.transpose() - e3 * e3.transpose();
    out.stiffness.block<3, 3>(ob, ob) += c * ctx.rate_factor * pt;
  }

  bool planar_ = false;
  Eigen::Matrix3d frame_a_, frame_b_;
  Eigen::Vector3d ground_point_ = Eigen::Vector3d::Zero();
};

}  // namespace

std::unique_ptr<Joint> make_clearance(const Model& model, const JointSpec& spec) {
  return std::make_unique<Clearance>(model, spec);
}

}  // namespace tfmb::beam::detail
