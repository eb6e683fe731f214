// Layout of the "structure" file kind; prose spec in formats/structure.md.
#include "schema_rules.hpp"

namespace tfmb::formats::detail {

Schema structure_schema() {
  Schema s{"structure",
           "tfmb/structure",
           1,
           3,
           "beam solution: displacements, rotations, sectional strains and forces, joints",
           false,
           {},
           {}};
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
  // Static analysis: the load path (1.3).
  s.attributes.push_back(sattr("/path", "method", "static: how the path was followed (1.3)",
                               {"load_stepping", "arc_length"}, false));
  s.attributes.push_back(
      sattr("/path", "monitor",
            "static: the node of node_displacement and the "
            "direction of characteristic_displacement, e.g. 'flap_a:end (0, -1, 0)' (1.3)",
            {}, false));
  s.datasets.push_back(f64("/path/load_factor", {"S"}, "1",
                           "static: load factor per converged step, row 0 the unloaded start (1.3)",
                           false));
  s.datasets.push_back(f64("/path/arc_length", {"S"}, "m",
                           "static: path length in the nodal translations, sum over the steps of "
                           "the norm of the translation increments (1.3)",
                           false));
  s.datasets.push_back(
      f64("/path/max_displacement", {"S"}, "m", "static: largest nodal displacement (1.3)", false));
  s.datasets.push_back(
      f64("/path/characteristic_displacement", {"S"}, "m",
          "static: node_displacement along the monitor's direction, else max_displacement; its "
          "turns are the limit points in displacement (1.3)",
          false));
  s.datasets.push_back(f64("/path/node_displacement", {"S", "3"}, "m",
                           "static: displacement of the monitored node (1.3)", false));
  s.datasets.push_back(
      i64("/path/iterations", {"S"}, "",
          "static: Newton iterations of the step, cut-back attempts included (1.3)", false));
  s.datasets.push_back(i64("/path/limit_points_load", {"Pl"}, "S",
                           "static: rows where the load-factor increment changes sign (1.3)",
                           false));
  s.datasets.push_back(i64(
      "/path/limit_points_displacement", {"Pd"}, "S",
      "static: rows where the characteristic displacement's increment changes sign (1.3)", false));
  add_provenance(s);
  return s;
}

}  // namespace tfmb::formats::detail
