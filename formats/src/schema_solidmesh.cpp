// Layout of the "solidmesh" file kind; prose spec in formats/solidmesh.md.
#include "schema_rules.hpp"

namespace tfmb::formats::detail {

Schema solidmesh_schema() {
  Schema s{"solidmesh", "tfmb/solidmesh", 1, 0,
           "mesh of the flap walls for heat conduction, linked to the beam elements", true, {}, {}};
  add_root(s, true);
  add_mesh(s);
  s.datasets.push_back(str("/link/flap_names", {"F"}, "flap names"));
  s.datasets.push_back(i64("/link/cell_flap", {"Nt+Nq"}, "F", "flap of each cell"));
  s.datasets.push_back(i64("/link/cell_element", {"Nt+Nq"}, "",
                           "beam element (within its flap) each cell belongs to"));
  s.datasets.push_back(f64("/link/point_thickness_coordinate", {"N"}, "m",
                           "signed distance from the beam reference line, positive towards the "
                           "outer surface"));
  add_provenance(s);
  return s;
}

}  // namespace tfmb::formats::detail
