// Layout of the "model" file kind; prose spec in formats/model.md. Written by tfmb-input
// and read only through formats/src/model.cpp (tfmb-input writes it; tfmb-mesh, tfmb-beam,
// tfmb-loads, tfmb-matmap and tfmb-heat read it).
// 2.0: beam discretisation, full-resolution reference lines, joint parameters, domain
// boundaries with kinds and order, solid outlines, thermal, mesh and analysis settings.
// 2.1: flexible joints: measure_functions (+ lambda_terms, mu_terms) replace 2.0's constant
// measure_lambda / measure_mu, which no tool read; joint kind prismatic with /axis.
// 2.2: optional /mesh_controls@cells_per_circle (curvature-based wall spacing).
// 2.3: optional /mesh_controls@end_cells (cells across a flap's end face).
// 2.4: support kinds sliding_clamp and sliding_pinned with /supports/*/axis.
// 2.5: optional /conditions@viscous_length (nu/u_tau of the y+ estimate; tfmb-mesh reports the
// first layer's y+ from it instead of compiling tfmb-input's estimate).
// 2.6: /conditions@turbulence k_omega_sst, k_omega_sst_v.
// 2.7: root @geometry may be "axisymmetric" (case.toml domain.geometry; channel domains only,
// whose lower piece is then of kind "axis" on y = 0; the reader checks both).
#include "schema_rules.hpp"

namespace tfmb::formats::detail {

namespace {
AttributeRule iattr(std::string object, std::string name, std::string meaning, double lo,
                    std::optional<double> hi = {}, bool required = true) {
  return nattr(std::move(object), std::move(name), "1", std::move(meaning), lo, hi, required,
               AttrType::int64);
}
}  // namespace

Schema model_schema() {
  Schema s{"model",
           "tfmb/model",
           2,
           7,
           "the analysis model: flaps as beams, sections, joints, supports, walls, flow domain, "
           "conditions, thermal, mesh and analysis settings",
           false,
           {},
           {}};
  add_root(s, true);
  s.attributes.push_back(sattr("/", "title", "case title from case.toml", {}, false));
  // Flaps.
  s.attributes.push_back(iattr("/flaps/*", "order", "position of the flap in case.toml (0-based)", 0));
  s.attributes.push_back(sattr("/flaps/*", "material", "material name in the material database"));
  s.attributes.push_back(nattr("/flaps/*", "thickness", "m", "wall thickness", 0.0));
  s.attributes.push_back(nattr("/flaps/*", "width", "m", "flap width (depth direction)", 0.0));
  s.attributes.push_back(sattr("/flaps/*", "half", "nozzle half", {"upper", "lower", "none"}));
  s.attributes.push_back(iattr("/flaps/*", "elements", "two-node beam elements along reference_curve", 1));
  s.attributes.push_back(sattr("/flaps/*", "curves", "geometry curves of the flap, comma-separated"));
  s.attributes.push_back(sattr("/flaps/*", "section_kind", "how the section was given",
                               {"rectangle", "explicit"}));
  s.attributes.push_back(nattr("/flaps/*", "youngs_modulus", "Pa",
                               "rectangle: room-temperature modulus the section was built with", 0.0,
                               std::nullopt, false));
  s.attributes.push_back(nattr("/flaps/*", "poisson_ratio", "1", "rectangle: Poisson ratio", 0.0, 0.5, false));
  s.attributes.push_back(nattr("/flaps/*", "density", "kg/m^3", "rectangle: density", 0.0, std::nullopt, false));
  s.datasets.push_back(f64("/flaps/*/reference_geometry", {"ng", "2"}, "m",
                           "beam reference line at full geometric resolution, start to end"));
  s.datasets.push_back(f64("/flaps/*/reference_curve", {"nr", "2"}, "m",
                           "beam nodes: elements+1 points at equal arc length, start to end; "
                           "element e joins nodes e and e+1"));
  s.datasets.push_back(f64("/flaps/*/section_stiffness", {"6", "6"}, "N, N m, N m^2",
                           "6x6 sectional stiffness, order axial, shear 2 (in-plane), shear 3, "
                           "torsion, bending 2 (out of plane), bending 3 (in plane)"));
  s.datasets.push_back(f64("/flaps/*/section_mass", {"6", "6"}, "kg/m, kg m",
                           "6x6 sectional mass, same order"));
  s.datasets.push_back(f64("/flaps/*/inner_wall", {"ng", "2"}, "m",
                           "surface facing the nozzle axis (half none: right of the reference "
                           "direction), reference_geometry offset by thickness/2"));
  s.datasets.push_back(f64("/flaps/*/outer_wall", {"ng", "2"}, "m", "the opposite surface"));
  s.datasets.push_back(f64("/flaps/*/wall_arc_length", {"ng"}, "m",
                           "arc length along reference_geometry of each wall point's foot"));
  s.datasets.push_back(f64("/flaps/*/solid_outline", {"no", "2"}, "m",
                           "closed counter-clockwise outline of the thickness region (conduction)"));
  // Joints.
  s.attributes.push_back(sattr("/joints/*", "kind", "joint kind",
                               {"rigid", "revolute", "revolute_spring", "revolute_clearance",
                                "flexible", "prescribed_rotation", "prismatic"}));
  s.attributes.push_back(sattr("/joints/*", "flap_a", "first flap"));
  s.attributes.push_back(sattr("/joints/*", "end_a", "end of the first flap", {"start", "end"}));
  s.attributes.push_back(sattr("/joints/*", "flap_b", "second flap"));
  s.attributes.push_back(sattr("/joints/*", "end_b", "end of the second flap", {"start", "end"}));
  s.attributes.push_back(nattr("/joints/*", "stiffness", "N m/rad", "revolute_spring: torsional stiffness",
                               0.0, std::nullopt, false));
  s.attributes.push_back(nattr("/joints/*", "damping", "N m s/rad", "revolute_spring: torsional damping",
                               0.0, std::nullopt, false));
  s.attributes.push_back(nattr("/joints/*", "inner_radius", "m", "revolute_clearance: pin radius", 0.0,
                               std::nullopt, false));
  s.attributes.push_back(nattr("/joints/*", "outer_radius", "m", "revolute_clearance: bore radius", 0.0,
                               std::nullopt, false));
  s.attributes.push_back(nattr("/joints/*", "contact_stiffness", "N/m",
                               "revolute_clearance: penalty contact stiffness", 0.0, std::nullopt, false));
  s.attributes.push_back(nattr("/joints/*", "friction", "1", "revolute_clearance: Coulomb coefficient",
                               0.0, 1.0, false));
  s.attributes.push_back(sattr("/joints/*", "deformation_measure", "flexible: deformation measures",
                               {"proposed", "typical"}, false));
  s.attributes.push_back(sattr("/joints/*", "measure_functions",
                               "flexible, proposed measures: lambda(sigma, p) and mu(sigma, p) (2.1)",
                               {"default", "1a", "1b", "1c", "1d", "2a", "2b", "2c", "2d", "3a", "3b", "3c",
                                "3d", "4a", "4b", "4c", "4d", "custom"},
                               false));
  s.datasets.push_back(f64("/joints/*/point", {"2"}, "m", "joint location"));
  s.datasets.push_back(f64("/joints/*/stiffness_matrix", {"6", "6"}, "N/m, N m/rad",
                           "flexible: 6x6 stiffness (translations, rotations)", false));
  s.datasets.push_back(f64("/joints/*/lambda_terms", {"nl", "3"}, "1",
                           "flexible, custom: lambda terms (coefficient, power of sigma, power of the rotation parameter magnitude p) (2.1)", false));
  s.datasets.push_back(f64("/joints/*/mu_terms", {"nm", "3"}, "1",
                           "flexible, custom: mu terms (coefficient, power of sigma, power of the rotation parameter magnitude p) (2.1)", false));
  s.datasets.push_back(f64("/joints/*/axis", {"2"}, "1", "prismatic: sliding direction (2.1)", false));
  s.datasets.push_back(f64("/joints/*/rotation_table", {"nt", "2"}, "s, rad",
                           "prescribed_rotation: rows (time, relative rotation angle)", false));
  // Supports.
  s.attributes.push_back(sattr("/supports/*", "flap", "supported flap"));
  s.attributes.push_back(sattr("/supports/*", "end", "supported end", {"start", "end"}));
  s.attributes.push_back(sattr("/supports/*", "kind", "support kind",
                               {"clamp", "pinned", "sliding_clamp", "sliding_pinned"}));
  s.datasets.push_back(f64("/supports/*/point", {"2"}, "m", "support location"));
  s.datasets.push_back(
      f64("/supports/*/axis", {"2"}, "1", "sliding kinds: unit sliding direction (2.4)", false));
  // Flow domain.
  s.attributes.push_back(sattr("/domain", "kind", "domain type", {"nozzle", "channel", "flatplate", "none"}));
  s.attributes.push_back(nattr("/domain", "plenum_length", "m", "nozzle: inflow face upstream of the first flap",
                               0.0, std::nullopt, false));
  s.attributes.push_back(nattr("/domain", "downstream_length", "m", "nozzle: downstream far-field face, this far behind the exit",
                               0.0, std::nullopt, false));
  s.attributes.push_back(nattr("/domain", "farfield_height", "m", "nozzle/flatplate: |y| of the far field",
                               0.0, std::nullopt, false));
  s.attributes.push_back(iattr("/domain", "boattail", "nozzle: 1 if the last flap returns to the nacelle", 0, 1, false));
  s.attributes.push_back(sattr("/domain", "wall_curve", "channel: geometry curve of the wall", {}, false));
  s.attributes.push_back(nattr("/domain", "plate_length", "m", "flatplate: plate length", 0.0, std::nullopt, false));
  s.attributes.push_back(nattr("/domain", "upstream_length", "m", "flatplate: symmetry plane ahead of the plate",
                               0.0, std::nullopt, false));
  s.attributes.push_back(sattr("/domain/boundaries/*", "kind", "boundary condition kind",
                               {"inflow", "farfield", "outflow", "wall", "slip_wall", "symmetry", "axis"}));
  s.attributes.push_back(iattr("/domain/boundaries/*", "order",
                               "position in the counter-clockwise boundary loop (0-based)", 0));
  // A flap's wall names both (tfmb-mesh copies them to the mesh boundaries, where the mesh
  // block's rule asks for both together).
  AttributeRule flap = sattr("/domain/boundaries/*", "flap", "flap whose wall this is", {}, false);
  flap.required_with = "side";
  s.attributes.push_back(flap);
  AttributeRule side =
      sattr("/domain/boundaries/*", "side", "side of the flap", {"inner", "outer", "end"}, false);
  side.required_with = "flap";
  s.attributes.push_back(side);
  s.datasets.push_back(f64("/domain/boundaries/*/points", {"nb", "2"}, "m",
                           "boundary piece in loop direction (domain on the left)"));
  // Flow conditions.
  s.attributes.push_back(nattr("/conditions", "nozzle_pressure_ratio", "1", "stagnation over ambient pressure", 1.0));
  s.attributes.push_back(nattr("/conditions", "stagnation_temperature", "K", "inflow stagnation temperature", 0.0));
  s.attributes.push_back(nattr("/conditions", "ambient_pressure", "Pa", "far-field static pressure", 0.0));
  s.attributes.push_back(nattr("/conditions", "ambient_temperature", "K", "far-field static temperature", 0.0));
  s.attributes.push_back(nattr("/conditions", "ambient_mach", "1", "external stream Mach number", 0.0));
  s.attributes.push_back(nattr("/conditions", "exit_pressure_ratio", "1",
                               "channel: exit static over inflow stagnation pressure (0: unused)", 0.0, 1.0));
  s.attributes.push_back(nattr("/conditions", "gamma", "1", "ratio of specific heats", 1.0, 2.0));
  s.attributes.push_back(nattr("/conditions", "gas_constant", "J/(kg K)", "specific gas constant", 0.0));
  s.attributes.push_back(nattr("/conditions", "prandtl", "1", "laminar Prandtl number", 0.0));
  s.attributes.push_back(nattr("/conditions", "turbulent_prandtl", "1", "turbulent Prandtl number", 0.0));
  s.attributes.push_back(
      sattr("/conditions", "turbulence", "flow model",
            {"spalart_allmaras", "k_omega_sst", "k_omega_sst_v", "laminar", "inviscid"}));
  s.attributes.push_back(nattr("/conditions", "reference_length", "m",
                               "length for the Reynolds number of the y+ estimate (0: 0.1 m)", 0.0));
  s.attributes.push_back(nattr("/conditions", "yplus_target", "1", "y+ the first cell was sized for (0: height given)", 0.0));
  s.attributes.push_back(nattr("/conditions", "first_cell_height", "m", "first cell height at walls", 0.0));
  s.attributes.push_back(
      nattr("/conditions", "viscous_length", "m",
            "nu/u_tau of the flat-plate skin-friction estimate: a cell height h has "
            "y+ = h / viscous_length (0: not recorded)",
            0.0, std::nullopt, false));
  // Thermal settings.
  s.attributes.push_back(sattr("/thermal", "flow_wall", "thermal wall condition of the flow solver",
                               {"adiabatic", "isothermal"}));
  s.attributes.push_back(nattr("/thermal", "wall_temperature", "K", "isothermal wall temperature (0: unused)", 0.0));
  s.attributes.push_back(sattr("/thermal", "solid_boundary", "how the flow heats the flap walls",
                               {"wall_temperature", "convection", "convection_radiation"}));
  s.attributes.push_back(nattr("/thermal", "emissivity", "1", "surface emissivity for radiation", 0.0, 1.0));
  s.attributes.push_back(nattr("/thermal", "reference_temperature", "K", "stress-free temperature", 0.0));
  // Mesh controls.
  s.attributes.push_back(nattr("/mesh_controls", "wall_size", "m", "cell length along walls (0: automatic)", 0.0));
  s.attributes.push_back(nattr("/mesh_controls", "far_size", "m", "cell size at the far field (0: automatic)", 0.0));
  s.attributes.push_back(nattr("/mesh_controls", "growth", "1", "boundary-layer growth ratio", 1.0));
  s.attributes.push_back(iattr("/mesh_controls", "max_layers", "boundary-layer layers at most", 0));
  s.attributes.push_back(nattr("/mesh_controls", "scale", "1", "multiplies every mesh size", 0.0));
  s.attributes.push_back(iattr("/mesh_controls", "cells_along", "structured: cells along the flow (0: automatic)", 0));
  s.attributes.push_back(iattr("/mesh_controls", "cells_across", "structured: cells across (0: automatic)", 0));
  s.attributes.push_back(iattr("/mesh_controls", "cells_upstream", "flatplate: cells ahead of the plate", 0));
  s.attributes.push_back(nattr("/mesh_controls", "leading_edge_spacing", "m", "flatplate: streamwise spacing at the leading edge", 0.0));
  s.attributes.push_back(iattr("/mesh_controls", "cells_per_circle", "nozzle walls: spacing at most 2 pi R / cells_per_circle where the wall's radius of curvature is R (0: off; 2.2)", 0, {}, false));
  s.attributes.push_back(iattr("/mesh_controls", "end_cells", "nozzle walls: cells across each flap end face at least (2 when absent; 2.3)", 2, {}, false));
  s.attributes.push_back(iattr("/mesh_controls", "solid_cells_per_element", "solid mesh cells along one beam element", 1));
  s.attributes.push_back(iattr("/mesh_controls", "solid_layers", "solid mesh cells through the thickness", 1));
  // Analysis settings.
  s.attributes.push_back(sattr("/analysis", "kind", "what the workflow runs", {"oneway", "twoway", "structure", "flow"}));
  s.attributes.push_back(sattr("/analysis", "time", "structural analysis type", {"static", "dynamic"}));
  s.attributes.push_back(nattr("/analysis", "end_time", "s", "dynamic: end time", 0.0));
  s.attributes.push_back(nattr("/analysis", "time_step", "s", "dynamic: time step", 0.0));
  s.attributes.push_back(iattr("/analysis", "load_steps", "static: load steps", 1));
  s.attributes.push_back(iattr("/analysis", "max_coupling_iterations", "two-way: iterations at most", 1));
  s.attributes.push_back(nattr("/analysis", "coupling_tolerance", "m", "two-way: wall displacement change tolerance", 0.0));
  s.attributes.push_back(sattr("/analysis", "convergence", "two-way convergence measure",
                               {"absolute", "relative", "residual-relative"}));
  s.attributes.push_back(sattr("/analysis", "acceleration", "two-way acceleration", {"constant", "aitken", "iqn-ils"}));
  s.attributes.push_back(nattr("/analysis", "relaxation", "1", "two-way (initial) relaxation factor", 0.0, 1.0));
  add_provenance(s);
  return s;
}

}  // namespace tfmb::formats::detail
