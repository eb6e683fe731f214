#include "tfmb-beam/cases.hpp"

#include <cmath>
#include <stdexcept>

namespace tfmb::beam::cases {

Model cantilever(double length, int n_elements, const Section& section) {
  Model m;
  m.sections.push_back(section);
  add_beam(
      m, n_elements, 0, [&](double s) { return Eigen::Vector3d(length * s, 0.0, 0.0); },
      [](double) { return Eigen::Vector3d::UnitX(); });
  JointSpec clamp;
  clamp.kind = JointKind::clamp;
  clamp.name = "root";
  clamp.node_b = 0;
  m.joints.push_back(clamp);
  return m;
}

Model bend45(int n_elements, double load, double shear_factor, double torsion_constant) {
  Model m;
  const double e = 1e7, g = 5e6;
  m.sections.push_back(make_diagonal_section(e, shear_factor * g, shear_factor * g, g * torsion_constant, e / 12.0,
                                             e / 12.0));
  const double r = 100.0, span = M_PI / 4.0;
  const auto ids = add_beam(
      m, n_elements, 0,
      [&](double s) { return Eigen::Vector3d(r - r * std::cos(span * s), r * std::sin(span * s), 0.0); },
      [&](double s) { return Eigen::Vector3d(std::sin(span * s), std::cos(span * s), 0.0); });
  JointSpec clamp;
  clamp.kind = JointKind::clamp;
  clamp.name = "root";
  clamp.node_b = ids.front();
  m.joints.push_back(clamp);
  m.nodal_loads.push_back({ids.back(), Eigen::Vector3d(0.0, 0.0, load), Eigen::Vector3d::Zero(), false});
  return m;
}

Section seed_table1_section() {
  // NOTES.md, Table 1 of the nozzle seed (both beams): EA, K22 = K33, GJ, EI_lag = EI_flap,
  // mass per length, I2 = I3.
  return make_diagonal_section(5.7962e6, 5.1331e6, 5.1331e6, 1.0179e1, 1.3042e1, 1.3042e1, 2.2195e-1, 1.8497e-2,
                               1.8497e-2);
}

Model seed_hinged_beams(double half_span, int n_elements, double load) {
  Model m;
  m.sections.push_back(seed_table1_section());
  const auto a = add_beam(
      m, n_elements, 0, [&](double s) { return Eigen::Vector3d(half_span * s, 0.0, 0.0); },
      [](double) { return Eigen::Vector3d::UnitX(); });
  const auto b = add_beam(
      m, n_elements, 0, [&](double s) { return Eigen::Vector3d(half_span * (1.0 + s), 0.0, 0.0); },
      [](double) { return Eigen::Vector3d::UnitX(); });
  JointSpec c1;
  c1.kind = JointKind::clamp;
  c1.name = "left";
  c1.node_b = a.front();
  JointSpec c2 = c1;
  c2.name = "right";
  c2.node_b = b.back();
  JointSpec hinge;
  hinge.kind = JointKind::revolute;
  hinge.name = "hinge";
  hinge.node_a = a.back();
  hinge.node_b = b.front();
  hinge.axis = Eigen::Vector3d::UnitZ();
  m.joints = {c1, c2, hinge};
  m.nodal_loads.push_back({a.back(), Eigen::Vector3d(0.0, -load, 0.0), Eigen::Vector3d::Zero(), false});
  return m;
}

Model seed_flexible_joint_example1(FlexibleMeasure measure, bool swap_handles, int elements_per_beam) {
  Model m;
  m.sections.push_back(make_diagonal_section(43.50e6, 4.0e6, 2.81e6, 28.05e3, 23.26e3, 298.7e3));
  const double length = 1.2;
  const auto a = add_beam(
      m, elements_per_beam, 0, [&](double s) { return Eigen::Vector3d(length * s, 0.0, 0.0); },
      [](double) { return Eigen::Vector3d::UnitX(); });
  const auto b = add_beam(
      m, elements_per_beam, 0, [&](double s) { return Eigen::Vector3d(length * (1.0 + s), 0.0, 0.0); },
      [](double) { return Eigen::Vector3d::UnitX(); });
  JointSpec clamp;
  clamp.kind = JointKind::clamp;
  clamp.name = "root";
  clamp.node_b = a.front();
  auto law = std::make_shared<FlexibleJointLaw>();
  law->stiffness.setZero();
  law->stiffness.topLeftCorner<3, 3>() << 2000, 10, 10, 10, 2000, 10, 10, 10, 2000;
  law->stiffness.diagonal().tail<3>().setConstant(1000.0);
  law->measure = measure;
  law->functions = seed_measure_functions("default");
  JointSpec bushing;
  bushing.kind = JointKind::flexible;
  bushing.name = "bushing";
  bushing.node_a = swap_handles ? b.front() : a.back();
  bushing.node_b = swap_handles ? a.back() : b.front();
  bushing.flexible_law = law;
  m.joints = {clamp, bushing};
  m.nodal_loads.push_back({b.back(), Eigen::Vector3d(500.0, 25.0, 200.0), Eigen::Vector3d::Zero(), false});
  return m;
}

Model seed_flexible_joint_example2(const std::string& functions, const Eigen::Vector3d& rotational_stiffness) {
  Model m;
  Node node;
  m.nodes.push_back(node);
  auto law = std::make_shared<FlexibleJointLaw>();
  law->stiffness.setZero();
  law->stiffness.topLeftCorner<3, 3>() << 1000, 100, 100, 100, 1000, 100, 100, 100, 1000;
  law->stiffness.diagonal().tail<3>() = rotational_stiffness;
  law->functions = seed_measure_functions(functions);
  JointSpec bushing;
  bushing.kind = JointKind::flexible;
  bushing.name = "bushing";
  bushing.node_a = -1;
  bushing.node_b = 0;
  bushing.flexible_law = law;
  m.joints = {bushing};
  m.nodal_loads.push_back({0, Eigen::Vector3d(125.0, 250.0, 375.0), Eigen::Vector3d(125.0, 250.0, 375.0), false});
  return m;
}

LeeFrame lee_frame(int elements_per_member, double load) {
  if (elements_per_member <= 0 || elements_per_member % 5 != 0)
    throw std::invalid_argument("lee_frame: elements_per_member must be a positive multiple of 5");
  LeeFrame f;
  Model& m = f.model;
  const double length = 120.0, e = 7.2e6, nu = 0.3, area = 6.0, inertia = 2.0;
  const double g = e / (2.0 * (1.0 + nu)), shear = 5.0 / 6.0 * g * area;
  // Torsion and out-of-plane bending do not enter the planar model; given finite values.
  m.sections.push_back(
      make_diagonal_section(e * area, shear, shear, g * 2.0 * inertia, e * inertia, e * inertia));
  const auto column = add_beam(
      m, elements_per_member, 0, [&](double s) { return Eigen::Vector3d(0.0, length * s, 0.0); },
      [](double) { return Eigen::Vector3d::UnitY(); });
  const auto beam = add_beam(
      m, elements_per_member, 0, [&](double s) { return Eigen::Vector3d(length * s, length, 0.0); },
      [](double) { return Eigen::Vector3d::UnitX(); });
  JointSpec foot;
  foot.kind = JointKind::revolute;
  foot.name = "foot";
  foot.node_a = -1;
  foot.node_b = column.front();
  JointSpec end = foot;
  end.name = "end";
  end.node_b = beam.back();
  JointSpec corner;
  corner.kind = JointKind::rigid;
  corner.name = "corner";
  corner.node_a = column.back();
  corner.node_b = beam.front();
  m.joints = {foot, end, corner};
  m.planar = true;
  add_planar_constraints(m);
  // 24 = 120 / 5 from the corner: node 2 n / 5 of the beam (2 n + 1 nodes over 120).
  f.load_node = beam[static_cast<std::size_t>(2 * elements_per_member / 5)];
  m.nodal_loads.push_back(
      {f.load_node, Eigen::Vector3d(0.0, -load, 0.0), Eigen::Vector3d::Zero(), false});
  return f;
}

}  // namespace tfmb::beam::cases
