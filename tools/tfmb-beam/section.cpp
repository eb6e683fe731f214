#include <string>

#include "tfmb-beam/model.hpp"

namespace tfmb::beam {

Section make_diagonal_section(double ea, double ga2, double ga3, double gj, double ei2, double ei3,
                              double mass_per_length, double i2, double i3) {
  Section s;
  s.stiffness.diagonal() << ea, ga2, ga3, gj, ei2, ei3;
  s.mass_per_length = mass_per_length;
  // Polar inertia of a section is the sum of the two bending inertias (perpendicular-axis theorem).
  s.inertia_per_length.diagonal() << i2 + i3, i2, i3;
  return s;
}

void add_planar_constraints(Model& model) {
  model.planar = true;
  for (size_t i = 0; i < model.nodes.size(); ++i) {
    JointSpec j;
    j.kind = JointKind::planar;
    j.name = "planar node " + std::to_string(i);
    j.node_b = static_cast<int>(i);
    model.joints.push_back(j);
  }
}

}  // namespace tfmb::beam
