// Layout of the "flowmesh" file kind; prose spec in formats/flowmesh.md.
#include "schema_rules.hpp"

namespace tfmb::formats::detail {

Schema flowmesh_schema() {
  Schema s{"flowmesh", "tfmb/flowmesh", 1, 0,
           "mixed quad/triangle fluid mesh with tagged boundaries", true, {}, {}};
  add_root(s, true);
  add_mesh(s);
  s.attributes.push_back(nattr("/mesh", "min_angle", "deg", "quality report: smallest cell angle",
                               0.0, 180.0, false));
  s.attributes.push_back(nattr("/mesh", "max_aspect_ratio", "1", "quality report", 1.0,
                               std::nullopt, false));
  add_provenance(s);
  return s;
}

}  // namespace tfmb::formats::detail
