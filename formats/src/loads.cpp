// The loads kind's one reader and writer: formats/loads.md (schema in schema_loads.cpp).
#include "tfmb/formats/loads.hpp"

#include <cmath>
#include <numbers>
#include <sstream>

#include "rows.hpp"
#include "tfmb/common/errors.hpp"
#include "tfmb/common/h5.hpp"
#include "tfmb/formats/schema.hpp"

namespace tfmb::formats {
namespace {

Eigen::Vector3d read_vector3(const h5::Reader& r, const std::string& object,
                             const std::string& name) {
  const std::vector<double> v = r.attr_f64_vector(object, name);
  if (v.size() != 3)
    r.fail(object, "attribute '" + name + "' must have 3 components");
  return {v[0], v[1], v[2]};
}

std::vector<double> components(const Eigen::Vector3d& v) {
  return {v.x(), v.y(), v.z()};
}

}  // namespace

void write_loads(const std::filesystem::path& file, const Loads& loads,
                 const Provenance& provenance) {
  h5::Writer w(file);
  write_header(w, "loads", loads.header);
  w.set_attr("/", "method", loads.method);
  w.set_attr("/", "load_basis", loads.load_basis);
  for (const LoadsFlap& f : loads.flaps) {
    const std::string g = "/flaps/" + f.name;
    w.write(g + "/s", f.s, "m", "arc length of each beam node");
    if (!f.position.empty())
      w.write(g + "/position", detail::rows(f.position), "m",
              "reference position x, y of each beam node");
    w.write(g + "/distributed_force", detail::rows(f.distributed_force), "N/m",
            "force per unit beam length at each node, over the flap width");
    w.write(g + "/distributed_moment", detail::rows(f.distributed_moment), "N",
            "moment per unit beam length at each node");
    w.write(g + "/nodal_force", detail::rows(f.nodal_force), "N", "consistent nodal forces");
    w.write(g + "/nodal_moment", detail::rows(f.nodal_moment), "N m", "consistent nodal moments");
    w.set_attr(g, "width", f.width);
    w.set_attr(g, "total_force", components(f.total_force));
    w.set_attr(g, "total_moment", components(f.total_moment));
    w.set_attr(g, "mapped_force", components(f.mapped_force));
    w.set_attr(g, "mapped_moment", components(f.mapped_moment));
    std::string names;
    for (const auto& t : f.traces)
      names += (names.empty() ? "" : " ") + t;
    w.set_attr(g, "traces", names);
  }
  write_provenance(w, provenance);
  w.commit();
  write_xdmf_sidecar(file);
}

Loads read_loads(const std::filesystem::path& file) {
  const h5::Reader r = open_checked(file, "loads");
  Loads loads;
  loads.source = file;
  loads.header = read_header(r);
  loads.method = r.attr_string("/", "method");
  loads.load_basis = r.attr_string("/", "load_basis");
  for (const std::string& name : r.children("/flaps")) {
    const std::string g = "/flaps/" + name;
    LoadsFlap f;
    f.name = name;
    f.width = r.attr_f64(g, "width");
    std::istringstream words(r.attr_string(g, "traces"));
    for (std::string t; words >> t;)
      f.traces.push_back(t);
    f.s = r.read_vector(g + "/s");
    const std::size_t n = f.s.size();
    if (n < 2)
      r.fail(g + "/s", "fewer than two beam nodes");
    for (std::size_t i = 1; i < n; ++i)
      if (!(f.s[i] >= f.s[i - 1]))
        r.fail(g + "/s", "arc length decreases at node " + std::to_string(i));
    if (r.exists(g + "/position")) {
      f.position = detail::read_rows<2>(r, g + "/position", n);
      // s is the arc length of the reference line through the nodes: between two nodes it is
      // at least their distance and at most pi/2 times it (a circular arc of up to a half
      // turn; no flap turns that far between two beam nodes). Found by the mutation suite: an
      // arc length of 1e300 m changed workflows/nodal-forces' lumping without a word.
      for (std::size_t i = 1; i < n; ++i) {
        const double arc = f.s[i] - f.s[i - 1];
        const double chord = (f.position[i] - f.position[i - 1]).norm();
        if (!(arc >= chord * (1.0 - 1e-9) - 1e-12 &&
              arc <= 0.5 * std::numbers::pi * chord * (1.0 + 1e-9) + 1e-12)) {
          std::ostringstream what;
          what << "node " << i << ": an arc length step of " << arc << " m between nodes " << chord
               << " m apart (/position); it lies between 1 and pi/2 times that";
          r.fail(g + "/s", what.str());
        }
      }
    }
    f.distributed_force = detail::read_rows<3>(r, g + "/distributed_force", n);
    f.distributed_moment = detail::read_rows<3>(r, g + "/distributed_moment", n);
    f.nodal_force = detail::read_rows<3>(r, g + "/nodal_force", n);
    f.nodal_moment = detail::read_rows<3>(r, g + "/nodal_moment", n);
    f.total_force = read_vector3(r, g, "total_force");
    f.total_moment = read_vector3(r, g, "total_moment");
    f.mapped_force = read_vector3(r, g, "mapped_force");
    f.mapped_moment = read_vector3(r, g, "mapped_moment");
    loads.flaps.push_back(std::move(f));
  }
  return loads;
}

}  // namespace tfmb::formats
