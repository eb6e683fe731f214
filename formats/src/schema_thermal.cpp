// Layout of the "thermal" file kind; prose spec in formats/thermal.md.
#include "schema_rules.hpp"

namespace tfmb::formats::detail {

Schema thermal_schema() {
  Schema s{"thermal", "tfmb/thermal", 1, 1,
           "solid temperatures and per beam element mean temperature and through-thickness "
           "difference",
           true, {}, {}};
  add_root(s, true);
  add_mesh(s);
  s.datasets.push_back(f64("/fields/point/temperature", {"N"}, "K", ""));
  s.datasets.push_back(f64("/fields/point/heat_flux", {"N", "3"}, "W/m^2", "", false));
  s.datasets.push_back(f64("/beam/*/mean_temperature", {"ne"}, "K", "area mean per beam element"));
  s.datasets.push_back(f64("/beam/*/delta_temperature", {"ne"}, "K",
                           "outer minus inner surface temperature of the linear fit through the "
                           "thickness"));
  s.attributes.push_back(nattr("/convergence", "converged", "1", "1 if Newton met its tolerance",
                               0.0, 1.0, false, AttrType::int64));
  s.attributes.push_back(sattr("/convergence", "criterion", "convergence criterion used", {}, false));
  s.attributes.push_back(nattr("/convergence", "iterations", "1", "Newton iterations", 0.0,
                               std::nullopt, false, AttrType::int64));
  add_provenance(s);
  return s;
}

}  // namespace tfmb::formats::detail
