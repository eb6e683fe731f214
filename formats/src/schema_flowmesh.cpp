// Layout of the "flowmesh" file kind; prose spec in formats/flowmesh.md. Written by tfmb-mesh.
// 1.1: quality attributes min_cell_area, first_layer_height, estimated_yplus, boundary_layers.
#include "schema_rules.hpp"

namespace tfmb::formats::detail {

Schema flowmesh_schema() {
  Schema s{"flowmesh", "tfmb/flowmesh", 1, 1,
           "mixed quad/triangle fluid mesh with tagged boundaries", true, {}, {}};
  add_root(s, true);
  add_mesh(s);
  s.attributes.push_back(nattr("/mesh", "min_angle", "deg", "quality report: smallest cell angle",
                               0.0, 180.0, false));
  s.attributes.push_back(nattr("/mesh", "max_aspect_ratio", "1", "quality report", 1.0,
                               std::nullopt, false));
  s.attributes.push_back(nattr("/mesh", "min_cell_area", "m^2",
                               "quality report: smallest corner-triangle area of any cell", std::nullopt,
                               std::nullopt, false));
  s.attributes.push_back(nattr("/mesh", "first_layer_height", "m",
                               "height of the first cell layer at walls (0: no wall layers)", 0.0,
                               std::nullopt, false));
  s.attributes.push_back(nattr("/mesh", "estimated_yplus", "1",
                               "y+ of the first layer from a flat-plate skin-friction estimate", 0.0,
                               std::nullopt, false));
  s.attributes.push_back(nattr("/mesh", "boundary_layers", "1", "number of structured wall layers",
                               0.0, std::nullopt, false, AttrType::int64));
  add_provenance(s);
  return s;
}

}  // namespace tfmb::formats::detail
