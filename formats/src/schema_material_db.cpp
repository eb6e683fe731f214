// Layout of the "material-db" file kind; prose spec in formats/material-db.md.
#include "schema_rules.hpp"

namespace tfmb::formats::detail {

Schema material_db_schema() {
  Schema s{"material-db", "tfmb/material-db", 1, 1,
           "tabulated material properties against temperature, with sources", false, {}, {}};
  add_root(s, false);
  s.attributes.push_back(sattr("/", "default_titanium", "material used where a case says 'titanium'",
                               {}, false));
  s.attributes.push_back(sattr("/materials/*", "description", "alloy and condition"));
  s.attributes.push_back(sattr("/materials/*", "aliases",
                               "other names of the material, comma-separated, matched without case"));
  s.attributes.push_back(nattr("/materials/*", "reference_temperature", "K",
                               "reference of the mean thermal expansion coefficient", 0.0));
  s.attributes.push_back(sattr("/materials/*", "missing",
                               "properties the sources do not give ('none' if complete)"));
  s.attributes.push_back(sattr("/materials/*/*", "source", "where the values come from"));
  s.attributes.push_back(sattr("/materials/*/*", "exactness",
                               "trust level: the least trustworthy of the table's points",
                               {"exact_table", "transcription", "abstract", "fit", "digitised",
                                "derived"}));
  s.attributes.push_back(sattr("/materials/*/*", "derivation",
                               "how derived values were computed ('none ...' if none)"));
  s.attributes.push_back(sattr("/materials/*/*", "note", "caveats of the sources", {}, false));
  s.datasets.push_back(f64("/materials/*/*/temperature", {"n"}, "K", "strictly increasing"));
  s.datasets.push_back(f64("/materials/*/*/value", {"n"}, "*", "property at each temperature"));
  s.datasets.push_back(str("/materials/*/*/point_exactness", {"n"},
                           "exactness of each point (same words as the table's exactness)"));
  s.datasets.push_back(str("/materials/*/*/point_source", {"n"},
                           "source of each point: CSV file and row, or how it was derived"));
  add_provenance(s);
  return s;
}

}  // namespace tfmb::formats::detail
