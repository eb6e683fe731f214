// The flowmesh kind's one reader and writer: formats/flowmesh.md (schema in
// schema_flowmesh.cpp).
#include "tfmb/formats/flowmesh.hpp"

#include "tfmb/common/h5.hpp"
#include "tfmb/formats/schema.hpp"

namespace tfmb::formats {
namespace {

constexpr const char* kQualityGroup = "/mesh";

void write_optional(h5::Writer& w, const char* name, const std::optional<double>& value) {
  if (value)
    w.set_attr(kQualityGroup, name, *value);
}

std::optional<double> read_optional(const h5::Reader& r, const char* name) {
  if (!r.has_attr(kQualityGroup, name))
    return std::nullopt;
  return r.attr_f64(kQualityGroup, name);
}

}  // namespace

void write_flowmesh(const std::filesystem::path& file, const FlowMesh& flow_mesh,
                    const Provenance& provenance) {
  {
    h5::Writer w(file);
    write_header(w, "flowmesh", flow_mesh.header);
    write_mesh(w, flow_mesh.mesh);
    const MeshQualityReport& q = flow_mesh.quality;
    write_optional(w, "min_angle", q.min_angle);
    write_optional(w, "max_aspect_ratio", q.max_aspect_ratio);
    write_optional(w, "min_cell_area", q.min_cell_area);
    write_optional(w, "estimated_yplus", q.estimated_yplus);
    write_optional(w, "first_layer_height", q.first_layer_height);
    if (q.boundary_layers)
      w.set_attr(kQualityGroup, "boundary_layers", *q.boundary_layers);
    write_provenance(w, provenance);
    w.commit();
  }
  write_xdmf_sidecar(file);
}

FlowMesh read_flowmesh(const std::filesystem::path& file) {
  const h5::Reader r = open_checked(file, "flowmesh");
  FlowMesh out;
  out.source = file;
  out.header = read_header(r);
  out.mesh = read_mesh(r);
  // The schema allows empty cell and boundary tables (every kind shares the mesh block); a flow
  // mesh without them has nothing to solve on and no condition to apply.
  if (out.mesh.cell_count() == 0)
    r.fail("/mesh/cells", "no cells");
  if (out.mesh.boundaries.empty())
    r.fail("/mesh/boundaries", "no boundaries");
  check_boundaries(r, out.mesh, EdgeOrder::domain_on_left);
  MeshQualityReport& q = out.quality;
  q.min_angle = read_optional(r, "min_angle");
  q.max_aspect_ratio = read_optional(r, "max_aspect_ratio");
  q.min_cell_area = read_optional(r, "min_cell_area");
  q.estimated_yplus = read_optional(r, "estimated_yplus");
  q.first_layer_height = read_optional(r, "first_layer_height");
  if (r.has_attr(kQualityGroup, "boundary_layers"))
    q.boundary_layers = r.attr_i64(kQualityGroup, "boundary_layers");
  return out;
}

}  // namespace tfmb::formats
