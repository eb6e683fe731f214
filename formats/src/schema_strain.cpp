// Layout of the "strain" file kind; prose spec in formats/strain.md.
#include "schema_rules.hpp"

namespace tfmb::formats::detail {

Schema strain_schema() {
  Schema s{"strain", "tfmb/strain", 1, 0,
           "mechanical, thermal and total fibre strains and margins of safety", false, {}, {}};
  add_root(s, true);
  s.attributes.push_back(nattr("/", "worst_margin_total", "1", "smallest total-strain margin"));
  s.attributes.push_back(sattr("/", "worst_flap", "flap of the smallest margin"));
  const std::vector<std::pair<std::string, std::string>> per_element = {
      {"s", "m"},
      {"mechanical_inner", "1"},
      {"mechanical_outer", "1"},
      {"thermal", "1"},
      {"total_inner", "1"},
      {"total_outer", "1"},
      {"allowable", "1"},
      {"margin_mechanical", "1"},
      {"margin_thermal", "1"},
      {"margin_total", "1"}};
  for (const auto& [name, units] : per_element) {
    s.datasets.push_back(f64("/flaps/*/" + name, {"ne"}, units, "per beam element"));
  }
  add_provenance(s);
  return s;
}

}  // namespace tfmb::formats::detail
