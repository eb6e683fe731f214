// Layout of the "strain" file kind; prose spec in formats/strain.md.
#include "schema_rules.hpp"

namespace tfmb::formats::detail {

Schema strain_schema() {
  Schema s{"strain", "tfmb/strain", 1, 1,
           "mechanical, thermal and total fibre strains and margins of safety", false, {}, {}};
  add_root(s, true);
  s.attributes.push_back(sattr("/", "mechanical_basis",
                               "what the structure's sectional strain was taken as (strain.md)",
                               {"mechanical", "kinematic", "force"}));
  s.attributes.push_back(nattr("/", "worst_margin_total", "1", "smallest total-strain margin"));
  s.attributes.push_back(nattr("/", "worst_margin_mechanical", "1", "smallest mechanical-strain margin"));
  s.attributes.push_back(nattr("/", "worst_margin_thermal", "1", "smallest thermal-strain margin"));
  s.attributes.push_back(sattr("/", "worst_flap", "flap of the smallest total margin"));
  s.attributes.push_back(nattr("/", "worst_segment", "1", "segment of the smallest total margin", 0.0,
                               std::nullopt, true, AttrType::int64));
  s.attributes.push_back(sattr("/", "worst_surface", "surface of the smallest total margin", {"inner", "outer"}));
  s.attributes.push_back(nattr("/", "worst_position", "m", "x, y of the smallest total margin",
                               std::nullopt, std::nullopt, true, AttrType::float64_vector));
  s.datasets.push_back(i64("/flaps/*/element", {"ns"}, "", "material element (materials.h5) of each segment"));
  s.datasets.push_back(f64("/flaps/*/position", {"ns", "2"}, "m", "reference position of the segment middle"));
  const std::vector<std::pair<std::string, std::string>> per_segment = {
      {"s", "arc length of the segment middle [m]"},
      {"mechanical_inner", "mechanical fibre strain at the inner surface"},
      {"mechanical_outer", "mechanical fibre strain at the outer surface"},
      {"thermal_inner", "free thermal strain at the inner surface"},
      {"thermal_outer", "free thermal strain at the outer surface"},
      {"total_inner", "mechanical + thermal at the inner surface"},
      {"total_outer", "mechanical + thermal at the outer surface"},
      {"allowable", "allowable strain at the element temperature"},
      {"margin_mechanical", "allowable / max |mechanical| - 1 (capped at 1e6)"},
      {"margin_thermal", "allowable / max |thermal| - 1 (capped at 1e6)"},
      {"margin_total", "allowable / max |total| - 1 (capped at 1e6)"}};
  for (const auto& [name, meaning] : per_segment) {
    s.datasets.push_back(f64("/flaps/*/" + name, {"ns"}, name == "s" ? "m" : "1", "per beam segment: " + meaning));
  }
  s.datasets.push_back(str("/worst/flap", {"W"}, "flaps of the lowest total margins, ascending"));
  s.datasets.push_back(str("/worst/surface", {"W"}, "inner or outer"));
  s.datasets.push_back(i64("/worst/segment", {"W"}, "", "segment within the flap"));
  s.datasets.push_back(i64("/worst/element", {"W"}, "", "material element"));
  s.datasets.push_back(f64("/worst/s", {"W"}, "m", "arc length"));
  s.datasets.push_back(f64("/worst/position", {"W", "2"}, "m", "x, y"));
  s.datasets.push_back(f64("/worst/total_strain", {"W"}, "1", "total fibre strain there"));
  s.datasets.push_back(f64("/worst/margin_total", {"W"}, "1", "total margin there"));
  add_provenance(s);
  return s;
}

}  // namespace tfmb::formats::detail
