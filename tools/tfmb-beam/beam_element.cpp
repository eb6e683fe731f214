#include "tfmb-beam/beam_element.hpp"

#include "tfmb-beam/rotation_wm.hpp"

namespace tfmb::beam {
namespace {

using H9 = Hyper<9>;

/// Double matrix times Hyper vector (scalar x Hyper products only, no Hyper x Hyper).
template <typename T>
Vec3<T> mul(const Eigen::Matrix3d& a, const Vec3<T>& v) {
  Vec3<T> r;
  for (int i = 0; i < 3; ++i) r(i) = v(0) * a(i, 0) + v(1) * a(i, 1) + v(2) * a(i, 2);
  return r;
}
template <typename T>
Vec3<T> mul(const Mat3<T>& a, const Eigen::Vector3d& v) {
  Vec3<T> r;
  for (int i = 0; i < 3; ++i) r(i) = a(i, 0) * v(0) + a(i, 1) * v(1) + a(i, 2) * v(2);
  return r;
}
template <typename T>
Vec3<T> mul(const Mat3<T>& a, const Vec3<T>& v) {
  Vec3<T> r;
  for (int i = 0; i < 3; ++i) r(i) = a(i, 0) * v(0) + a(i, 1) * v(1) + a(i, 2) * v(2);
  return r;
}
template <typename T>
Vec3<T> mul_transpose(const Mat3<T>& a, const Vec3<T>& v) {
  Vec3<T> r;
  for (int i = 0; i < 3; ++i) r(i) = a(0, i) * v(0) + a(1, i) * v(1) + a(2, i) * v(2);
  return r;
}

/// theta x z for the increment theta = variables offset..offset+2 (at value zero).
Vec3<H9> variable_cross(int offset, const Vec3<H9>& z) {
  Vec3<H9> r;
  r(0) = times_variable(z(2), offset + 1) - times_variable(z(1), offset + 2);
  r(1) = times_variable(z(0), offset + 2) - times_variable(z(2), offset + 0);
  r(2) = times_variable(z(1), offset + 0) - times_variable(z(0), offset + 1);
  return r;
}
/// R(theta) z and R(theta)^T z with R to second order, I +- S + S^2/2 (exact for a Hyper at 0).
Vec3<H9> rotate_by_increment(int offset, const Vec3<H9>& z, double sign) {
  const Vec3<H9> t = variable_cross(offset, z);
  return z + t * sign + variable_cross(offset, t) * 0.5;
}

/// Relative rotation parameters r_j = WM(Lambda_2(theta)^T Lambda_j(theta)) of the end nodes as
/// functions of the nodal increments (FORMULATION.md sec. 2, objective interpolation about the
/// middle node). r_j = compose(c2j, Lambda_2^T p_j) with p_j the parameters of
/// R(theta_2)^T R(theta_j), taken to second order (a + b + b x a / 2, exact for a Hyper at zero).
std::array<Vec3<H9>, 3> relative_rotations(const std::array<Eigen::Matrix3d, 3>& frame,
                                           const std::array<Eigen::Vector3d, 3>& relative_param,
                                           const std::array<Vec3<H9>, 3>& theta) {
  std::array<Vec3<H9>, 3> r;
  r[1] = Vec3<H9>::Constant(H9(0.0));
  const Eigen::Matrix3d l2t = frame[1].transpose();
  for (int j = 0; j < 3; j += 2) {
    // theta_j x theta_2 = -(theta_2 x theta_j), with theta_2 the variables 3..5.
    const Vec3<H9> p = theta[j] - theta[1] - variable_cross(3, theta[j]) * 0.5;
    r[j] = wm_compose<H9>(relative_param[j].cast<H9>(), mul(l2t, p));
  }
  return r;
}

/// Frame transpose and curvature for plain doubles (reference geometry): exact formulas.
void section_kinematics_reference(const std::array<Eigen::Matrix3d, 3>& frame,
                                  const std::array<Eigen::Vector3d, 3>& relative_param, const std::array<double, 3>& n,
                                  const std::array<double, 3>& dn_ds, Eigen::Matrix3d& a, Eigen::Vector3d& k) {
  Eigen::Vector3d r = n[0] * relative_param[0] + n[2] * relative_param[2];
  Eigen::Vector3d rp = dn_ds[0] * relative_param[0] + dn_ds[2] * relative_param[2];
  a = wm_rotation<double>(r).transpose() * frame[1].transpose();
  k = wm_tangent<double>(r).transpose() * rp;
}

std::array<Eigen::Vector3d, 3> relative_parameters(const std::array<Eigen::Matrix3d, 3>& frame) {
  std::array<Eigen::Vector3d, 3> c;
  for (int j = 0; j < 3; ++j) c[j] = wm_from_rotation(frame[1].transpose() * frame[j]);
  c[1].setZero();
  return c;
}

}  // namespace

ElementGeometry make_element_geometry(const std::array<Eigen::Vector3d, 3>& position,
                                      const std::array<Eigen::Matrix3d, 3>& frame) {
  ElementGeometry g;
  const auto rel = relative_parameters(frame);
  for (int gp = 0; gp < kGaussPoints; ++gp) {
    const double xi = gauss_point(gp);
    const auto n = shape_quadratic(xi);
    const auto dn = shape_quadratic_derivative(xi);
    Eigen::Vector3d dx = Eigen::Vector3d::Zero();
    for (int j = 0; j < 3; ++j) dx += dn[j] * position[j];
    const double jac = dx.norm();
    g.weight_times_jacobian[gp] = jac;  // Gauss weights are 1 for two points
    g.inverse_jacobian[gp] = 1.0 / jac;
    std::array<double, 3> dn_ds{};
    for (int j = 0; j < 3; ++j) dn_ds[j] = dn[j] / jac;
    Eigen::Matrix3d a;
    Eigen::Vector3d k;
    section_kinematics_reference(frame, rel, n, dn_ds, a, k);
    g.force_strain_ref[gp] = a * (dx / jac);
    g.moment_strain_ref[gp] = k;
  }
  // Three-point Gauss for the length (exact for the quadratic map's |x'| to good accuracy).
  const double pts[3] = {-std::sqrt(0.6), 0.0, std::sqrt(0.6)};
  const double wts[3] = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};
  for (int i = 0; i < 3; ++i) {
    const auto dn = shape_quadratic_derivative(pts[i]);
    Eigen::Vector3d dx = Eigen::Vector3d::Zero();
    for (int j = 0; j < 3; ++j) dx += dn[j] * position[j];
    g.length += wts[i] * dx.norm();
  }
  return g;
}

void evaluate_beam_element(const ElementGeometry& geometry, const Section& section,
                           const Vector6d& initial_strain, const ElementState& state,
                           const ElementLoads& loads, bool with_tangent, ElementResult& result) {
  result.force.setZero();
  if (with_tangent) result.tangent.setZero();
  result.strain_energy = 0.0;
  const auto rel = relative_parameters(state.frame);
  std::array<Vec3<H9>, 3> theta;
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) theta[j](i) = H9::variable(3 * j + i, 0.0);
  const Matrix6d& c = section.stiffness;
  const std::array<Vec3<H9>, 3> rel_h = relative_rotations(state.frame, rel, theta);
  const Eigen::Matrix3d l2 = state.frame[1];
  const Eigen::Matrix3d l2t = l2.transpose();

  for (int gp = 0; gp < kGaussPoints; ++gp) {
    const double xi = gauss_point(gp);
    const auto n = shape_quadratic(xi);
    const auto dn = shape_quadratic_derivative(xi);
    const double inv_j = geometry.inverse_jacobian[gp];
    const double wj = geometry.weight_times_jacobian[gp];
    std::array<double, 3> dn_ds{};
    Eigen::Vector3d dx = Eigen::Vector3d::Zero();
    for (int j = 0; j < 3; ++j) {
      dn_ds[j] = dn[j] * inv_j;
      dx += dn_ds[j] * state.position[j];
    }
    // Section frame Lambda = R(theta_2) Lambda_2 R(r): A = Lambda^T = R(r)^T Lambda_2^T R(theta_2)^T.
    const Vec3<H9> r = rel_h[0] * n[0] + rel_h[2] * n[2];
    const Vec3<H9> rp = rel_h[0] * dn_ds[0] + rel_h[2] * dn_ds[2];
    const Mat3<H9> rot = wm_rotation<H9>(r);
    const Vec3<H9> k = wm_tangent_transpose_times<H9>(r, rp);
    const Vec3<H9> e = mul_transpose(rot, mul(l2t, rotate_by_increment(3, dx.cast<H9>(), -1.0)));
    // Spatial vectors A^T v for a material vector v: R(theta_2) Lambda_2 R(r) v.
    auto push_forward = [&](const Eigen::Vector3d& v) { return rotate_by_increment(3, mul(l2, mul(rot, v)), 1.0); };
    std::array<const H9*, 6> eps_h{&e(0), &e(1), &e(2), &k(0), &k(1), &k(2)};
    Vector6d eps;
    for (int i = 0; i < 3; ++i) {
      eps(i) = e(i).v - geometry.force_strain_ref[gp](i);
      eps(3 + i) = k(i).v - geometry.moment_strain_ref[gp](i);
    }
    eps -= initial_strain;
    const Vector6d sigma = c * eps;
    result.strain[gp] = eps;
    result.stress[gp] = sigma;
    result.strain_energy += 0.5 * wj * eps.dot(sigma);
    Eigen::Matrix3d rot_val;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) rot_val(i, j) = rot(i, j).v;
    const Eigen::Matrix3d a_val = rot_val.transpose() * l2t;
    // Strain-displacement matrix B (6 x 18): d eps / d(du_j, dtheta_j).
    Eigen::Matrix<double, 6, 18> b = Eigen::Matrix<double, 6, 18>::Zero();
    for (int j = 0; j < 3; ++j) {
      b.block<3, 3>(0, 6 * j) = dn_ds[j] * a_val;
      for (int r = 0; r < 6; ++r)
        for (int i = 0; i < 3; ++i) b(r, 6 * j + 3 + i) = eps_h[r]->g[3 * j + i];
    }
    result.force.noalias() += wj * b.transpose() * sigma;

    // Distributed loads (consistent nodal forces with the same quadrature).
    const Eigen::Vector3d follower = a_val.transpose() * loads.follower_force_per_length;
    for (int j = 0; j < 3; ++j)
      result.force.segment<3>(6 * j) -= wj * n[j] * (loads.dead_force_per_length + follower);

    if (!with_tangent) continue;
    result.tangent.noalias() += wj * b.transpose() * c * b;
    // Geometric stiffness, rotation-rotation: sum_a sigma_a d2 eps_a / dtheta2.
    Eigen::Matrix<double, 9, 9> g_tt;
    for (int p = 0; p < 9; ++p)
      for (int q = 0; q <= p; ++q) {
        double s = 0.0;
        for (int r = 0; r < 6; ++r) s += sigma(r) * eps_h[r]->hess(p, q);
        g_tt(p, q) = g_tt(q, p) = wj * s;
      }
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) result.tangent.block<3, 3>(6 * i + 3, 6 * j + 3) += g_tt.block<3, 3>(3 * i, 3 * j);
    // Displacement-rotation: d(A^T sigma_e)/dtheta, and the follower load's dependence on rotation.
    const Vec3<H9> at_sigma = push_forward(sigma.head<3>());
    const Vec3<H9> at_follower = push_forward(loads.follower_force_per_length);
    Eigen::Matrix<double, 3, 9> d_at_sigma, d_follower;
    for (int r = 0; r < 3; ++r)
      for (int p = 0; p < 9; ++p) {
        d_at_sigma(r, p) = at_sigma(r).g[p];
        d_follower(r, p) = at_follower(r).g[p];
      }
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        const Eigen::Matrix3d blk = wj * dn_ds[i] * d_at_sigma.block<3, 3>(0, 3 * j);
        result.tangent.block<3, 3>(6 * i, 6 * j + 3) += blk - wj * n[i] * d_follower.block<3, 3>(0, 3 * j);
        result.tangent.block<3, 3>(6 * j + 3, 6 * i) += blk.transpose();
      }
  }
  if (with_tangent) {
    // Spin-conjugate forces change with the multiplicative update as H(dtheta)^-T: -1/2 S(m).
    for (int j = 0; j < 3; ++j)
      result.tangent.block<3, 3>(6 * j + 3, 6 * j + 3) -= 0.5 * skew<double>(Eigen::Vector3d(result.force.segment<3>(6 * j + 3)));
  }
}

}  // namespace tfmb::beam
