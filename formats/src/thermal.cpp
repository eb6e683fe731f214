// The thermal kind's one reader and writer: formats/thermal.md (schema in schema_thermal.cpp).
#include "tfmb/formats/thermal.hpp"

#include "tfmb/common/errors.hpp"
#include "tfmb/common/h5.hpp"
#include "tfmb/formats/schema.hpp"

namespace tfmb::formats {

void write_thermal(const std::filesystem::path& file, const Thermal& thermal,
                   const Provenance& provenance) {
  h5::Writer w(file);
  write_header(w, "thermal", thermal.header);
  write_mesh(w, thermal.mesh);
  w.write("/fields/point/temperature", thermal.temperature, "K", "nodal temperature");
  if (thermal.heat_flux.rows() > 0)
    w.write("/fields/point/heat_flux", thermal.heat_flux, "W/m^2",
            "q = -k grad T, area-weighted nodal average");
  for (const ThermalBeamFlap& f : thermal.beam) {
    const std::string g = "/beam/" + f.name;
    w.write(g + "/mean_temperature", f.mean_temperature, "K", "area mean per beam element");
    w.write(g + "/delta_temperature", f.delta_temperature, "K",
            "outer minus inner surface temperature of the linear fit through the thickness");
  }
  w.create_group("/convergence");
  w.set_attr("/convergence", "converged", static_cast<std::int64_t>(thermal.converged ? 1 : 0));
  w.set_attr("/convergence", "iterations", thermal.iterations);
  w.set_attr("/convergence", "criterion", thermal.criterion);
  write_provenance(w, provenance);
  w.commit();
  write_xdmf_sidecar(file);
}

Thermal read_thermal(const std::filesystem::path& file) {
  const h5::Reader r = open_checked(file, "thermal");
  Thermal t;
  t.source = file;
  t.header = read_header(r);
  t.mesh = read_mesh(r);
  const std::size_t n = t.mesh.node_count();
  t.temperature = r.read_vector("/fields/point/temperature", n);
  if (r.exists("/fields/point/heat_flux"))
    t.heat_flux = r.read_matrix("/fields/point/heat_flux", static_cast<Eigen::Index>(n), 3);
  if (!r.is_group("/beam"))
    r.fail("/beam", "missing: no per beam element temperatures");
  for (const std::string& name : r.children("/beam")) {
    const std::string g = "/beam/" + name;
    ThermalBeamFlap f;
    f.name = name;
    f.mean_temperature = r.read_vector(g + "/mean_temperature");
    f.delta_temperature = r.read_vector(g + "/delta_temperature", f.mean_temperature.size());
    for (std::size_t e = 0; e < f.mean_temperature.size(); ++e) {
      if (!(f.mean_temperature[e] > 0.0))
        r.fail(g + "/mean_temperature", "element " + std::to_string(e) + ": " +
                                            std::to_string(f.mean_temperature[e]) +
                                            " K is not a temperature");
    }
    t.beam.push_back(std::move(f));
  }
  for (std::size_t k = 0; k < n; ++k)
    if (!(t.temperature[k] > 0.0))
      r.fail("/fields/point/temperature", "node " + std::to_string(k) + ": not a temperature");
  // The convergence record is optional (an external solver may not have one).
  if (r.has_attr("/convergence", "converged"))
    t.converged = r.attr_i64("/convergence", "converged") == 1;
  if (r.has_attr("/convergence", "iterations"))
    t.iterations = r.attr_i64("/convergence", "iterations");
  if (r.has_attr("/convergence", "criterion"))
    t.criterion = r.attr_string("/convergence", "criterion");
  return t;
}

}  // namespace tfmb::formats
