// Flexible joint with the seed's finite-deformation measures (flexible_joint.hpp): consistent
// tangent against finite differences, objectivity, k/l swap invariance, the small-motion limits.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

#include "tfmb-beam/flexible_joint.hpp"

using namespace tfmb::beam;

namespace {

Matrix6d seed_example2_stiffness() {
  Matrix6d d = Matrix6d::Zero();
  d.topLeftCorner<3, 3>() << 1000, 100, 100, 100, 1000, 100, 100, 100, 1000;
  d.diagonal().tail<3>() << 1000, 1000, 100;
  return d;
}

FlexibleJointLaw law_for(const std::string& functions, FlexibleMeasure measure = FlexibleMeasure::proposed) {
  FlexibleJointLaw law;
  law.stiffness = seed_example2_stiffness();
  law.measure = measure;
  law.functions = seed_measure_functions(functions);
  // A joint frame that is not the global one, so that frame mix-ups show.
  law.frame = wm_rotation<double>(Eigen::Vector3d(0.3, -0.5, 0.2));
  return law;
}

// A deformed state well in the nonlinear range: relative rotation ~1.3 rad, displacement ~0.4 m.
void deformed_handles(HandleState& k, HandleState& l) {
  k.position = Eigen::Vector3d(1.0, -0.4, 0.3);
  k.rotation = wm_from_axis_angle(Eigen::Vector3d(1, 2, -1).normalized(), 0.9);
  l.position = k.position + Eigen::Vector3d(0.25, -0.2, 0.25);
  l.rotation = wm_compose<double>(k.rotation, wm_from_axis_angle(Eigen::Vector3d(-0.3, 1, 0.6).normalized(), 1.3));
}

// Handles after the solver's update x <- x + du, R <- R(dpsi) R of local variable j by h.
void perturb(HandleState& k, HandleState& l, int j, double h) {
  HandleState& s = j < 6 ? k : l;
  const int i = j % 6;
  if (i < 3) {
    s.position(i) += h;
  } else {
    Eigen::Vector3d d = Eigen::Vector3d::Zero();
    d(i - 3) = h;
    s.rotation = wm_compose<double>(s.rotation, d);
  }
}

double max_abs(const Eigen::MatrixXd& m) { return m.cwiseAbs().maxCoeff(); }

}  // namespace

// The consistent tangent is the derivative of the elastic forces along the solver's update; a
// central difference with h = 1e-5 has truncation error ~h^2 |F'''| ~ 1e-10 relative here.
TEST(FlexibleJoint, TangentMatchesFiniteDifferences) {
  for (const std::string name : {"default", "1d", "2c", "3b", "4d"}) {
    for (FlexibleMeasure measure : {FlexibleMeasure::proposed, FlexibleMeasure::typical}) {
      if (measure == FlexibleMeasure::typical && name != "default") continue;
      const FlexibleJointLaw law = law_for(name, measure);
      HandleState k, l;
      deformed_handles(k, l);
      const FlexibleJointResponse r = evaluate_flexible_joint(law, k, l);
      Eigen::Matrix<double, 12, 12> fd;
      const double h = 1e-5;
      for (int j = 0; j < 12; ++j) {
        HandleState kp = k, lp = l, km = k, lm = l;
        perturb(kp, lp, j, h);
        perturb(km, lm, j, -h);
        fd.col(j) = (evaluate_flexible_joint(law, kp, lp).force - evaluate_flexible_joint(law, km, lm).force) / (2 * h);
      }
      const double rel = max_abs(r.tangent - fd) / max_abs(r.tangent);
      EXPECT_LT(rel, 1e-6) << name << (measure == FlexibleMeasure::typical ? " typical" : " proposed");
      std::cout << "[flexible tangent] " << name << (measure == FlexibleMeasure::typical ? " typical" : " proposed")
                << ": max |K - K_fd| / max |K| = " << rel << "\n";
      // The symmetric Hessian alone would be off by 1/2 S(moment): that part is not negligible here.
      EXPECT_GT(max_abs(r.force.segment<3>(9)), 1.0);
    }
  }
}

// Forces on the two handles balance: the joint is massless and its energy depends on the relative
// motion only (seed eq. 6): the total force vanishes and so does the total moment about the origin.
TEST(FlexibleJoint, ForcesAreInEquilibrium) {
  const FlexibleJointLaw law = law_for("default");
  HandleState k, l;
  deformed_handles(k, l);
  const FlexibleJointResponse r = evaluate_flexible_joint(law, k, l);
  const Eigen::Vector3d f = r.force.segment<3>(0) + r.force.segment<3>(6);
  const Eigen::Vector3d m = r.force.segment<3>(3) + r.force.segment<3>(9) + k.position.cross(r.force.segment<3>(0)) +
                            l.position.cross(r.force.segment<3>(6));
  EXPECT_LT(f.norm(), 1e-10 * r.force.norm());
  EXPECT_LT(m.norm(), 1e-10 * r.force.norm());
}

// Objectivity (Malvern): a rigid motion superposed on a deformed state leaves the energy and the
// measures unchanged, for the proposed and the typical measures alike.
TEST(FlexibleJoint, SuperposedRigidMotionLeavesMeasuresUnchanged) {
  for (FlexibleMeasure measure : {FlexibleMeasure::proposed, FlexibleMeasure::typical}) {
    const FlexibleJointLaw law = law_for("2d", measure);
    HandleState k, l;
    deformed_handles(k, l);
    const FlexibleJointResponse r0 = evaluate_flexible_joint(law, k, l);
    for (double angle : {0.7, 2.5, 3.1}) {
      const Eigen::Vector3d q = wm_from_axis_angle(Eigen::Vector3d(0.2, -1, 0.4).normalized(), angle);
      const Eigen::Matrix3d rq = wm_rotation<double>(q);
      const Eigen::Vector3d t(3.0, -1.0, 2.0);
      HandleState k2 = k, l2 = l;
      k2.position = rq * k.position + t;
      l2.position = rq * l.position + t;
      k2.rotation = wm_compose<double>(k.rotation, q);
      l2.rotation = wm_compose<double>(l.rotation, q);
      const FlexibleJointResponse r = evaluate_flexible_joint(law, k2, l2);
      EXPECT_NEAR(r.energy, r0.energy, 1e-12 * r0.energy);
      EXPECT_LT((r.measures - r0.measures).norm(), 1e-12 * r0.measures.norm());
    }
  }
}

// Swapping handles k and l: the proposed measures change sign (the relative motion is inverted,
// P -> -P), so the energy is the same; the typical stretch is resolved in the other handle's frame
// and the energy changes.
TEST(FlexibleJoint, SwappingHandles) {
  HandleState k, l;
  deformed_handles(k, l);
  for (const std::string& name : seed_measure_function_names()) {
    const FlexibleJointLaw law = law_for(name);
    const FlexibleJointResponse kl = evaluate_flexible_joint(law, k, l);
    const FlexibleJointResponse lk = evaluate_flexible_joint(law, l, k);
    EXPECT_LT((kl.measures + lk.measures).norm(), 1e-12 * kl.measures.norm()) << name;
    EXPECT_NEAR(kl.energy, lk.energy, 1e-12 * kl.energy) << name;
    // Forces on each handle are the same whichever is called k.
    EXPECT_LT((kl.force.head<6>() - lk.force.tail<6>()).norm(), 1e-10 * kl.force.norm()) << name;
  }
  const FlexibleJointLaw typical = law_for("default", FlexibleMeasure::typical);
  const double e_kl = evaluate_flexible_joint(typical, k, l).energy;
  const double e_lk = evaluate_flexible_joint(typical, l, k).energy;
  EXPECT_GT(std::abs(e_kl - e_lk), 1e-3 * e_kl);
}

// q = H(p)^-1 u makes P = (q, p) the eigenvector of the relative motion tensor for the unit
// eigenvalue, R q + u x p = q (README, "Flexible joint"), and sigma = p.q = p p' d with
// p' = dp/dphi = 1 + p^2/16 and d = n.u the intrinsic displacement (seed, after eq. 15).
TEST(FlexibleJoint, DisplacementParametersAreTheEigenvector) {
  const Eigen::Vector3d n = Eigen::Vector3d(1, -2, 0.5).normalized();
  for (double phi : {1e-3, 0.4, 1.5, 3.0}) {
    const Eigen::Vector3d p = wm_from_axis_angle(n, phi);
    const Eigen::Vector3d u(0.3, 0.1, -0.7);
    const Eigen::Vector3d q = wm_tangent_inverse<double>(p) * u;
    EXPECT_LT((wm_rotation<double>(p) * q + u.cross(p) - q).norm(), 1e-14);
    const double pn = p.norm();
    EXPECT_NEAR(p.dot(q), pn * (1 + pn * pn / 16) * n.dot(u), 1e-14);
  }
}

// Small relative motion: all choices, proposed and typical, give E = (u, phi n) to first order.
TEST(FlexibleJoint, SmallMotionLimit) {
  HandleState k, l;
  const double s = 1e-6;
  l.position = s * Eigen::Vector3d(0.3, -0.2, 0.5);
  l.rotation = wm_from_axis_angle(Eigen::Vector3d(1, 1, 0).normalized(), s);
  Vector6d expected;
  expected << s * 0.3, -s * 0.2, s * 0.5, s / std::sqrt(2.0), s / std::sqrt(2.0), 0;
  std::vector<FlexibleJointLaw> laws;
  for (const std::string& name : seed_measure_function_names()) laws.push_back(law_for(name));
  laws.push_back(law_for("default", FlexibleMeasure::typical));
  for (FlexibleJointLaw law : laws) {
    law.frame.setIdentity();
    const Vector6d e = evaluate_flexible_joint(law, k, l).measures;
    EXPECT_LT((e - expected).norm(), 1e-5 * expected.norm()) << law.functions.name;
  }
}

// Choices that break the seed's small-motion limits (eqs. 18, 19) are refused with a message
// naming the violated limit.
TEST(FlexibleJoint, RejectsChoicesViolatingTheLimits) {
  MeasureFunctions f = seed_measure_functions("default");
  EXPECT_NO_THROW(check_measure_functions(f));
  for (const std::string& name : seed_measure_function_names()) EXPECT_NO_THROW(check_measure_functions(seed_measure_functions(name)));
  f.mu = MeasureFunction{{{2.0, 0, 0}, {1.0, 0, 2}}, false};
  try {
    check_measure_functions(f);
    FAIL() << "mu = 2 + p^2 accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("mu -> 1"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("2 + p^2"), std::string::npos) << e.what();
  }
  f = seed_measure_functions("default");
  f.lambda = MeasureFunction{{{0.5, 0, 0}, {1.0, 1, 0}}, false};
  try {
    check_measure_functions(f);
    FAIL() << "lambda = 0.5 + sigma accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("lambda -> 0"), std::string::npos) << e.what();
  }
  f = seed_measure_functions("default");
  f.mu = MeasureFunction{{{1.0, 0, 0}, {1.0, 0, 1}}, false};
  EXPECT_THROW(check_measure_functions(f), std::invalid_argument);  // 1 + |p|: not smooth at p = 0
  EXPECT_THROW(seed_measure_functions("5a"), std::invalid_argument);
}
