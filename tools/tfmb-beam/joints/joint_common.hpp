// Shared helpers for the joint implementations (private to the library).
#pragma once

#include <stdexcept>

#include "tfmb-beam/hyper_dual.hpp"
#include "tfmb-beam/joints.hpp"
#include "tfmb-beam/rotation_wm.hpp"

namespace tfmb::beam::detail {

/// Position, section frame and total rotation parameters of a node as functions of its local
/// increments (du at variables offset..offset+2, dtheta at offset+3..offset+5).
template <int N>
struct NodeVars {
  Vec3<Hyper<N>> x;
  Mat3<Hyper<N>> frame;      // R(dtheta) * current frame
  Mat3<Hyper<N>> rotation;   // R(dtheta) * R(c): rotation from the reference frame
  Vec3<Hyper<N>> param;      // WM parameters of `rotation`
};

inline Eigen::Matrix3d current_rotation(const State& state, int node) {
  return wm_rotation<double>(state.rotation[node]);
}

template <int N>
NodeVars<N> node_vars(const Model& model, const State& state, int node, int offset) {
  NodeVars<N> v;
  Vec3<Hyper<N>> du, dth;
  for (int i = 0; i < 3; ++i) {
    du(i) = Hyper<N>::variable(offset + i, 0.0);
    dth(i) = Hyper<N>::variable(offset + 3 + i, 0.0);
  }
  v.x = state.position[node].cast<Hyper<N>>() + du;
  const Mat3<Hyper<N>> rd = wm_rotation<Hyper<N>>(dth);
  const Eigen::Matrix3d r = current_rotation(state, node);
  v.rotation = rd * r.cast<Hyper<N>>();
  v.frame = rd * (r * model.nodes[node].frame).cast<Hyper<N>>();
  v.param = wm_compose<Hyper<N>>(state.rotation[node].cast<Hyper<N>>(), dth);
  return v;
}

/// Ground: a fixed node-like frame at `position` with identity rotation.
template <int N>
NodeVars<N> ground_vars(const Eigen::Vector3d& position) {
  NodeVars<N> v;
  v.x = position.cast<Hyper<N>>();
  v.frame = Eigen::Matrix3d::Identity().cast<Hyper<N>>();
  v.rotation = v.frame;
  v.param = Vec3<Hyper<N>>::Zero();
  return v;
}

/// Fills the constraint part of `out` from Phi evaluated with Hyper<N> (first nv variables used).
template <int N>
void fill_constraints(const std::vector<Hyper<N>>& phi, const Eigen::VectorXd& lambda, int nv, JointEval& out) {
  const int m = static_cast<int>(phi.size());
  out.phi.resize(m);
  out.jacobian.setZero(m, nv);
  out.hessian_lambda.setZero(nv, nv);
  for (int i = 0; i < m; ++i) {
    out.phi(i) = phi[i].v;
    for (int p = 0; p < nv; ++p) out.jacobian(i, p) = phi[i].g[p];
    if (lambda.size() == m && lambda(i) != 0.0)
      for (int p = 0; p < nv; ++p)
        for (int q = 0; q < nv; ++q) out.hessian_lambda(p, q) += lambda(i) * phi[i].hess(p, q);
  }
}

/// Adds a potential's gradient and Hessian (first nv variables) to the joint forces.
template <int N>
void add_potential(const Hyper<N>& energy, int nv, JointEval& out) {
  for (int p = 0; p < nv; ++p) {
    out.force(p) += energy.g[p];
    for (int q = 0; q < nv; ++q) out.stiffness(p, q) += energy.hess(p, q);
  }
}

/// Keeps the equations listed in `keep` (planar models drop the out-of-plane ones).
template <int N>
std::vector<Hyper<N>> select(const std::vector<Hyper<N>>& phi, const std::vector<int>& keep) {
  if (keep.empty()) return phi;
  std::vector<Hyper<N>> out;
  for (int i : keep) out.push_back(phi[i]);
  return out;
}

/// Global dofs of a node's six variables.
inline void push_node_dofs(int node, JointEval& out) {
  out.rotation_blocks.push_back(static_cast<int>(out.dofs.size()) + 3);
  for (int i = 0; i < 6; ++i) out.dofs.push_back(6 * node + i);
}

/// The two handles of a two-node joint as Hyper<N> variables (handle a the ground at
/// `ground_point` when spec.node_a < 0), their node dofs pushed to `out` in variable order.
template <int N>
void handle_vars(const JointContext& ctx, const JointSpec& spec, const Eigen::Vector3d& ground_point,
                 NodeVars<N>& a, NodeVars<N>& b, JointEval& out) {
  if (spec.node_a < 0) {
    a = ground_vars<N>(ground_point);
    b = node_vars<N>(ctx.model, ctx.state, spec.node_b, 0);
    push_node_dofs(spec.node_b, out);
  } else {
    a = node_vars<N>(ctx.model, ctx.state, spec.node_a, 0);
    b = node_vars<N>(ctx.model, ctx.state, spec.node_b, 6);
    push_node_dofs(spec.node_a, out);
    push_node_dofs(spec.node_b, out);
  }
}

/// An orthonormal frame whose third column is `axis`.
inline Eigen::Matrix3d frame_from_axis(const Eigen::Vector3d& axis) {
  const Eigen::Vector3d e3 = axis.normalized();
  Eigen::Vector3d t = std::abs(e3.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  const Eigen::Vector3d e1 = (t - t.dot(e3) * e3).normalized();
  Eigen::Matrix3d f;
  f.col(0) = e1;
  f.col(1) = e3.cross(e1);
  f.col(2) = e3;
  return f;
}

std::unique_ptr<Joint> make_clamp(const Model& model, const JointSpec& spec);
std::unique_ptr<Joint> make_rigid(const Model& model, const JointSpec& spec);
std::unique_ptr<Joint> make_revolute(const Model& model, const JointSpec& spec);
std::unique_ptr<Joint> make_clearance(const Model& model, const JointSpec& spec);
std::unique_ptr<Joint> make_planar(const Model& model, const JointSpec& spec);
std::unique_ptr<Joint> make_flexible(const Model& model, const JointSpec& spec);
std::unique_ptr<Joint> make_lower_pair(const Model& model, const JointSpec& spec);

}  // namespace tfmb::beam::detail
