#include "tfmb-beam/flexible_joint_seed.hpp"

#include <algorithm>

#include "tfmb-beam/assembly.hpp"
#include "tfmb-beam/cases.hpp"
#include "tfmb-beam/static_solver.hpp"

namespace tfmb::beam::seed {
namespace {

// Tight Newton tolerances: the swap comparison resolves differences down to ~1e-12.
StaticOptions tight_options() {
  StaticOptions o;
  o.tolerance = 1e-13;
  o.increment_tolerance = 1e-12;
  o.max_iterations = 40;
  return o;
}

std::vector<double> load_factors(const std::vector<double>& a_levels) {
  std::vector<double> f;
  for (double a : a_levels) f.push_back(a / 9.0);
  return f;
}

Vector6d joint_measures(const Assembly& assembly, const State& state, int joint) {
  Vector6d e;
  const char* names[] = {"stretch_1", "stretch_2", "stretch_3", "wryness_1", "wryness_2", "wryness_3"};
  const auto outs = assembly.joint_outputs(state, joint);
  for (int i = 0; i < 6; ++i)
    for (const auto& o : outs)
      if (o.name == names[i]) e(i) = o.value;
  return e;
}

}  // namespace

Example1Result run_example1(FlexibleMeasure measure, const std::vector<double>& a_levels, int elements_per_beam) {
  Example1Result r;
  const Model m_kl = cases::seed_flexible_joint_example1(measure, false, elements_per_beam);
  const Model m_lk = cases::seed_flexible_joint_example1(measure, true, elements_per_beam);
  const Assembly a_kl(m_kl), a_lk(m_lk);
  const auto s_kl = solve_at_load_factors(a_kl, a_kl.initial_state(), load_factors(a_levels), tight_options());
  const auto s_lk = solve_at_load_factors(a_lk, a_lk.initial_state(), load_factors(a_levels), tight_options());
  const size_t n = std::min(s_kl.size(), s_lk.size());
  const int tip = static_cast<int>(m_kl.nodes.size()) - 1;
  double max_disp = 0.0, max_angle = 0.0, max_e = 0.0, dx = 0.0, dr = 0.0, de = 0.0;
  for (size_t i = 0; i < n; ++i) {
    r.a.push_back(a_levels[i]);
    JointPoint p_kl, p_lk;
    p_kl.tip_displacement = s_kl[i].position[tip] - m_kl.nodes[tip].position;
    p_lk.tip_displacement = s_lk[i].position[tip] - m_lk.nodes[tip].position;
    p_kl.measures = joint_measures(a_kl, s_kl[i], 1);
    p_lk.measures = joint_measures(a_lk, s_lk[i], 1);
    for (size_t node = 0; node < m_kl.nodes.size(); ++node) {
      max_disp = std::max(max_disp, (s_kl[i].position[node] - m_kl.nodes[node].position).norm());
      max_angle = std::max(max_angle, wm_angle(s_kl[i].rotation[node]));
      dx = std::max(dx, (s_kl[i].position[node] - s_lk[i].position[node]).norm());
      dr = std::max(dr, (wm_rotation<double>(s_kl[i].rotation[node]) - wm_rotation<double>(s_lk[i].rotation[node])).norm());
    }
    max_e = std::max(max_e, p_kl.measures.norm());
    de = std::max(de, (p_kl.measures + p_lk.measures).norm());
    r.kl.push_back(p_kl);
    r.lk.push_back(p_lk);
  }
  r.max_position_difference = dx / std::max(max_disp, 1e-300);
  r.max_rotation_difference = dr / std::max(max_angle, 1e-300);
  r.max_measure_difference = de / std::max(max_e, 1e-300);
  return r;
}

Example2Result run_example2(const std::string& functions, const std::vector<double>& a_levels,
                            const Eigen::Vector3d& rotational_stiffness) {
  Example2Result r;
  const Model m = cases::seed_flexible_joint_example2(functions, rotational_stiffness);
  const Assembly asmb(m);
  const auto states = solve_at_load_factors(asmb, asmb.initial_state(), load_factors(a_levels), tight_options());
  for (size_t i = 0; i < states.size(); ++i) {
    r.a.push_back(a_levels[i]);
    r.measures.push_back(joint_measures(asmb, states[i], 0));
  }
  return r;
}

double example2_spread(double a, const Eigen::Vector3d& rotational_stiffness) {
  Vector6d reference = Vector6d::Zero();
  double spread = 0.0;
  for (const std::string& name : seed_measure_function_names()) {
    if (name == "default") continue;
    const Example2Result r = run_example2(name, {a}, rotational_stiffness);
    if (r.measures.empty()) return 1e300;
    if (name == "1a") reference = r.measures[0];
    spread = std::max(spread, (r.measures[0] - reference).norm() / reference.norm());
  }
  return spread;
}

}  // namespace tfmb::beam::seed
