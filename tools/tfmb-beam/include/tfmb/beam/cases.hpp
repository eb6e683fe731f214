// Builders for the benchmark models used by the verification tests and the benchmark program.
#pragma once

#include "tfmb/beam/model.hpp"

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

}  // namespace tfmb::beam::cases
