// Layout of the "loads" file kind; prose spec in formats/loads.md.
#include "schema_rules.hpp"

namespace tfmb::formats::detail {

Schema loads_schema() {
  Schema s{"loads", "tfmb/loads", 1, 2, "distributed and nodal beam loads from the wall traces",
           false,   {},           {}};
  add_root(s, true);
  s.attributes.push_back(sattr("/", "method", "mapping method", {"linear", "conservative"}));
  s.attributes.push_back(sattr("/", "load_basis",
                               "what the loads are per: per unit beam length over the flap width "
                               "(the flow traces, per unit depth, times each flap's width)"));
  s.attributes.push_back(nattr("/flaps/*", "width", "m", "flap width the traces were multiplied by",
                               0.0));
  s.attributes.push_back(sattr("/flaps/*", "traces", "names of the wall traces mapped (space-separated)"));
  s.attributes.push_back(nattr("/flaps/*", "total_force", "N", "integral of the traces (x, y, z)",
                               std::nullopt, std::nullopt, true, AttrType::float64_vector));
  s.attributes.push_back(nattr("/flaps/*", "total_moment", "N m", "about the origin (x, y, z)",
                               std::nullopt, std::nullopt, true, AttrType::float64_vector));
  s.attributes.push_back(nattr("/flaps/*", "mapped_force", "N",
                               "sum of the nodal forces (x, y, z); equals total_force to 1e-10 "
                               "relative with method conservative",
                               std::nullopt, std::nullopt, true, AttrType::float64_vector));
  s.attributes.push_back(nattr("/flaps/*", "mapped_moment", "N m",
                               "moment of the nodal forces plus the nodal moments about the origin",
                               std::nullopt, std::nullopt, true, AttrType::float64_vector));
  s.datasets.push_back(f64("/flaps/*/s", {"nn"}, "m", "arc length of each beam node"));
  s.datasets.push_back(f64("/flaps/*/position", {"nn", "2"}, "m",
                           "reference position x, y of each beam node (1.2; the sidecar draws "
                           "the flap's loads along it)",
                           false));
  s.datasets.push_back(f64("/flaps/*/distributed_force", {"nn", "3"}, "N/m",
                           "force per unit beam length at each node (linear between nodes), over "
                           "the flap width"));
  s.datasets.push_back(f64("/flaps/*/distributed_moment", {"nn", "3"}, "N",
                           "moment per unit beam length at each node (offset of the walls from "
                           "the reference line)"));
  s.datasets.push_back(f64("/flaps/*/nodal_force", {"nn", "3"}, "N",
                           "consistent nodal forces (integrals of the distributed force times the "
                           "linear shape functions)"));
  s.datasets.push_back(f64("/flaps/*/nodal_moment", {"nn", "3"}, "N m", "consistent nodal moments"));
  add_provenance(s);
  return s;
}

}  // namespace tfmb::formats::detail
