// Consistent tangent of the beam element and of the assembled system (with joints) against
// central finite differences of the residual.
#include <gtest/gtest.h>

#include <random>

#include "tfmb-beam/assembly.hpp"
#include "tfmb-beam/beam_element.hpp"
#include "tfmb-beam/rotation_wm.hpp"

using namespace tfmb::beam;

namespace {

Section coupled_section() {
  Section s = make_diagonal_section(1e4, 4e3, 3e3, 50.0, 80.0, 120.0);
  // Off-diagonal couplings (extension-twist, shear-bending) exercise the full 6x6 law.
  s.stiffness(0, 3) = s.stiffness(3, 0) = 30.0;
  s.stiffness(1, 5) = s.stiffness(5, 1) = -20.0;
  return s;
}

Eigen::Matrix3d random_rotation(std::mt19937& gen, double max_angle) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const Eigen::Vector3d axis = Eigen::Vector3d(u(gen), u(gen), u(gen)).normalized();
  return Eigen::AngleAxisd(max_angle * u(gen), axis).toRotationMatrix();
}

}  // namespace

TEST(BeamElement, ReferenceStateIsStressFree) {
  // A curved element (arc) with twisted frames carries no force in its reference configuration.
  std::array<Eigen::Vector3d, 3> x;
  std::array<Eigen::Matrix3d, 3> f;
  for (int j = 0; j < 3; ++j) {
    const double t = 0.2 * j;
    x[j] = Eigen::Vector3d(std::sin(t), 1 - std::cos(t), 0.1 * t);
    f[j] = Eigen::AngleAxisd(t, Eigen::Vector3d::UnitZ()).toRotationMatrix() *
           Eigen::AngleAxisd(0.3 * t, Eigen::Vector3d::UnitX()).toRotationMatrix();
  }
  const ElementGeometry g = make_element_geometry(x, f);
  ElementResult r;
  evaluate_beam_element(g, coupled_section(), Vector6d::Zero(), {x, f}, {}, true, r);
  EXPECT_LT(r.force.norm(), 1e-10);
}

TEST(BeamElement, TangentMatchesFiniteDifferences) {
  std::mt19937 gen(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::array<Eigen::Vector3d, 3> x0;
  std::array<Eigen::Matrix3d, 3> f0;
  for (int j = 0; j < 3; ++j) {
    const double t = 0.25 * j;
    x0[j] = Eigen::Vector3d(std::sin(t), 1 - std::cos(t), 0.0);
    f0[j] = Eigen::AngleAxisd(t, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  }
  const ElementGeometry g = make_element_geometry(x0, f0);
  // A large deformed state: rotations up to ~70 degrees, displacements ~0.1.
  ElementState s;
  const Eigen::Matrix3d rigid = random_rotation(gen, 2.5);
  for (int j = 0; j < 3; ++j) {
    s.position[j] = rigid * x0[j] + 0.1 * Eigen::Vector3d(u(gen), u(gen), u(gen));
    s.frame[j] = random_rotation(gen, 0.6) * rigid * f0[j];
  }
  Vector6d initial;
  initial << 1e-3, 0, 0, 0.01, -0.02, 0.03;
  ElementLoads loads;
  loads.dead_force_per_length = Eigen::Vector3d(1.0, 2.0, -3.0);
  loads.follower_force_per_length = Eigen::Vector3d(0.5, -4.0, 2.0);
  const Section sec = coupled_section();
  ElementResult r;
  evaluate_beam_element(g, sec, initial, s, loads, true, r);
  const double eps = 1e-6;
  Matrix18d fd;
  for (int k = 0; k < 18; ++k) {
    ElementState sp = s, sm = s;
    const int node = k / 6, comp = k % 6;
    if (comp < 3) {
      sp.position[node](comp) += eps;
      sm.position[node](comp) -= eps;
    } else {
      const Eigen::Vector3d d = Eigen::Vector3d::Unit(comp - 3) * eps;
      sp.frame[node] = wm_rotation<double>(d) * s.frame[node];
      sm.frame[node] = wm_rotation<double>(Eigen::Vector3d(-d)) * s.frame[node];
    }
    ElementResult rp, rm;
    evaluate_beam_element(g, sec, initial, sp, loads, false, rp);
    evaluate_beam_element(g, sec, initial, sm, loads, false, rm);
    fd.col(k) = (rp.force - rm.force) / (2 * eps);
  }
  // Central differences: truncation ~eps^2 |K'''| and round-off ~1e-16 |f| / eps, both far below
  // 1e-6 of the tangent's norm.
  EXPECT_LT((fd - r.tangent).norm(), 1e-6 * r.tangent.norm()) << "max abs diff " << (fd - r.tangent).cwiseAbs().maxCoeff();
}

TEST(Assembly, TangentWithJointsMatchesFiniteDifferences) {
  Model m;
  m.sections.push_back(coupled_section());
  auto line = [](double x0, double x1) {
    return std::pair{[=](double s) { return Eigen::Vector3d(x0 + (x1 - x0) * s, 0.0, 0.0); },
                     [](double) { return Eigen::Vector3d::UnitX(); }};
  };
  auto [p1, t1] = line(0.0, 1.0);
  auto [p2, t2] = line(1.0, 2.0);
  const auto a = add_beam(m, 2, 0, p1, t1);
  const auto b = add_beam(m, 2, 0, p2, t2);
  JointSpec root;
  root.kind = JointKind::clamp;
  root.name = "root";
  root.node_b = a.front();
  m.joints.push_back(root);
  JointSpec hinge;
  hinge.kind = JointKind::revolute;
  hinge.name = "hinge";
  hinge.node_a = a.back();
  hinge.node_b = b.front();
  hinge.axis = Eigen::Vector3d(0.0, 0.3, 1.0);
  hinge.spring_stiffness = 7.0;
  m.joints.push_back(hinge);
  JointSpec rigid;
  rigid.kind = JointKind::rigid;
  rigid.name = "rigid";
  rigid.node_a = b[1];
  rigid.node_b = b[3];
  m.joints.push_back(rigid);
  m.nodal_loads.push_back({b.back(), Eigen::Vector3d(1, 2, 3), Eigen::Vector3d(0.1, 0.2, 0.3), true});
  m.nodal_loads.push_back({a[2], Eigen::Vector3d(-1, 2, 0), Eigen::Vector3d(0.3, 0.0, -0.3), false});
  Assembly asmb(m);
  // Perturb every unknown randomly to a state away from equilibrium.
  std::mt19937 gen(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  State s = asmb.initial_state();
  Eigen::VectorXd dx(asmb.size());
  for (int i = 0; i < dx.size(); ++i) dx(i) = 0.3 * u(gen);
  asmb.apply_increment(s, dx);
  Eigen::VectorXd r;
  Triplets k;
  asmb.assemble(s, 0.7, r, &k);
  Eigen::SparseMatrix<double> kt(asmb.size(), asmb.size());
  kt.setFromTriplets(k.begin(), k.end());
  const Eigen::MatrixXd kd(kt);
  const double eps = 1e-6;
  Eigen::MatrixXd fd(asmb.size(), asmb.size());
  for (int i = 0; i < asmb.size(); ++i) {
    State sp = s, sm = s;
    Eigen::VectorXd e = Eigen::VectorXd::Zero(asmb.size());
    e(i) = eps;
    asmb.apply_increment(sp, e);
    asmb.apply_increment(sm, -e);
    Eigen::VectorXd rp, rm;
    asmb.assemble(sp, 0.7, rp, nullptr);
    asmb.assemble(sm, 0.7, rm, nullptr);
    fd.col(i) = (rp - rm) / (2 * eps);
  }
  for (int i = 0; i < kd.rows(); ++i)
    for (int j = 0; j < kd.cols(); ++j)
      if (std::abs(fd(i, j) - kd(i, j)) > 1e-3 * (1 + std::abs(kd(i, j))))
        ADD_FAILURE() << asmb.dof_name(i) << " / " << asmb.dof_name(j) << ": fd " << fd(i, j) << " k " << kd(i, j);
  Eigen::Index ri, ci;
  const double maxdiff = (fd - kd).cwiseAbs().maxCoeff(&ri, &ci);
  EXPECT_LT((fd - kd).norm(), 1e-6 * kd.norm()) << "max abs diff " << maxdiff << " at (" << asmb.dof_name(ri) << ", "
                                                << asmb.dof_name(ci) << ") fd " << fd(ri, ci) << " k " << kd(ri, ci);
}
