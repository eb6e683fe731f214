// Joints in statics: revolute (seed validation), torsional spring, actuator, clearance contact,
// and mechanism detection.
#include <gtest/gtest.h>

#include <cmath>

#include "tfmb-beam/assembly.hpp"
#include "tfmb-beam/cases.hpp"
#include "tfmb-beam/errors.hpp"
#include "tfmb-beam/static_solver.hpp"

using namespace tfmb::beam;

namespace {

double output(const std::vector<JointOutput>& outs, const std::string& name) {
  for (const auto& o : outs)
    if (o.name == name) return o.value;
  throw std::runtime_error("no output " + name);
}

Model hinged_to_ground(double length, int n_el, const Section& sec, JointSpec hinge) {
  Model m = cases::cantilever(length, n_el, sec);
  m.joints.clear();
  hinge.kind = JointKind::revolute;
  hinge.node_a = -1;
  hinge.node_b = 0;
  hinge.axis = Eigen::Vector3d::UnitZ();
  m.joints.push_back(hinge);
  return m;
}

}  // namespace

// Seed validation (NOTES.md Table 1): two beams of 0.5 m joined at the centre by a revolute
// joint, outer ends clamped, P = 0.01 N at the centre. The hinge carries no moment, so by symmetry
// each half is a cantilever with tip force P/2: delta = (P/2) a^3 / (3 EI) + (P/2) a / K22
// (Timoshenko). P is small enough that membrane stiffening (the axially restrained span) stays
// ~1e-4 of the answer, below the 0.5 % tolerance.
TEST(Joints, SeedHingedBeamsStaticDeflection) {
  const double a = 0.5, p = 0.01;
  Model m = cases::seed_hinged_beams(a, 4, p);
  Assembly asmb(m);
  const StaticResult r = solve_static(asmb, asmb.initial_state());
  ASSERT_TRUE(r.converged);
  const Section sec = cases::seed_table1_section();
  const double ei = sec.stiffness(5, 5), k22 = sec.stiffness(1, 1);
  const double exact = 0.5 * p * a * a * a / (3.0 * ei) + 0.5 * p * a / k22;
  const int centre = m.joints[2].node_a;
  const double delta = -r.state.position[centre].y();
  EXPECT_LT(std::abs(delta - exact) / exact, 5e-3);
  std::cout << "[seed static] delta = " << delta << " m, analytic " << exact << " m, relative difference "
            << (delta - exact) / exact << "\n";
  // The two centre nodes move together; the hinge opens symmetrically.
  EXPECT_LT((r.state.position[m.joints[2].node_a] - r.state.position[m.joints[2].node_b]).norm(), 1e-12);
  const double phi = output(asmb.joint_outputs(r.state, 2), "relative_rotation");
  // Relative rotation = 2 x cantilever tip slope (P/2) a^2 / (2 EI).
  const double slope = 0.5 * p * a * a / (2.0 * ei);
  EXPECT_NEAR(std::abs(phi), 2.0 * slope, 5e-3 * 2.0 * slope);
}

// The same hinged beams as a planar model (in-plane joint equations plus planar guides on every
// node) give the same deflection as the 3D model.
TEST(Joints, PlanarModelMatches3D) {
  Model m3 = cases::seed_hinged_beams(0.5, 4, 0.01);
  Model m2 = m3;
  add_planar_constraints(m2);
  Assembly a3(m3), a2(m2);
  const StaticResult r3 = solve_static(a3, a3.initial_state());
  const StaticResult r2 = solve_static(a2, a2.initial_state());
  ASSERT_TRUE(r3.converged && r2.converged);
  const int centre = m3.joints[2].node_a;
  EXPECT_NEAR(r2.state.position[centre].y(), r3.state.position[centre].y(), 1e-12);
  EXPECT_EQ(a2.num_multipliers(), 2 * 3 + 3 + 3 * static_cast<int>(m2.nodes.size()));
}

// Beam on a ground hinge with a torsional spring: tip deflection under a small transverse force is
// the rigid rotation P L / k times L plus the cantilever's bending P L^3 / (3 EI).
TEST(Joints, RevoluteTorsionalSpring) {
  const double length = 2.0, ei = 50.0, k = 400.0, p = 1e-3;
  JointSpec hinge;
  hinge.name = "spring hinge";
  hinge.spring_stiffness = k;
  Model m = hinged_to_ground(length, 4, make_diagonal_section(1e8, 1e8, 1e8, 1e3, ei, ei), hinge);
  const int tip = static_cast<int>(m.nodes.size()) - 1;
  m.nodal_loads.push_back({tip, Eigen::Vector3d(0, -p, 0), Eigen::Vector3d::Zero(), false});
  Assembly asmb(m);
  const StaticResult r = solve_static(asmb, asmb.initial_state());
  ASSERT_TRUE(r.converged);
  const double exact = p * length * length / k + p * length * length * length / (3.0 * ei);
  EXPECT_NEAR(-r.state.position[tip].y(), exact, 1e-4 * exact);
  EXPECT_NEAR(output(asmb.joint_outputs(r.state, 0), "relative_rotation"), -p * length / k, 1e-4 * p * length / k);
  EXPECT_NEAR(output(asmb.joint_outputs(r.state, 0), "spring_moment"), -p * length, 1e-4 * p * length);
}

// Actuator: the hinge angle is prescribed to 60 degrees; a nearly rigid beam turns with it and
// the actuator holds the moment of the dead tip force, P L cos(60 deg).
TEST(Joints, RevolutePrescribedRotation) {
  const double length = 1.0, p = 2.0, angle = M_PI / 3.0;
  JointSpec hinge;
  hinge.name = "actuator";
  hinge.prescribed = true;
  hinge.prescribed_angle = angle;
  Model m = hinged_to_ground(length, 4, make_diagonal_section(1e9, 1e9, 1e9, 1e8, 1e8, 1e8), hinge);
  const int tip = static_cast<int>(m.nodes.size()) - 1;
  m.nodal_loads.push_back({tip, Eigen::Vector3d(0, -p, 0), Eigen::Vector3d::Zero(), false});
  Assembly asmb(m);
  const StaticResult r = solve_static(asmb, asmb.initial_state());
  ASSERT_TRUE(r.converged);
  const auto out = asmb.joint_outputs(r.state, 0);
  EXPECT_NEAR(output(out, "relative_rotation"), angle, 1e-10);
  // Beam compliance: rotation ~ P L^2 / (2 EI) = 1e-8.
  EXPECT_LT((r.state.position[tip] - Eigen::Vector3d(std::cos(angle), std::sin(angle), 0)).norm(), 1e-7);
  EXPECT_NEAR(std::abs(output(out, "actuator_moment")), p * length * std::cos(angle), 1e-6);
}

// Clearance joint: a cantilever whose tip pin sits in a ground hole. While the tip deflection is
// below the radial clearance there is no contact force; once the gap has closed the contact force
// carries the load the beam does not: F_c = P - k_b delta, with k_b the tip stiffness.
TEST(Joints, ClearanceContactForce) {
  const double length = 1.0, ei = 10.0, cr = 1e-3;
  const Section sec = make_diagonal_section(1e9, 1e9, 1e9, 100.0, ei, ei);
  const double kb = 3.0 * ei / (length * length * length);
  for (const double p : {0.5 * kb * cr, 5.0 * kb * cr}) {
    Model m = cases::cantilever(length, 4, sec);
    const int tip = static_cast<int>(m.nodes.size()) - 1;
    JointSpec c;
    c.kind = JointKind::clearance;
    c.name = "pin";
    c.node_a = -1;
    c.node_b = tip;
    c.axis = Eigen::Vector3d::UnitZ();
    c.pin_radius = 0.01;
    c.hole_radius = 0.01 + cr;
    c.contact_stiffness = 1e3 * kb;
    m.joints.push_back(c);
    m.nodal_loads.push_back({tip, Eigen::Vector3d(0, -p, 0), Eigen::Vector3d::Zero(), false});
    Assembly asmb(m);
    const StaticResult r = solve_static(asmb, asmb.initial_state());
    ASSERT_TRUE(r.converged);
    const auto out = asmb.joint_outputs(r.state, 1);
    const double delta = -r.state.position[tip].y();
    const double fc = output(out, "contact_force");
    // Shear and axial compliance are 1e-8 of bending here: 1e-4 tolerance.
    if (p < kb * cr) {
      EXPECT_EQ(fc, 0.0);
      EXPECT_NEAR(delta, p / kb, 1e-4 * p / kb);
      EXPECT_NEAR(output(out, "gap"), cr - delta, 1e-9);
    } else {
      EXPECT_GT(delta, cr);
      EXPECT_NEAR(fc, p - kb * delta, 1e-4 * p);
      EXPECT_NEAR(output(out, "penetration"), fc / c.contact_stiffness, 1e-9);
      std::cout << "[clearance] P = " << p << " N: contact force " << fc << " N, beam carries " << kb * delta
                << " N, gap closed by " << delta - cr << " m\n";
    }
  }
}

// Clearance joint carrying a body that nothing else holds (the config2 situation): a beam hinged
// to the ground at one end, its other end a pin in a ground hole, loaded across at midspan. With
// the gap open the beam turns freely about the hinge (a mechanism at the unloaded start); in
// statics the joint's centring tangent must still let Newton find the contact equilibrium, and
// that equilibrium must be the exact one (no force from the regularisation): by moments about the
// hinge the contact force is P/2 and the pin sits at cr + P / (2 K) from the hole centre.
TEST(Joints, ClearanceJointCarryingAFreeBodyInStatics) {
  const double length = 1.0, cr = 2e-4, k_contact = 1e8, p = 1e3;
  JointSpec hinge;
  hinge.name = "hinge";
  // Stiff in bending (midspan deflection P L^3 / 48 EI = 2 um): the bent beam's end does not
  // move along x enough to tilt the contact normal (which would change |F| by 1/cos).
  Model m = hinged_to_ground(length, 4, make_diagonal_section(1e9, 1e9, 1e9, 1e7, 1e7, 1e7), hinge);
  const int tip = static_cast<int>(m.nodes.size()) - 1, mid = tip / 2;
  JointSpec c;
  c.kind = JointKind::clearance;
  c.name = "pin";
  c.node_a = -1;
  c.node_b = tip;
  c.axis = Eigen::Vector3d::UnitZ();
  c.pin_radius = 0.004;
  c.hole_radius = 0.004 + cr;
  c.contact_stiffness = k_contact;
  m.joints.push_back(c);
  m.nodal_loads.push_back({mid, Eigen::Vector3d(0, -p, 0), Eigen::Vector3d::Zero(), false});
  Assembly asmb(m);
  const StaticResult r = solve_static(asmb, asmb.initial_state());
  ASSERT_TRUE(r.converged);
  const auto out = asmb.joint_outputs(r.state, 1);
  EXPECT_NEAR(output(out, "contact_force"), 0.5 * p, 1e-6 * p);
  EXPECT_NEAR(output(out, "eccentricity"), cr + 0.5 * p / k_contact, 1e-9);
  EXPECT_LT(r.state.position[tip].y(), -cr);  // the gap closed downwards
}

// A beam held only by a frictionless ground hinge and loaded across is a mechanism: the solver
// must say which motion is free instead of returning garbage.
TEST(Joints, MechanismIsReportedWithTheFreeDirection) {
  JointSpec hinge;
  hinge.name = "pin";
  Model m = hinged_to_ground(1.0, 2, make_diagonal_section(1e6, 1e6, 1e6, 1e3, 1e3, 1e3), hinge);
  m.nodal_loads.push_back({4, Eigen::Vector3d(0, -1, 0), Eigen::Vector3d::Zero(), false});
  Assembly asmb(m);
  try {
    (void)solve_static(asmb, asmb.initial_state());
    FAIL() << "expected a ModelError";
  } catch (const ModelError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("mechanism"), std::string::npos) << msg;
    EXPECT_TRUE(msg.find("rotation about z") != std::string::npos || msg.find("joint 'pin'") != std::string::npos)
        << msg;
    std::cout << "[mechanism] " << msg << "\n";
  }
  // No support at all: six rigid-body motions.
  Model free = cases::cantilever(1.0, 2, make_diagonal_section(1e6, 1e6, 1e6, 1e3, 1e3, 1e3));
  free.joints.clear();
  free.nodal_loads.push_back({4, Eigen::Vector3d(0, -1, 0), Eigen::Vector3d::Zero(), false});
  Assembly af(free);
  EXPECT_THROW((void)solve_static(af, af.initial_state()), ModelError);
}

TEST(Joints, BadJointDataIsRejected) {
  Model m = cases::cantilever(1.0, 2, make_diagonal_section(1, 1, 1, 1, 1, 1));
  JointSpec c;
  c.kind = JointKind::clearance;
  c.name = "bad";
  c.node_a = -1;
  c.node_b = 4;
  c.pin_radius = 0.02;
  c.hole_radius = 0.01;
  c.contact_stiffness = 1.0;
  m.joints.push_back(c);
  EXPECT_THROW(Assembly{m}, ModelError);
  m.joints.back().kind = JointKind::revolute;
  m.joints.back().node_a = 0;  // not coincident with node 4
  EXPECT_THROW(Assembly{m}, ModelError);
  m.joints.back().node_b = 99;
  EXPECT_THROW(Assembly{m}, ModelError);
}

// Newton failure: with too few iterations allowed the solver cuts back, then stops with the last
// converged state (load factor < 1) instead of throwing or returning a diverged state.
TEST(Statics, NonConvergenceReturnsLastConvergedState) {
  Model m = cases::bend45(8, 600.0, 1.0, 1.0 / 6.0);
  Assembly asmb(m);
  StaticOptions opt;
  opt.initial_steps = 1;
  opt.max_iterations = 3;
  opt.max_cutbacks = 3;
  const StaticResult r = solve_static(asmb, asmb.initial_state(), opt);
  EXPECT_FALSE(r.converged);
  EXPECT_LT(r.load_factor, 1.0);
  EXPECT_EQ(r.cutbacks, 4);
  for (const auto& x : r.state.position) EXPECT_TRUE(x.allFinite());
}
