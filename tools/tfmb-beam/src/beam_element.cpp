#include "tfmb/beam/beam_element.hpp"

#include "tfmb/beam/rotation_wm.hpp"

namespace tfmb::beam {
namespace {

using H9 = Hyper<9>;

/// Section frame transpose A = Lambda(xi)^T and curvature k = H(r)^T r' at one point, as
/// functions of the nodal rotation increments theta_j (FORMULATION.md sec. 2; objective
/// interpolation of relative rotations about the middle node).
template <typename T>
void section_kinematics(const std::array<Eigen::Matrix3d, 3>& frame,
                        const std::array<Eigen::Vector3d, 3>& relative_param,  // WM(L2^T Lj), j = 0..2
                        const std::array<Vec3<T>, 3>& theta, const std::array<double, 3>& n,
                        const std::array<double, 3>& dn_ds, Mat3<T>& a, Vec3<T>& k) {
  const Mat3<T> l2t = frame[1].transpose().cast<T>();
  Vec3<T> r = Vec3<T>::Zero();
  Vec3<T> rp = Vec3<T>::Zero();
  for (int j = 0; j < 3; j += 2) {
    // R(-theta_2) R(theta_j): the spatial relative increment; then pulled back by Lambda_2.
    const Vec3<T> p = wm_compose<T>(theta[j], wm_inverse<T>(theta[1]));
    const Vec3<T> q = l2t * p;
    const Vec3<T> rj = wm_compose<T>(relative_param[j].cast<T>(), q);
    r += rj * n[j];
    rp += rj * dn_ds[j];
  }
  const Mat3<T> rot_t = wm_rotation<T>(r).transpose();
  a = rot_t * l2t * wm_rotation<T>(theta[1]).transpose();
  k = wm_tangent<T>(r).transpose() * rp;
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
  const std::array<Vec3<double>, 3> zero{Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(),
                                         Eigen::Vector3d::Zero()};
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
    section_kinematics<double>(frame, rel, zero, n, dn_ds, a, k);
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
    Mat3<H9> a;
    Vec3<H9> k;
    section_kinematics<H9>(state.frame, rel, theta, n, dn_ds, a, k);
    const Vec3<H9> e = a * dx.cast<H9>();
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

    Eigen::Matrix3d a_val;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) a_val(i, j) = a(i, j).v;
    // Spatial internal force n = Lambda N: force on node j is integral of N_j' n.
    const Eigen::Vector3d n_spatial = a_val.transpose() * sigma.head<3>();
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
    const Vec3<H9> at_sigma = a.transpose() * sigma.head<3>().cast<H9>();
    const Vec3<H9> at_follower = a.transpose() * loads.follower_force_per_length.cast<H9>();
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
    (void)n_spatial;
  }
  if (with_tangent) {
    // Spin-conjugate forces change with the multiplicative update as H(dtheta)^-T: -1/2 S(m).
    for (int j = 0; j < 3; ++j)
      result.tangent.block<3, 3>(6 * j + 3, 6 * j + 3) -= 0.5 * skew<double>(Eigen::Vector3d(result.force.segment<3>(6 * j + 3)));
  }
}

}  // namespace tfmb::beam
