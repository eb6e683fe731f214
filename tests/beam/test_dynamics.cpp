// Dynamics and modal verification: cantilever frequencies, pendulum period on a revolute joint,
// energy behaviour of generalized-alpha, the seed's hinged beams under a suddenly applied load.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>

#include "refdata.hpp"
#include "tfmb-beam/assembly.hpp"
#include "tfmb-beam/cases.hpp"
#include "tfmb-beam/dynamic_solver.hpp"
#include "tfmb-beam/modal.hpp"
#include "tfmb-beam/static_solver.hpp"

using namespace tfmb::beam;

// Clamped-free Euler-Bernoulli frequencies omega_n = (beta_n L)^2 sqrt(EI / (m L^4)). Shear and
// axial stiffness 1e6 EI/L^2 and rotary inertia 1e-8 m L^2 make the Reissner beam's deviation
// ~1e-4 for mode 5; the mesh (20 quadratic elements) adds less.
TEST(Modal, CantileverFrequencies) {
  const auto table = beam_test::read_table(beam_test::refdata_dir() + "/cantilever_frequencies_euler_bernoulli.csv");
  const double ei = 1.0, m = 1.0, length = 1.0;
  Model model = cases::cantilever(length, 20, make_diagonal_section(1e6, 1e6, 1e6, 1e6, ei, ei, m, 1e-8, 1e-8));
  Assembly asmb(model);
  const ModalResult r = modal_analysis(asmb, asmb.initial_state(), 12);
  // Bending in the two planes gives pairs of equal frequencies (EI2 = EI3): take every other one.
  for (const auto& row : table.rows) {
    const int mode = static_cast<int>(row[table.col("mode")]);
    const double exact = row[table.col("betaL_squared")] * std::sqrt(ei / (m * std::pow(length, 4))) / (2 * M_PI);
    const double f1 = r.frequencies_hz(2 * (mode - 1)), f2 = r.frequencies_hz(2 * (mode - 1) + 1);
    EXPECT_NEAR(f1 / exact, 1.0, 1e-3) << "mode " << mode;
    EXPECT_NEAR(f2 / exact, 1.0, 1e-3) << "mode " << mode;
    std::cout << "[modal] mode " << mode << ": " << f1 << " Hz, Euler-Bernoulli " << exact << " Hz, ratio " << f1 / exact
              << "\n";
  }
}

namespace {

// Uniform rod of length 1 m, mass 1 kg/m, pivoted at one end on a ground revolute joint (axis z),
// released from rest at theta0 from the downward vertical under g = 9.81 m/s^2. The rod is stiff
// (EI = 1e4) so its elastic deformation changes the period by < 1e-5.
struct PendulumRun {
  double period = 0.0;
  double energy_drift = 0.0;     // max |E(t) - E(0)| / (m g L)
  double energy_increase = 0.0;  // max (E(t) - E(0)) / (m g L)
};

PendulumRun run_pendulum(double theta0, double rho, double h, double end_time) {
  const double g = 9.81;
  Model m = cases::cantilever(1.0, 4, make_diagonal_section(1e7, 1e7, 1e7, 1e4, 1e4, 1e4, 1.0, 1e-7, 1e-7));
  // Rotate the rod to theta0 from the downward vertical: direction (sin, -cos).
  const Eigen::Vector3d dir(std::sin(theta0), -std::cos(theta0), 0.0);
  const Eigen::Matrix3d rot = Eigen::AngleAxisd(theta0 - M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  for (auto& n : m.nodes) {
    n.position = dir * n.position.x();
    n.frame = rot * n.frame;
  }
  m.joints.clear();
  JointSpec pin;
  pin.kind = JointKind::revolute;
  pin.name = "pivot";
  pin.node_a = -1;
  pin.node_b = 0;
  m.joints.push_back(pin);
  m.gravity = Eigen::Vector3d(0, -g, 0);
  Assembly asmb(m);
  DynamicOptions opt;
  opt.time_step = h;
  opt.end_time = end_time;
  opt.rho_infinity = rho;
  PendulumRun out;
  std::vector<double> crossings;
  const int tip = static_cast<int>(m.nodes.size()) - 1;
  double prev_t = 0.0, prev_x = m.nodes.back().position.x();
  DynamicSolver* solver_ptr = nullptr;
  double e0 = 0.0;
  opt.on_step = [&](double t, const State& s) {
    const double x = s.position[tip].x();
    // Crossings of the vertical (x = 0) moving in -x: one per period.
    if (prev_x > 0.0 && x <= 0.0) crossings.push_back(prev_t + (t - prev_t) * prev_x / (prev_x - x));
    prev_t = t;
    prev_x = x;
    const double e = solver_ptr->kinetic_energy() + solver_ptr->potential_energy(s, t);
    out.energy_drift = std::max(out.energy_drift, std::abs(e - e0) / g);
    out.energy_increase = std::max(out.energy_increase, (e - e0) / g);
  };
  DynamicSolver solver(asmb, opt);
  solver_ptr = &solver;
  e0 = solver.potential_energy(asmb.initial_state(), 0.0);
  const DynamicResult r = solver.run(asmb.initial_state());
  EXPECT_TRUE(r.completed);
  if (crossings.size() >= 2) out.period = (crossings.back() - crossings.front()) / (crossings.size() - 1);
  return out;
}

}  // namespace

// Period against the exact large-amplitude period (refdata pendulum_revolute_period.csv).
TEST(Dynamics, PendulumPeriodOnRevoluteJoint) {
  const auto table = beam_test::read_table(beam_test::refdata_dir() + "/pendulum_revolute_period.csv");
  for (const double theta_deg : {10.0, 90.0}) {
    double exact = 0.0;
    for (const auto& row : table.rows)
      if (row[table.col("theta0_deg")] == theta_deg) exact = row[table.col("T_rod_1m_s")];
    ASSERT_GT(exact, 0.0);
    const PendulumRun p = run_pendulum(theta_deg * M_PI / 180.0, 0.8, 2e-3, 2.2 * exact);
    // Second-order scheme with h = T/800: period error ~ (omega h)^2 / 12 ~ 5e-6; tolerance 1e-3.
    EXPECT_NEAR(p.period / exact, 1.0, 1e-3) << "theta0 " << theta_deg;
    std::cout << "[pendulum] theta0 " << theta_deg << " deg: period " << p.period << " s, exact " << exact
              << " s, ratio " << p.period / exact << ", energy drift " << p.energy_drift << " (x m g L)\n";
  }
}

// Energy: with rho_inf = 1 generalized-alpha has no numerical dissipation, so the total energy of
// the undamped pendulum stays constant up to the (second-order) truncation error; with
// rho_inf = 0.6 it may only decrease.
TEST(Dynamics, EnergyConservedToTheSchemesDissipation) {
  const PendulumRun undamped = run_pendulum(M_PI / 3.0, 1.0, 2e-3, 2.0);
  EXPECT_LT(undamped.energy_drift, 1e-3);
  const PendulumRun damped = run_pendulum(M_PI / 3.0, 0.6, 2e-3, 2.0);
  EXPECT_LT(damped.energy_increase, 1e-6);
  std::cout << "[energy] rho_inf 1: max |dE|/(m g L) = " << undamped.energy_drift
            << "; rho_inf 0.6: max increase " << damped.energy_increase << ", max |dE| " << damped.energy_drift << "\n";
}

// Seed validation, dynamic part: the centre load of the hinged beams applied suddenly at t = 0
// and held for one second. An undamped linear structure under a step load oscillates between 0
// and twice the static deflection about the static value; rho_inf = 0.9 removes only the highest
// (mesh) frequencies.
TEST(Dynamics, SeedHingedBeamsStepLoad) {
  const double a = 0.5, p = 0.01;
  Model m = cases::seed_hinged_beams(a, 4, p);
  const int centre = m.joints[2].node_a;
  Assembly asmb(m);
  const StaticResult st = solve_static(asmb, asmb.initial_state());
  ASSERT_TRUE(st.converged);
  const double delta_static = -st.state.position[centre].y();
  DynamicOptions opt;
  opt.time_step = 5e-4;
  opt.end_time = 1.0;
  opt.rho_infinity = 0.9;
  double peak = 0.0, sum = 0.0;
  int n = 0;
  opt.on_step = [&](double, const State& s) {
    const double d = -s.position[centre].y();
    peak = std::max(peak, d);
    sum += d;
    ++n;
  };
  DynamicSolver solver(asmb, opt);
  const DynamicResult r = solver.run(asmb.initial_state());
  ASSERT_TRUE(r.completed);
  const double mean = sum / n;
  EXPECT_NEAR(peak / delta_static, 2.0, 0.02);
  EXPECT_NEAR(mean / delta_static, 1.0, 0.02);
  std::cout << "[seed dynamic] static " << delta_static << " m, peak " << peak << " m (x" << peak / delta_static
            << "), mean over 1 s " << mean << " m, " << r.steps << " steps, " << r.iterations << " iterations\n";
}

// Revolute joint with torsional spring and damper: a stiff rod (I_O = m L^3 / 3) on the hinge,
// kicked by a short tip force, then free: I phi'' + c phi' + k phi = 0, so successive maxima of
// phi decay by the logarithmic decrement 2 pi zeta / sqrt(1 - zeta^2), zeta = c / (2 sqrt(k I)),
// and the damped period is 2 pi / (omega_n sqrt(1 - zeta^2)).
TEST(Dynamics, RevoluteSpringDamperFreeDecay) {
  const double k = 10.0, c = 0.2, inertia = 1.0 / 3.0;
  Model m = cases::cantilever(1.0, 4, make_diagonal_section(1e7, 1e7, 1e7, 1e4, 1e4, 1e4, 1.0, 1e-7, 1e-7));
  m.joints.clear();
  JointSpec hinge;
  hinge.kind = JointKind::revolute;
  hinge.name = "sprung hinge";
  hinge.node_a = -1;
  hinge.node_b = 0;
  hinge.spring_stiffness = k;
  hinge.damping = c;
  m.joints.push_back(hinge);
  const int tip = static_cast<int>(m.nodes.size()) - 1;
  m.nodal_loads.push_back({tip, Eigen::Vector3d(0, 1.0, 0), Eigen::Vector3d::Zero(), false});
  Assembly asmb(m);
  DynamicOptions opt;
  opt.time_step = 2e-3;
  opt.end_time = 4.8;
  opt.rho_infinity = 0.9;
  opt.load_function = [](double t) { return t <= 0.05 ? 1.0 : 0.0; };
  // Up-crossings of phi = 0 give the period; the maximum between two up-crossings gives the
  // amplitude of that cycle (robust against the rod's small elastic wiggles).
  std::vector<double> t_up, phi_max;
  double prev_phi = 0.0, prev_t = 0.0, cycle_max = 0.0;
  opt.on_step = [&](double t, const State& s) {
    const double phi = s.joint_dofs(0);
    if (t > 0.1 && prev_phi < 0.0 && phi >= 0.0) {
      t_up.push_back(prev_t + (t - prev_t) * (-prev_phi) / (phi - prev_phi));
      if (t_up.size() > 1) phi_max.push_back(cycle_max);
      cycle_max = 0.0;
    }
    cycle_max = std::max(cycle_max, phi);
    prev_phi = phi;
    prev_t = t;
  };
  DynamicSolver solver(asmb, opt);
  const DynamicResult r = solver.run(asmb.initial_state());
  ASSERT_TRUE(r.completed);
  ASSERT_GE(phi_max.size(), 3u);
  const double zeta = c / (2.0 * std::sqrt(k * inertia));
  const double decrement = std::log(phi_max[0] / phi_max[2]) / 2.0;
  const double period = (t_up[2] - t_up[0]) / 2.0;
  const double omega_n = std::sqrt(k / inertia);
  // Maxima sampled on a 2 ms grid (phase error ~(omega h)^2/8 ~ 1e-5) and the rod's elastic
  // wiggles (~1e-4 of the amplitude): 1 % on the decrement, 0.2 % on the period.
  EXPECT_NEAR(decrement / (2 * M_PI * zeta / std::sqrt(1 - zeta * zeta)), 1.0, 0.01);
  EXPECT_NEAR(period / (2 * M_PI / (omega_n * std::sqrt(1 - zeta * zeta))), 1.0, 0.002);
  std::cout << "[spring-damper] decrement " << decrement << " (exact " << 2 * M_PI * zeta / std::sqrt(1 - zeta * zeta)
            << "), period " << period << " s (exact " << 2 * M_PI / (omega_n * std::sqrt(1 - zeta * zeta)) << " s)\n";
}

namespace {

// Rod of 1 m, 1 kg/m, hanging at 60 degrees from a clearance joint (pin on the rod end, hole
// in the ground) under gravity; returns the largest increase and the final change of the total
// energy (kinetic + strain + gravity + contact penalty) over one second, divided by m g L.
std::pair<double, double> clearance_pendulum_energy(double mu) {
  const double g = 9.81, theta0 = M_PI / 3.0;
  Model m = cases::cantilever(1.0, 4, make_diagonal_section(1e7, 1e7, 1e7, 1e4, 1e4, 1e4, 1.0, 1e-7, 1e-7));
  const Eigen::Vector3d dir(std::sin(theta0), -std::cos(theta0), 0.0);
  const Eigen::Matrix3d rot = Eigen::AngleAxisd(theta0 - M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  for (auto& n : m.nodes) {
    n.position = dir * n.position.x();
    n.frame = rot * n.frame;
  }
  m.joints.clear();
  JointSpec pin;
  pin.kind = JointKind::clearance;
  pin.name = "pin";
  pin.node_a = -1;
  pin.node_b = 0;
  pin.pin_radius = 0.010;
  pin.hole_radius = 0.0101;
  pin.contact_stiffness = 1e5;
  pin.friction_coefficient = mu;
  pin.friction_regularisation_speed = 1e-2;  // 1e-3 also runs, with step cut-backs, ~5x slower
  m.joints.push_back(pin);
  m.gravity = Eigen::Vector3d(0, -g, 0);
  Assembly asmb(m);
  DynamicOptions opt;
  opt.time_step = 1e-3;
  opt.end_time = 1.0;
  opt.rho_infinity = 1.0;
  DynamicSolver* sp = nullptr;
  double e0 = 0.0, increase = 0.0, last = 0.0;
  auto energy = [&](const State& s, double t) {
    double e = sp->kinetic_energy() + sp->potential_energy(s, t);
    for (const auto& o : asmb.joint_outputs(s, 0))
      if (o.name == "penetration") e += 0.5 * pin.contact_stiffness * o.value * o.value;
    return e;
  };
  opt.on_step = [&](double t, const State& s) {
    last = energy(s, t) - e0;
    increase = std::max(increase, last);
  };
  DynamicSolver solver(asmb, opt);
  sp = &solver;
  e0 = energy(asmb.initial_state(), 0.0);
  const DynamicResult r = solver.run(asmb.initial_state());
  EXPECT_TRUE(r.completed) << "mu " << mu << " stopped at t = " << r.time;
  return {increase / g, last / g};
}

}  // namespace

// Clearance joint in dynamics: the penalty contact is conservative, so without friction the
// energy is kept to the integrator's accuracy (rho_inf = 1); regularised Coulomb friction can
// only remove energy.
TEST(Dynamics, ClearanceJointEnergyWithAndWithoutFriction) {
  const auto [inc0, end0] = clearance_pendulum_energy(0.0);
  const auto [inc1, end1] = clearance_pendulum_energy(0.3);
  std::cout << "[clearance dynamics] mu 0: max increase " << inc0 << ", final change " << end0
            << " (x m g L); mu 0.3: max increase " << inc1 << ", final change " << end1 << "\n";
  EXPECT_LT(std::abs(end0), 1e-3);
  EXPECT_LT(inc1, 1e-3);
  EXPECT_LT(end1, end0 - 1e-3);
}
