// Layout of the "walldisp" file kind; prose spec in formats/walldisp.md.
#include "schema_rules.hpp"

namespace tfmb::formats::detail {

Schema walldisp_schema() {
  Schema s{"walldisp", "tfmb/walldisp", 1, 1,
           "displacement of every wall point from the beam solution", false, {}, {}};
  add_root(s, true);
  s.attributes.push_back(sattr("/", "wall_source",
                               "where the wall points come from: the model walls or a flow mesh's "
                               "flap wall nodes"));
  s.attributes.push_back(sattr("/walls/*", "flap", "flap the wall belongs to"));
  s.attributes.push_back(sattr("/walls/*", "side", "side of the flap", {"inner", "outer", "end"}));
  s.datasets.push_back(f64("/walls/*/x0", {"n", "2"}, "m", "undeformed wall point"));
  s.datasets.push_back(f64("/walls/*/displacement", {"n", "2"}, "m",
                           "displacement: beam displacement plus the rotated thickness offset"));
  s.datasets.push_back(i64("/walls/*/node", {"n"}, "",
                           "flow mesh node of each point (when the points came from a mesh)",
                           false));
  add_provenance(s);
  return s;
}

}  // namespace tfmb::formats::detail
