// Layout of the "material-db" file kind; prose spec in formats/material-db.md.
#include "schema_rules.hpp"

namespace tfmb::formats::detail {

Schema material_db_schema() {
  Schema s{"material-db", "tfmb/material-db", 1, 0,
           "tabulated material properties against temperature, with sources", false, {}, {}};
  add_root(s, false);
  s.attributes.push_back(sattr("/materials/*", "description", "alloy and condition"));
  s.attributes.push_back(nattr("/materials/*", "reference_temperature", "K",
                               "reference of the mean thermal expansion coefficient", 0.0));
  s.attributes.push_back(sattr("/materials/*/*", "source", "where the values come from"));
  s.attributes.push_back(sattr("/materials/*/*", "exactness", "trust level",
                               {"exact_table", "transcription", "digitised", "derived"}));
  s.datasets.push_back(f64("/materials/*/*/temperature", {"n"}, "K", "strictly increasing"));
  s.datasets.push_back(f64("/materials/*/*/value", {"n"}, "*", "property at each temperature"));
  add_provenance(s);
  return s;
}

}  // namespace tfmb::formats::detail
