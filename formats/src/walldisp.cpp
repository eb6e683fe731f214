// The walldisp kind's one reader and writer: formats/walldisp.md (schema in schema_walldisp.cpp).
#include "tfmb/formats/walldisp.hpp"

#include <limits>

#include "rows.hpp"
#include "tfmb/common/errors.hpp"
#include "tfmb/common/h5.hpp"
#include "tfmb/formats/schema.hpp"

namespace tfmb::formats {
void write_walldisp(const std::filesystem::path& file, const WallDisplacements& walls,
                    const Provenance& provenance) {
  h5::Writer w(file);
  write_header(w, "walldisp", walls.header);
  w.set_attr("/", "wall_source", walls.wall_source);
  for (const WallDisplacement& wall : walls.walls) {
    const std::string g = "/walls/" + wall.name;
    w.write(g + "/x0", detail::rows(wall.x0), "m", "undeformed wall point");
    w.write(g + "/displacement", detail::rows(wall.displacement), "m", "displacement");
    if (!wall.nodes.empty())
      w.write(g + "/node", wall.nodes, "1", "flow mesh node of each point");
    w.set_attr(g, "flap", wall.flap);
    w.set_attr(g, "side", wall.side);
  }
  write_provenance(w, provenance);
  w.commit();
  write_xdmf_sidecar(file);
}

WallDisplacements read_walldisp(const std::filesystem::path& file) {
  const h5::Reader r = open_checked(file, "walldisp");
  WallDisplacements out;
  out.source = file;
  out.header = read_header(r);
  out.wall_source = r.attr_string("/", "wall_source");
  for (const std::string& name : r.children("/walls")) {
    const std::string g = "/walls/" + name;
    WallDisplacement wall;
    wall.name = name;
    wall.flap = r.attr_string(g, "flap");
    wall.side = r.attr_string(g, "side");
    const h5::MatrixXdR x0 = r.read_matrix(g + "/x0", {}, 2);
    if (x0.rows() < 1)
      r.fail(g + "/x0", "no points");
    const h5::MatrixXdR u = r.read_matrix(g + "/displacement", x0.rows(), 2);
    for (Eigen::Index i = 0; i < x0.rows(); ++i) {
      wall.x0.emplace_back(x0(i, 0), x0(i, 1));
      wall.displacement.emplace_back(u(i, 0), u(i, 1));
    }
    if (r.exists(g + "/node"))
      wall.nodes = r.read_index_vector(g + "/node", static_cast<std::size_t>(x0.rows()), 0,
                                       std::numeric_limits<std::int64_t>::max());
    out.walls.push_back(std::move(wall));
  }
  return out;
}

}  // namespace tfmb::formats
