// Unit tests of the Wiener-Milenkovic utilities against quaternion / Rodrigues formulas and
// finite differences (FORMULATION.md sec. 1 and 5.1).
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <random>

#include "tfmb-beam/rotation_wm.hpp"

using namespace tfmb::beam;

namespace {

Eigen::Matrix3d rodrigues(const Eigen::Vector3d& axis, double angle) {
  return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
}

std::vector<std::pair<Eigen::Vector3d, double>> samples() {
  std::mt19937 gen(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<std::pair<Eigen::Vector3d, double>> s;
  for (int i = 0; i < 40; ++i) s.push_back({Eigen::Vector3d(u(gen), u(gen), u(gen)).normalized(), 3.1 * u(gen)});
  s.push_back({Eigen::Vector3d::UnitZ(), M_PI - 1e-9});
  return s;
}

// Machine precision for O(1) matrices, times a small factor for the ~20 operations involved.
constexpr double kTight = 1e-13;

}  // namespace

TEST(RotationWM, MatchesRodrigues) {
  for (const auto& [axis, angle] : samples()) {
    const Eigen::Vector3d c = 4.0 * std::tan(angle / 4.0) * axis;
    EXPECT_LT((wm_rotation<double>(c) - rodrigues(axis, angle)).norm(), kTight);
  }
}

TEST(RotationWM, OrthogonalAndProperForLargeParameters) {
  const Eigen::Vector3d c(3.0, -7.0, 12.0);  // |c| > 4: a rotation past 180 degrees
  const Eigen::Matrix3d r = wm_rotation<double>(c);
  EXPECT_LT((r.transpose() * r - Eigen::Matrix3d::Identity()).norm(), kTight);
  EXPECT_NEAR(r.determinant(), 1.0, kTight);
  // The shadow parameters describe the same rotation.
  const Eigen::Vector3d cs = wm_rescale(c);
  EXPECT_LE(cs.norm(), 4.0);
  EXPECT_LT((wm_rotation<double>(cs) - r).norm(), kTight);
}

TEST(RotationWM, FromRotationRoundTrip) {
  for (const auto& [axis, angle] : samples()) {
    const Eigen::Matrix3d r = rodrigues(axis, angle);
    const Eigen::Vector3d c = wm_from_rotation(r);
    EXPECT_LE(c.norm(), 4.0 + 1e-12);
    EXPECT_LT((wm_rotation<double>(c) - r).norm(), 1e-12);
    // Stereographic projection of the quaternion (FORMULATION.md sec. 1).
    Eigen::Quaterniond q(r);
    if (q.w() < 0) q.coeffs() *= -1;
    EXPECT_LT((c - 4.0 * q.vec() / (1.0 + q.w())).norm(), 1e-12);
  }
}

TEST(RotationWM, CompositionMatchesProduct) {
  const auto s = samples();
  for (size_t i = 0; i + 1 < s.size(); ++i) {
    const Eigen::Vector3d a = 4.0 * std::tan(s[i].second / 4.0) * s[i].first;
    const Eigen::Vector3d b = 4.0 * std::tan(s[i + 1].second / 4.0) * s[i + 1].first;
    const Eigen::Vector3d c = wm_compose<double>(a, b);
    EXPECT_LE(c.norm(), 4.0 + 1e-12);
    EXPECT_LT((wm_rotation<double>(c) - wm_rotation<double>(b) * wm_rotation<double>(a)).norm(), 1e-12);
  }
}

TEST(RotationWM, RepeatedCompositionPast360Degrees) {
  // 400 increments of 1.8 degrees = two full turns: the composed parameters stay bounded and
  // the accumulated rotation is exact.
  const Eigen::Vector3d axis = Eigen::Vector3d(1, 2, 2).normalized();
  const double dphi = 4.0 * M_PI / 400.0;
  const Eigen::Vector3d dc = 4.0 * std::tan(dphi / 4.0) * axis;
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (int i = 0; i < 430; ++i) {
    c = wm_compose<double>(c, dc);
    ASSERT_LE(c.norm(), 4.0 + 1e-12);
  }
  EXPECT_LT((wm_rotation<double>(c) - rodrigues(axis, 430 * dphi)).norm(), 1e-11);
}

TEST(RotationWM, TangentInverseAndTransposeIdentity) {
  for (const auto& [axis, angle] : samples()) {
    const Eigen::Vector3d c = 4.0 * std::tan(angle / 4.0) * axis;
    const Eigen::Matrix3d h = wm_tangent<double>(c);
    EXPECT_LT((h * wm_tangent_inverse<double>(c) - Eigen::Matrix3d::Identity()).norm(), 1e-12);
    const Eigen::Vector3d v(0.3, -0.7, 1.1);
    EXPECT_LT((wm_tangent_transpose_times<double>(c, v) - h.transpose() * v).norm(), 1e-12);
    EXPECT_LT((wm_rotation<double>(c).transpose() * h - h.transpose()).norm(), 1e-12);
  }
}

TEST(RotationWM, TangentMatchesFiniteDifferenceOfRotation) {
  // S(H dc) = dR R^T: central differences, step 1e-6 -> truncation ~1e-12, round-off ~1e-10.
  const double eps = 1e-6;
  for (const auto& [axis, angle] : samples()) {
    const Eigen::Vector3d c = 4.0 * std::tan(angle / 4.0) * axis;
    const Eigen::Matrix3d h = wm_tangent<double>(c);
    const Eigen::Matrix3d rt = wm_rotation<double>(c).transpose();
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d d = Eigen::Vector3d::Unit(k) * eps;
      const Eigen::Matrix3d dr = (wm_rotation<double>(Eigen::Vector3d(c + d)) - wm_rotation<double>(Eigen::Vector3d(c - d))) / (2 * eps);
      EXPECT_LT((axial(dr * rt) - h.col(k)).norm(), 1e-8);
    }
  }
}

TEST(RotationWM, DerivativeOfTangentTimesVector) {
  const double eps = 1e-6;
  const Eigen::Vector3d a(0.3, -1.2, 0.7);
  for (const auto& [axis, angle] : samples()) {
    const Eigen::Vector3d c = 4.0 * std::tan(angle / 4.0) * axis;
    const Eigen::Matrix3d d = wm_tangent_times_vector_derivative(c, a);
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d e = Eigen::Vector3d::Unit(k) * eps;
      const Eigen::Vector3d fd = (wm_tangent<double>(Eigen::Vector3d(c + e)) * a - wm_tangent<double>(Eigen::Vector3d(c - e)) * a) / (2 * eps);
      EXPECT_LT((fd - d.col(k)).norm(), 1e-8);
    }
  }
}

TEST(RotationWM, HyperDualDerivativesOfRotation) {
  // Hyper<3> gives exact first and second derivatives of R(c); compare with central differences.
  using H = Hyper<3>;
  const Eigen::Vector3d c0(0.4, -0.9, 1.3);
  Vec3<H> c;
  for (int i = 0; i < 3; ++i) c(i) = H::variable(i, c0(i));
  const Mat3<H> r = wm_rotation<H>(c);
  const double eps = 1e-5;
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d e = Eigen::Vector3d::Unit(k) * eps;
    const Eigen::Matrix3d rp = wm_rotation<double>(Eigen::Vector3d(c0 + e));
    const Eigen::Matrix3d rm = wm_rotation<double>(Eigen::Vector3d(c0 - e));
    const Eigen::Matrix3d r0 = wm_rotation<double>(c0);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        EXPECT_NEAR(r(i, j).g[k], (rp(i, j) - rm(i, j)) / (2 * eps), 1e-9);
        EXPECT_NEAR(r(i, j).hess(k, k), (rp(i, j) - 2 * r0(i, j) + rm(i, j)) / (eps * eps), 1e-5);
      }
  }
}
