// Lower pairs (spherical, prismatic, cylindrical, screw, planar) and the flexible joint in dynamics.
// Lower pairs: in a large-motion dynamic run
// the constrained relative motion stays at zero to solver tolerance, and the free motion matches
// a closed-form rigid-body answer. Rod: 1 m, 1 kg/m, stiff (its elastic deflection under gravity
// is ~1e-4 m or less, which bounds how closely a rigid-body answer can hold).
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

#include "refdata.hpp"
#include "tfmb-beam/assembly.hpp"
#include "tfmb-beam/cases.hpp"
#include "tfmb-beam/dynamic_solver.hpp"
#include "tfmb-beam/flexible_joint.hpp"
#include "tfmb-beam/static_solver.hpp"

using namespace tfmb::beam;

namespace {

constexpr double kG = 9.81;

double output(const std::vector<JointOutput>& outs, const std::string& name) {
  for (const auto& o : outs)
    if (o.name == name) return o.value;
  throw std::runtime_error("no output " + name);
}

/// Rod along `direction` from the origin, joined at node 0 to the ground by `kind` about `axis`.
Model rod_on_ground_joint(JointKind kind, const Eigen::Vector3d& axis, const Eigen::Vector3d& direction,
                          double ei = 1e5) {
  Model m = cases::cantilever(1.0, 4, make_diagonal_section(1e8, 1e8, 1e8, ei, ei, ei, 1.0, 1e-7, 1e-7));
  const Eigen::Vector3d dir = direction.normalized();
  const Eigen::Matrix3d rot = Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitX(), dir).toRotationMatrix();
  for (auto& n : m.nodes) {
    n.position = dir * n.position.x();
    n.frame = rot * n.frame;
  }
  m.joints.clear();
  JointSpec j;
  j.kind = kind;
  j.name = "pair";
  j.node_a = -1;
  j.node_b = 0;
  j.axis = axis;
  m.joints.push_back(j);
  return m;
}

struct PairRun {
  State final;
  double max_violation = 0.0;  // largest constraint violation seen over the run (m or rad)
  std::vector<JointOutput> final_outputs;
};

/// Integrates to `end_time`; `violation(state)` measures the constraint violation geometrically.
PairRun integrate(Model& m, double end_time, double h, const std::function<double(const State&)>& violation,
              const std::vector<Eigen::Vector3d>& v0 = {}, const std::vector<Eigen::Vector3d>& w0 = {}) {
  Assembly asmb(m);
  DynamicOptions opt;
  opt.time_step = h;
  opt.end_time = end_time;
  opt.rho_infinity = 0.8;
  opt.tolerance = 1e-11;
  PairRun run;
  opt.on_step = [&](double, const State& s) { run.max_violation = std::max(run.max_violation, violation(s)); };
  DynamicSolver solver(asmb, opt);
  if (!v0.empty()) solver.set_initial_velocity(v0, w0);
  const DynamicResult r = solver.run(asmb.initial_state());
  EXPECT_TRUE(r.completed);
  run.final = r.state;
  run.final_outputs = asmb.joint_outputs(r.state, 0);
  return run;
}

Eigen::Matrix3d node_rotation(const State& s, int node) { return wm_rotation<double>(s.rotation[node]); }

}  // namespace

// Spherical joint, large 3D motion: the rod starts horizontal with an angular velocity about the
// vertical and falls while it turns; the pivot node stays at the pivot. Free motion: swinging in
// a plane at 10 degrees it has the period of the same rod on a revolute joint (refdata).
TEST(LowerPairs, Spherical) {
  {
    Model m = rod_on_ground_joint(JointKind::spherical, Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitX());
    m.gravity = Eigen::Vector3d(0, -kG, 0);
    const Eigen::Vector3d w(0, 3.0, 0);  // about the vertical: the rod sweeps a cone while falling
    std::vector<Eigen::Vector3d> v0, w0;
    for (const auto& n : m.nodes) {
      v0.push_back(w.cross(n.position));
      w0.push_back(w);
    }
    const PairRun r = integrate(m, 1.0, 2e-3, [](const State& s) { return s.position[0].norm(); }, v0, w0);
    EXPECT_LT(r.max_violation, 1e-10);
    
    std::cout << "[spherical] max |x_pivot| over 1 s: " << r.max_violation << " m; tip at "
              << r.final.position.back().transpose() << "\n";
  }
  const auto table = beam_test::read_table(beam_test::refdata_dir() + "/pendulum_revolute_period.csv");
  double exact = 0.0;
  for (const auto& row : table.rows)
    if (row[table.col("theta0_deg")] == 10.0) exact = row[table.col("T_rod_1m_s")];
  ASSERT_GT(exact, 0.0);
  const double theta0 = 10.0 * M_PI / 180.0;
  Model m = rod_on_ground_joint(JointKind::spherical, Eigen::Vector3d::UnitZ(),
                                Eigen::Vector3d(std::sin(theta0), -std::cos(theta0), 0.0));
  m.gravity = Eigen::Vector3d(0, -kG, 0);
  std::vector<double> crossings;
  double prev_t = 0.0, prev_x = m.nodes.back().position.x();
  Assembly asmb(m);
  DynamicOptions opt;
  opt.time_step = 2e-3;
  opt.end_time = 2.2 * exact;
  opt.on_step = [&](double t, const State& s) {
    const double x = s.position.back().x();
    if (prev_x > 0.0 && x <= 0.0) crossings.push_back(prev_t + (t - prev_t) * prev_x / (prev_x - x));
    prev_t = t;
    prev_x = x;
  };
  DynamicSolver solver(asmb, opt);
  ASSERT_TRUE(solver.run(asmb.initial_state()).completed);
  ASSERT_GE(crossings.size(), 2u);
  const double period = (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
  // h = T/800 as the revolute test: period error ~1e-5; tolerance 1e-3.
  EXPECT_NEAR(period / exact, 1.0, 1e-3);
  std::cout << "[spherical] period " << period << " s, exact " << exact << " s\n";
}

// Prismatic joint on an inclined axis: the rod slides without turning, s = (g.e) t^2 / 2 (a
// constant acceleration, which generalized-alpha integrates exactly); about 3 m of sliding.
TEST(LowerPairs, Prismatic) {
  const Eigen::Vector3d axis = Eigen::Vector3d(1, -1, 0.5).normalized();
  Model m = rod_on_ground_joint(JointKind::prismatic, axis, Eigen::Vector3d(0, 0.6, 0.8));
  m.gravity = Eigen::Vector3d(0, -kG, 0);
  const PairRun r = integrate(m, 1.0, 2e-3, [&](const State& s) {
    const Eigen::Vector3d x = s.position[0];
    return std::max((x - x.dot(axis) * axis).norm(), wm_angle(s.rotation[0]));
  });
  const double exact = 0.5 * m.gravity.dot(axis) * 1.0;
  EXPECT_LT(r.max_violation, 1e-10);
  // The centre of mass slides exactly so; the joint node differs from it by the rod's elastic
  // deformation under the lateral part of gravity (EI = 1e5: ~1e-6 m).
  EXPECT_NEAR(output(r.final_outputs, "sliding"), exact, 1e-6);
  EXPECT_NEAR(r.final.position[0].dot(axis), exact, 1e-6);
  std::cout << "[prismatic] sliding " << output(r.final_outputs, "sliding") << " m, exact " << exact
            << " m; max violation " << r.max_violation << "\n";
}

// Cylindrical joint: the same inclined axis, the rod spinning about it at 5 rad/s and swinging
// under gravity; sliding along the axis is decoupled from the rotation about it.
TEST(LowerPairs, Cylindrical) {
  const Eigen::Vector3d axis = Eigen::Vector3d(1, -1, 0.5).normalized();
  Model m = rod_on_ground_joint(JointKind::cylindrical, axis, axis.cross(Eigen::Vector3d::UnitZ()));
  m.gravity = Eigen::Vector3d(0, -kG, 0);
  const Eigen::Vector3d w = 5.0 * axis;
  std::vector<Eigen::Vector3d> v0, w0;
  for (const auto& n : m.nodes) {
    v0.push_back(w.cross(n.position));
    w0.push_back(w);
  }
  const PairRun r = integrate(m, 1.0, 1e-3, [&](const State& s) {
    const Eigen::Vector3d x = s.position[0];
    const Eigen::Vector3d e3 = node_rotation(s, 0) * axis;  // the rod's copy of the axis
    return std::max((x - x.dot(axis) * axis).norm(), e3.cross(axis).norm());
  }, v0, w0);
  const double exact = 0.5 * m.gravity.dot(axis);
  EXPECT_LT(r.max_violation, 1e-10);
  EXPECT_NEAR(output(r.final_outputs, "sliding"), exact, 1e-6);  // as the prismatic joint
  std::cout << "[cylindrical] sliding " << output(r.final_outputs, "sliding") << " m, exact " << exact
            << " m, turned " << output(r.final_outputs, "relative_rotation") << " rad; max violation " << r.max_violation << "\n";
}

// Screw joint with a vertical axis: the horizontal rod screws down under gravity,
// (M h^2 + I) phi'' = -M g h, I = M L^2/3 (+ rotary inertia), s = h phi. Over 2 s it turns by
// ~2.9 rad. The rod's elastic droop (~1e-5 m) changes I by ~1e-5.
TEST(LowerPairs, Screw) {
  const double lead = 0.05;  // [m/rad]
  Model m = rod_on_ground_joint(JointKind::screw, Eigen::Vector3d::UnitY(), Eigen::Vector3d::UnitX(), 1e6);
  m.joints[0].screw_lead = lead;
  m.gravity = Eigen::Vector3d(0, -kG, 0);
  const double mass = 1.0, inertia = 1.0 / 3.0 + 1e-7;
  const double alpha = -mass * kG * lead / (mass * lead * lead + inertia);
  const double t_end = 2.0;
  const PairRun r = integrate(m, t_end, 2e-3, [&](const State& s) {
    const Eigen::Vector3d x = s.position[0];
    const Eigen::Matrix3d rot = node_rotation(s, 0);
    // On the axis, axis kept, and sliding = lead x rotation angle about y (from the rod's x axis).
    const double angle = std::atan2(-rot(2, 0), rot(0, 0));
    double v = std::max(std::hypot(x.x(), x.z()), (rot * Eigen::Vector3d::UnitY()).cross(Eigen::Vector3d::UnitY()).norm());
    if (std::abs(angle) < 3.0) v = std::max(v, std::abs(x.y() - lead * angle));
    return v;
  });
  const double phi = output(r.final_outputs, "relative_rotation");
  EXPECT_LT(r.max_violation, 1e-10);
  EXPECT_NEAR(phi, 0.5 * alpha * t_end * t_end, 1e-4 * std::abs(0.5 * alpha * t_end * t_end));
  EXPECT_NEAR(output(r.final_outputs, "sliding"), lead * phi, 1e-10);
  std::cout << "[screw] phi " << phi << " rad, exact " << 0.5 * alpha * t_end * t_end << " rad; max violation "
            << r.max_violation << "\n";
}

// Planar joint (plane normal z): a rod spinning at 2 rad/s about its centre of mass falls in the
// plane under the in-plane part of gravity while the out-of-plane part is carried by the joint.
// Rigid planar motion: centre of mass x_c(t) = x_c0 - g t^2/2 y, angle 2 t.
TEST(LowerPairs, Planar) {
  Model m = rod_on_ground_joint(JointKind::planar_pair, Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitX(), 1e6);
  m.gravity = Eigen::Vector3d(0, -kG, -kG);
  const double omega = 2.0;
  const Eigen::Vector3d centre(0.5, 0, 0), w(0, 0, omega);
  std::vector<Eigen::Vector3d> v0, w0;
  for (const auto& n : m.nodes) {
    v0.push_back(w.cross(n.position - centre));
    w0.push_back(w);
  }
  const double t_end = 1.0;
  const PairRun r = integrate(m, t_end, 1e-3, [&](const State& s) {
    const Eigen::Vector3d e3 = node_rotation(s, 0) * Eigen::Vector3d::UnitZ();
    return std::max(std::abs(s.position[0].z()), e3.cross(Eigen::Vector3d::UnitZ()).norm());
  }, v0, w0);
  const Eigen::Vector3d xc = centre + Eigen::Vector3d(0, -0.5 * kG * t_end * t_end, 0);
  const Eigen::Vector3d exact = xc + Eigen::AngleAxisd(omega * t_end, Eigen::Vector3d::UnitZ()) * (-centre);
  EXPECT_LT(r.max_violation, 1e-10);
  // Rigid-body answer to the rod's elastic deformation (~1e-5 m with EI = 1e6) and the scheme's
  // O(h^2) phase error of the spin (~1e-6).
  EXPECT_LT((r.final.position[0] - exact).norm(), 1e-4);
  EXPECT_NEAR(output(r.final_outputs, "relative_rotation"), omega * t_end, 1e-4);
  std::cout << "[planar] handle at " << r.final.position[0].transpose() << ", rigid-body " << exact.transpose()
            << "; max violation " << r.max_violation << "\n";
}

// Reactions: a rod (w = 9.81 N/m) clamped at its tip and held at its start by the pair (axis x)
// is a propped cantilever (spherical: the start is pinned, reaction 3 w L / 8, no moment) or a
// fixed-fixed beam with the axial motion, torsion or sliding released (the others: reaction w L/2,
// moment w L^2/12). The reaction is the force and moment the joint applies to the rod's start.
TEST(LowerPairs, StaticReactions) {
  const double w = kG, length = 1.0;
  for (JointKind kind : {JointKind::spherical, JointKind::cylindrical, JointKind::prismatic, JointKind::screw,
                         JointKind::planar_pair}) {
    Model m = cases::cantilever(length, 8, make_diagonal_section(1e9, 1e9, 1e9, 1e4, 1e4, 1e4, 1.0, 1e-7, 1e-7));
    m.joints.clear();
    JointSpec pair;
    pair.kind = kind;
    pair.name = "pair";
    pair.node_a = -1;
    pair.node_b = 0;
    pair.axis = kind == JointKind::planar_pair ? Eigen::Vector3d::UnitY() : Eigen::Vector3d::UnitX();
    pair.screw_lead = 0.01;
    JointSpec clamp;
    clamp.kind = JointKind::clamp;
    clamp.name = "tip";
    clamp.node_b = static_cast<int>(m.nodes.size()) - 1;
    m.joints = {pair, clamp};
    m.gravity = Eigen::Vector3d(0, -w, 0);
    Assembly asmb(m);
    const StaticResult r = solve_static(asmb, asmb.initial_state());
    ASSERT_TRUE(r.converged);
    const auto outs = asmb.joint_outputs(r.state, 0);
    const bool pinned = kind == JointKind::spherical;
    const double force = pinned ? 3.0 * w * length / 8.0 : w * length / 2.0;
    const double moment = pinned ? 0.0 : w * length * length / 12.0;
    EXPECT_NEAR(output(outs, "reaction_force_y"), force, 1e-4 * force) << static_cast<int>(kind);
    EXPECT_NEAR(output(outs, "reaction_moment_z"), moment, 1e-4 * w * length * length) << static_cast<int>(kind);
    // Where the pair lets the start slide along x no axial force builds up; the spherical joint
    // (and, through the rod's torsion, the screw) hold it, and the sag of ~3e-6 m then carries a
    // small membrane force.
    if (kind != JointKind::spherical && kind != JointKind::screw) {
      EXPECT_NEAR(output(outs, "reaction_force_x"), 0.0, 1e-8);
    }
  }
}

// Flexible joint in dynamics: a rod on a ground bushing (the seed's default measures), set
// spinning and swinging with no gravity, exchanges kinetic and joint strain energy at large
// relative rotation (> 1 rad); with rho_inf = 1 the total energy stays constant to the scheme's
// truncation error.
TEST(FlexibleJointDynamics, EnergyConserved) {
  Model m = rod_on_ground_joint(JointKind::spherical, Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitX());
  auto law = std::make_shared<FlexibleJointLaw>();
  law->stiffness = Matrix6d::Zero();
  law->stiffness.diagonal() << 2e3, 1e3, 1e3, 20.0, 10.0, 5.0;
  m.joints[0].kind = JointKind::flexible;
  m.joints[0].flexible_law = law;
  std::vector<Eigen::Vector3d> v0, w0;
  const Eigen::Vector3d w(0.5, 3.0, 4.0);
  for (const auto& n : m.nodes) {
    v0.push_back(w.cross(n.position));
    w0.push_back(w);
  }
  Assembly asmb(m);
  DynamicOptions opt;
  opt.time_step = 1e-3;
  opt.end_time = 1.5;
  opt.rho_infinity = 1.0;
  double e0 = -1.0, drift = 0.0, max_angle = 0.0;
  DynamicSolver* solver = nullptr;
  opt.on_step = [&](double t, const State& s) {
    const double e = solver->kinetic_energy() + solver->potential_energy(s, t);
    if (e0 < 0.0) e0 = e;
    drift = std::max(drift, std::abs(e - e0));
    max_angle = std::max(max_angle, wm_angle(s.rotation[0]));
  };
  DynamicSolver s(asmb, opt);
  solver = &s;
  s.set_initial_velocity(v0, w0);
  ASSERT_TRUE(s.run(asmb.initial_state()).completed);
  EXPECT_GT(max_angle, 1.0);
  EXPECT_LT(drift, 1e-3 * e0);
  std::cout << "[flexible dynamics] largest rotation " << max_angle << " rad, energy " << e0 << " J, drift " << drift << " J\n";
}
