// The solidmesh kind's one reader and writer: formats/solidmesh.md (schema in
// schema_solidmesh.cpp).
#include "tfmb/formats/solidmesh.hpp"

#include <algorithm>
#include <limits>

#include "tfmb/common/h5.hpp"
#include "tfmb/formats/schema.hpp"

namespace tfmb::formats {

void write_solidmesh(const std::filesystem::path& file, const SolidMesh& solid,
                     const Provenance& provenance) {
  {
    h5::Writer w(file);
    write_header(w, "solidmesh", solid.header);
    write_mesh(w, solid.mesh);
    w.write_strings("/link/flap_names", solid.flap_names, "flap names, indexed by cell_flap");
    w.write("/link/cell_flap", solid.cell_flap, "1", "flap index of each cell");
    w.write("/link/cell_element", solid.cell_element, "1",
            "beam element (within its flap) of each cell");
    w.write("/link/point_thickness_coordinate", solid.point_thickness_coordinate, "m",
            "signed distance from the reference line, positive towards the outer wall");
    write_provenance(w, provenance);
    w.commit();
  }
  write_xdmf_sidecar(file);
}

SolidMesh read_solidmesh(const std::filesystem::path& file) {
  const h5::Reader r = open_checked(file, "solidmesh");
  SolidMesh solid;
  solid.source = file;
  solid.header = read_header(r);
  solid.mesh = read_mesh(r);
  check_boundaries(r, solid.mesh, EdgeOrder::one_chain);
  const std::size_t cells = solid.mesh.cell_count();
  solid.flap_names = r.read_strings("/link/flap_names");
  if (solid.flap_names.empty())
    r.fail("/link/flap_names", "no flaps");
  solid.cell_flap = r.read_index_vector("/link/cell_flap", cells, 0,
                                        static_cast<std::int64_t>(solid.flap_names.size()));
  solid.cell_element =
      r.read_index_vector("/link/cell_element", cells, 0, std::numeric_limits<std::int64_t>::max());
  solid.point_thickness_coordinate =
      r.read_vector("/link/point_thickness_coordinate", solid.mesh.node_count());
  // The wall has a thickness: its nodes lie on both sides of the reference line. All zero (or
  // all of one sign) would make every through-thickness temperature difference zero.
  double lowest = 0.0, highest = 0.0;
  for (double z : solid.point_thickness_coordinate) {
    lowest = std::min(lowest, z);
    highest = std::max(highest, z);
  }
  if (!(lowest < 0.0 && highest > 0.0))
    r.fail("/link/point_thickness_coordinate", "does not span the wall thickness (from " +
                                                   std::to_string(lowest) + " to " +
                                                   std::to_string(highest) + " m)");
  return solid;
}

}  // namespace tfmb::formats
