// Layout of the "walldisp" file kind; prose spec in formats/walldisp.md.
#include "schema_rules.hpp"

namespace tfmb::formats::detail {

Schema walldisp_schema() {
  Schema s{"walldisp", "tfmb/walldisp", 1, 0,
           "displacement of every wall point from the beam solution", false, {}, {}};
  add_root(s, true);
  s.datasets.push_back(f64("/walls/*/x0", {"n", "2"}, "m", "undeformed wall point"));
  s.datasets.push_back(f64("/walls/*/displacement", {"n", "2"}, "m", "displacement"));
  add_provenance(s);
  return s;
}

}  // namespace tfmb::formats::detail
