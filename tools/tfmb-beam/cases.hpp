// Builders for the benchmark models used by the verification tests and the benchmark program.
#pragma once

#include <vector>

#include "tfmb-beam/flexible_joint.hpp"
#include "tfmb-beam/model.hpp"

namespace tfmb::beam::cases {

/// Straight cantilever along +x of length `length`, clamped at x = 0 (clamp joint "root"),
/// `n_elements` quadratic elements, one section. The tip node is the last node.
Model cantilever(double length, int n_elements, const Section& section);

/// 45-degree bend of Bathe & Bolourchi (1979): arc of radius 100 in the x-y plane, centre
/// (100, 0, 0), clamped at the origin with tangent +y, dead tip force +z of magnitude `load`.
/// Unit square section, E = 1e7, nu = 0: EA = 1e7, GA2 = GA3 = shear_factor * 5e6,
/// GJ = 5e6 * torsion_constant, EI = 1e7/12.
Model bend45(int n_elements, double load, double shear_factor, double torsion_constant);

/// Seed validation (NOTES.md, Table 1): two beams of length `half_span` each, joined at the centre
/// by a revolute joint about z ("hinge"), outer ends clamped, transverse dead force `load` (-y) at
/// the centre node. `n_elements` per beam. Node ids: centre nodes are the last of beam 1 and the
/// first of beam 2.
Model seed_hinged_beams(double half_span, int n_elements, double load);
Section seed_table1_section();

/// Flexible-joint seed, example 1: two beams of 1.2 m along +x joined at x = 1.2 m by a flexible
/// joint ("bushing", joint 1), the first clamped at its root (joint 0), the second loaded at its
/// tip by the dead force (500, 25, 200) N (load factor 1 = the seed's a = 9). Sections: axial
/// 43.50 MN, shear 4.0 and 2.81 MN, torsion 28.05 kN m^2, bending 23.26 and 298.7 kN m^2. Joint
/// stiffness: translations [[2000,10,10],[10,2000,10],[10,10,2000]], rotations diag(1000).
/// `swap_handles`: handle k is the start of beam 2 and l the end of beam 1 (the seed's dashed lines).
/// The tip node is the last node.
Model seed_flexible_joint_example1(FlexibleMeasure measure, bool swap_handles, int elements_per_beam = 8);

/// Flexible-joint seed, example 2: handle k clamped (the ground), handle l a single node at the
/// origin loaded by the dead force and moment (125, 250, 375) N, N m (load factor 1 = a = 9);
/// joint stiffness translations [[1000,100,100],[100,1000,100],[100,100,1000]], rotations
/// diag(1000, 1000, 100) as printed (`rotational_stiffness`), measures `functions`
/// (seed_measure_functions).
Model seed_flexible_joint_example2(const std::string& functions,
                                  const Eigen::Vector3d& rotational_stiffness = Eigen::Vector3d(1000, 1000, 100));

/// Lee's frame (Lee, Manuel & Rossow 1968; Simo & Vu-Quoc 1986, Part II, sec. 10): a right-angle
/// frame of two members of length 120, a column from (0, 0) to (0, 120) and a beam from (0, 120)
/// to (120, 120), rigidly joined at the corner ("corner"), hinged to the ground at the column's
/// foot ("foot") and at the beam's far end ("end"); E = 7.2e6, nu = 0.3, A = 6, I = 2 (a 3 x 2
/// rectangle, shear factor 5/6); a dead load `load` (-y) on the beam at 24 from the corner (node
/// `LeeFrame::load_node`). Consistent units (the published ones are in and lbf, the limit load of
/// the dead-load path is 18532 in Simo & Vu-Quoc's units); planar. `elements_per_member` must be
/// a multiple of 5 so that the load point is a node.
struct LeeFrame {
  Model model;
  int load_node = 0;
};
LeeFrame lee_frame(int elements_per_member, double load);

}  // namespace tfmb::beam::cases
