// Revolute joint with radial clearance (FORMULATION.md sec. 4.2): pin of radius Rp on body B in a
// hole of radius Rh on body A. The hinge axes stay parallel and the pin cannot slide along the axis
// (three constraints); in the hole plane the pin moves freely until the eccentricity e exceeds the
// radial clearance cr = Rh - Rp, then a penalty normal force F_n = K (e - cr) pushes it back
// (compliant-contact option (b) of FORMULATION.md with exponent 1). In dynamics a regularised
// Coulomb friction F_t = -mu F_n tanh(|v_t| / v_reg) v_t/|v_t| acts at the contact point.
// Statics: inside an open gap nothing holds the pin, so a body carried only by the joint is a
// mechanism until contact closes and the Newton tangent is singular at the unloaded start. The
// static tangent therefore gets a weak centring stiffness, kStaticCentring times the contact
// stiffness, on the pin eccentricity; the residual does not, so a converged solution is the
// exact one (a modified Newton: the first corrections carry the pin across the gap to contact,
// after which the contact stiffness dominates). Dynamics needs none: the mass holds the motion.
#include <cmath>
#include <string>

#include "joint_common.hpp"

namespace tfmb::beam::detail {
namespace {

constexpr double kStaticCentring = 1e-4;

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
    const bool statics = ctx.node_velocity == nullptr;
    if (statics) {
      const H centring = 0.5 * kStaticCentring * spec_.contact_stiffness * e2;
      for (int p = 0; p < nv; ++p)
        for (int q = 0; q < nv; ++q) out.stiffness(p, q) += centring.hess(p, q);
    }
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
    const double th = std::tanh(speed / vreg);
    const Eigen::Vector3d dir = vt / speed;
    const Eigen::Vector3d ft = -spec_.friction_coefficient * fn * th * dir;
    // Generalized forces on the bodies: force at the contact point and its moment about the node,
    // f = G F with G = [I; S(r)] (r = R_p n on the pin, R_h n on the hole, with opposite sign).
    const Eigen::Matrix3d id = Eigen::Matrix3d::Identity();
    const Eigen::Matrix3d pt = id - n * n.transpose() - e3 * e3.transpose();
    const Eigen::Vector3d rb = spec_.pin_radius * n, ra = spec_.hole_radius * n;
    const bool two = spec_.node_a >= 0;
    const int ob = two ? 6 : 0;
    // Residual convention: internal - external, so applied forces enter with a minus sign.
    out.force.segment<3>(ob) -= ft;
    out.force.segment<3>(ob + 3) -= rb.cross(ft);
    if (two) {
      out.force.segment<3>(0) += ft;
      out.force.segment<3>(3) += ra.cross(ft);
    }
    // Velocity tangent (positions held): dF/dv_t = -mu F_n [tanh(s/vr)/s (P - d d^T) +
    // sech^2(s/vr)/vr d d^T], v_t = P (v_B + w_B x r_b - v_A - w_A x r_a), and d(rate)/d(increment)
    // = rate_factor. The dependence on positions is left out (Newton converges, more slowly).
    const Eigen::Matrix3d dd = dir * dir.transpose();
    const Eigen::Matrix3d dfdv =
        -spec_.friction_coefficient * fn * ((th / speed) * (pt - dd) + (1.0 - th * th) / vreg * dd);
    Eigen::Matrix<double, 3, 12> jv = Eigen::Matrix<double, 3, 12>::Zero();  // d v_t / d(rates)
    Eigen::Matrix<double, 12, 3> g = Eigen::Matrix<double, 12, 3>::Zero();   // generalized force map
    jv.block<3, 3>(0, ob) = pt;
    jv.block<3, 3>(0, ob + 3) = -pt * skew<double>(rb);
    g.block<3, 3>(ob, 0) = id;
    g.block<3, 3>(ob + 3, 0) = skew<double>(rb);
    if (two) {
      jv.block<3, 3>(0, 0) = -pt;
      jv.block<3, 3>(0, 3) = pt * skew<double>(ra);
      g.block<3, 3>(0, 0) = -id;
      g.block<3, 3>(3, 0) = -skew<double>(ra);
    }
    const int nv = two ? 12 : 6;
    const Eigen::MatrixXd kf = -ctx.rate_factor * (g * dfdv * jv).topLeftCorner(nv, nv);
    out.stiffness.topLeftCorner(nv, nv) += kf;
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
