// Layout of the "model" file kind; prose spec in formats/model.md.
#include "schema_rules.hpp"

namespace tfmb::formats::detail {

Schema model_schema() {
  Schema s{"model", "tfmb/model", 1, 0,
           "the analysis model: flaps as beams, sections, joints, supports, walls, flow domain, "
           "conditions",
           false, {}, {}};
  add_root(s, true);
  s.attributes.push_back(sattr("/flaps/*", "material", "material name in the material database"));
  s.attributes.push_back(nattr("/flaps/*", "thickness", "m", "wall thickness", 0.0));
  s.attributes.push_back(nattr("/flaps/*", "width", "m", "flap width (depth direction)", 0.0));
  s.attributes.push_back(sattr("/flaps/*", "half", "nozzle half", {"upper", "lower", "none"}));
  s.attributes.push_back(sattr("/joints/*", "kind", "joint kind",
                               {"rigid", "revolute", "revolute_spring", "revolute_clearance",
                                "flexible", "prescribed_rotation"}));
  s.attributes.push_back(sattr("/joints/*", "flap_a", "first flap"));
  s.attributes.push_back(sattr("/joints/*", "end_a", "end of the first flap", {"start", "end"}));
  s.attributes.push_back(sattr("/joints/*", "flap_b", "second flap"));
  s.attributes.push_back(sattr("/joints/*", "end_b", "end of the second flap", {"start", "end"}));
  s.attributes.push_back(sattr("/supports/*", "flap", "supported flap"));
  s.attributes.push_back(sattr("/supports/*", "end", "supported end", {"start", "end"}));
  s.attributes.push_back(sattr("/supports/*", "kind", "support kind", {"clamp", "pinned"}));
  s.attributes.push_back(sattr("/domain/boundaries/*", "kind", "boundary condition kind",
                               {"inflow", "farfield", "outflow", "wall", "slip_wall", "symmetry",
                                "axis"}));
  s.attributes.push_back(nattr("/conditions", "nozzle_pressure_ratio", "1",
                               "stagnation over ambient pressure", 1.0));
  s.attributes.push_back(nattr("/conditions", "stagnation_temperature", "K", "", 0.0));
  s.attributes.push_back(nattr("/conditions", "ambient_pressure", "Pa", "", 0.0));
  s.attributes.push_back(nattr("/conditions", "ambient_temperature", "K", "", 0.0));
  s.attributes.push_back(nattr("/conditions", "gamma", "1", "ratio of specific heats", 1.0, 2.0));
  s.attributes.push_back(nattr("/conditions", "gas_constant", "J/(kg K)", "", 0.0));
  s.datasets.push_back(f64("/flaps/*/reference_curve", {"nr", "2"}, "m",
                           "beam reference line, one row per beam node, start to end"));
  s.datasets.push_back(f64("/flaps/*/section_stiffness", {"6", "6"}, "*",
                           "6x6 sectional stiffness (axial, 2 shears, torsion, 2 bendings): N, N m^2"));
  s.datasets.push_back(f64("/flaps/*/section_mass", {"6", "6"}, "*",
                           "6x6 sectional mass: kg/m, kg m"));
  s.datasets.push_back(f64("/flaps/*/inner_wall", {"ni", "2"}, "m", "wetted inner surface"));
  s.datasets.push_back(f64("/flaps/*/outer_wall", {"no", "2"}, "m", "wetted outer surface"));
  s.datasets.push_back(f64("/joints/*/point", {"2"}, "m", "joint location"));
  s.datasets.push_back(f64("/joints/*/parameters", {"*"}, "*",
                           "kind-specific parameters (see model.md)", false));
  s.datasets.push_back(f64("/domain/boundaries/*/points", {"nb", "2"}, "m",
                           "flow domain boundary curve"));
  add_provenance(s);
  return s;
}

}  // namespace tfmb::formats::detail
