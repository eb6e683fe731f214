// Layout of the "structure" file kind; prose spec in formats/structure.md.
#include "schema_rules.hpp"

namespace tfmb::formats::detail {

Schema structure_schema() {
  Schema s{"structure", "tfmb/structure", 1, 2,
           "beam solution: displacements, rotations, sectional strains and forces, joints",
           false, {}, {}};
  add_root(s, true);
  s.attributes.push_back(sattr("/", "analysis", "analysis kind", {"static", "dynamic", "modal"}));
  s.attributes.push_back(nattr("/", "converged", "1", "1 if the solution converged", 0.0, 1.0,
                               true, AttrType::int64));
  s.datasets.push_back(f64("/beam/points", {"N", "3"}, "m", "beam node reference positions"));
  s.datasets.push_back(i64("/beam/segments", {"E", "2"}, "N",
                           "display segments between nodes (an element of order p gives p)"));
  s.datasets.push_back(f64("/fields/point/displacement", {"N", "3"}, "m", ""));
  s.datasets.push_back(f64("/fields/point/rotation", {"N", "3"}, "1",
                           "Wiener-Milenkovic rotation parameters"));
  s.datasets.push_back(f64("/fields/cell/sectional_strain", {"E", "6"}, "*",
                           "axial, 2 shear, torsion, 2 curvatures: 1, 1/m"));
  s.datasets.push_back(f64("/fields/cell/sectional_force", {"E", "6"}, "*",
                           "axial, 2 shear forces, torsion, 2 bending moments: N, N m"));
  s.datasets.push_back(i64("/flaps/*/nodes", {"nn"}, "N", "beam nodes of the flap, in order"));
  s.datasets.push_back(i64("/flaps/*/segments", {"ns"}, "E", "segments of the flap, in order"));
  s.datasets.push_back(f64("/joints/*/reaction", {"6"}, "*", "force (N) and moment (N m)"));
  s.datasets.push_back(f64("/joints/*/relative_rotation", {"*"}, "rad", "", false));
  s.datasets.push_back(f64("/joints/*/contact_force", {"*"}, "N", "clearance joints", false));
  s.datasets.push_back(f64("/joints/*/gap", {"*"}, "m", "clearance joints", false));
  s.datasets.push_back(f64("/joints/*/deformation", {"6"}, "m, 1",
                           "flexible joints: stretch (3) and wryness (3) in the joint frame (1.2)", false));
  s.datasets.push_back(f64("/joints/*/strain_energy", {"1"}, "J", "flexible joints (1.2)", false));
  s.datasets.push_back(f64("/joints/*/sliding", {"1"}, "m", "prismatic joints: relative displacement along the axis (1.2)", false));
  s.datasets.push_back(f64("/history/time", {"T"}, "s", "dynamic analysis", false));
  s.datasets.push_back(f64("/restart/velocity", {"N", "3"}, "m/s", "dynamic: nodal velocity at the end (1.2)", false));
  s.datasets.push_back(f64("/restart/angular_velocity", {"N", "3"}, "rad/s",
                           "dynamic: nodal angular velocity at the end, material frame (1.2)", false));
  s.datasets.push_back(f64("/restart/joint_dofs", {"J"}, "rad", "dynamic: joint unknowns at the end (1.2)", false));
  s.datasets.push_back(f64("/restart/joint_rates", {"J"}, "rad/s", "dynamic: their rates (1.2)", false));
  s.attributes.push_back(nattr("/restart", "time", "s", "dynamic: time reached by the run (1.2)", 0.0, std::nullopt, false));
  s.datasets.push_back(f64("/history/displacement", {"T", "N", "3"}, "m", "", false));
  s.datasets.push_back(f64("/modes/frequency", {"M"}, "Hz", "modal analysis: natural frequencies", false));
  s.datasets.push_back(f64("/modes/displacement", {"M", "N", "3"}, "1",
                           "nodal translations of each mode, divided by its largest entry", false));
  add_provenance(s);
  return s;
}

}  // namespace tfmb::formats::detail
