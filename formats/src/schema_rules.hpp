// Internal: helpers used by the per-kind schema files (schema_<kind>.cpp). Each kind's layout
// lives in its own file so that the owner of a stage can change it (with its version, spec
// formats/<kind>.md, reader/writer and tests) without touching the others.
#pragma once

#include "tfmb/formats/schema.hpp"

namespace tfmb::formats::detail {

using h5::DType;

using h5::DType;

inline DatasetRule f64(std::string path, std::vector<std::string> shape, std::string units,
                std::string meaning, bool required = true) {
  return {std::move(path), DType::float64, std::move(shape), std::move(units), required, "", 0,
          std::move(meaning)};
}

inline DatasetRule i64(std::string path, std::vector<std::string> shape, std::string bound,
                std::string meaning, bool required = true, std::int64_t lower = 0) {
  return {std::move(path), DType::int64, std::move(shape), "1", required, std::move(bound), lower,
          std::move(meaning)};
}

inline DatasetRule str(std::string path, std::vector<std::string> shape, std::string meaning,
                bool required = true) {
  return {std::move(path), DType::string, std::move(shape), "1", required, "", 0,
          std::move(meaning)};
}

inline AttributeRule sattr(std::string object, std::string name, std::string meaning,
                    std::vector<std::string> allowed = {}, bool required = true) {
  AttributeRule rule;
  rule.object_path = std::move(object);
  rule.name = std::move(name);
  rule.type = AttrType::string;
  rule.required = required;
  rule.allowed = std::move(allowed);
  rule.meaning = std::move(meaning);
  return rule;
}

inline AttributeRule nattr(std::string object, std::string name, std::string units, std::string meaning,
                    std::optional<double> minimum = {}, std::optional<double> maximum = {},
                    bool required = true, AttrType type = AttrType::float64) {
  AttributeRule rule;
  rule.object_path = std::move(object);
  rule.name = std::move(name);
  rule.type = type;
  rule.required = required;
  rule.minimum = minimum;
  rule.maximum = maximum;
  rule.units = std::move(units);
  rule.meaning = std::move(meaning);
  return rule;
}

inline void add_root(Schema& s, bool geometric) {
  s.attributes.push_back(sattr("/", "format", "file kind", {s.format}));
  s.attributes.push_back(sattr("/", "format_version", "major.minor; readers refuse another major"));
  s.attributes.push_back(sattr("/", "creator", "program and version that wrote the file"));
  s.attributes.push_back(sattr("/", "created",
                               "UTC time of writing, or 'not recorded' (default, so that identical "
                               "runs give byte-identical files)"));
  if (geometric) {
    s.attributes.push_back(sattr("/", "geometry", "x along the nozzle axis, y transverse",
                                 {"planar", "axisymmetric"}));
    s.attributes.push_back(nattr("/", "depth", "m",
                                 "planar: the depth that per-unit-depth quantities refer to "
                                 "(normally 1); axisymmetric: 1",
                                 0.0, std::nullopt));
  }
}

inline void add_provenance(Schema& s) {
  s.attributes.push_back(sattr("/provenance", "command_line", "command that wrote the file", {}, false));
  s.attributes.push_back(sattr("/provenance", "settings", "resolved settings (TOML text)", {}, false));
  s.datasets.push_back(str("/provenance/input_files", {"K"}, "input files as given", false));
  s.datasets.push_back(str("/provenance/input_sha256", {"K"}, "SHA-256 of each input file", false));
}

inline void add_mesh(Schema& s) {
  s.mesh_bearing = true;
  s.datasets.push_back(f64("/mesh/points", {"N", "2"}, "m", "node coordinates x, y"));
  s.datasets.push_back(i64("/mesh/cells/triangle", {"Nt", "3"}, "N",
                           "0-based node ids, counter-clockwise; global cell id = row"));
  s.datasets.push_back(i64("/mesh/cells/quad", {"Nq", "4"}, "N",
                           "0-based node ids, counter-clockwise; global cell id = Nt + row"));
  s.datasets.push_back(i64("/mesh/topology_xdmf_mixed", {"*"}, "",
                           "derived: XDMF Mixed topology stream (4 = triangle, 5 = quad)", false));
  s.datasets.push_back(i64("/mesh/regions/*", {"*"}, "Nt+Nq", "cell ids of a physical region", false));
  s.datasets.push_back(i64("/mesh/boundaries/*/edges", {"*", "2"}, "N",
                           "boundary edges (node ids), ordered head to tail along the curve"));
  s.attributes.push_back(sattr("/mesh/boundaries/*", "kind", "boundary condition kind",
                               {"inflow", "farfield", "outflow", "wall", "slip_wall", "symmetry",
                                "axis", "solid_inner", "solid_outer", "solid_end"}));
  // A boundary that is a flap's wall names the flap and the side: tfmb-loads and tfmb-heat find
  // a flap's walls by the two together (a wall without them, e.g. the nacelle, is no flap's).
  AttributeRule flap = sattr("/mesh/boundaries/*", "flap",
                             "flap whose wall this is (every wall of a model flap has it: "
                             "tfmb-loads and tfmb-heat find a flap's walls by flap and side)",
                             {}, false);
  flap.required_with = "side";
  s.attributes.push_back(flap);
  AttributeRule side = sattr("/mesh/boundaries/*", "side", "wetted side of the flap",
                             {"inner", "outer", "end"}, false);
  side.required_with = "flap";
  s.attributes.push_back(side);
}

Schema model_schema();
Schema flowmesh_schema();
Schema solidmesh_schema();
Schema flow_schema();
Schema thermal_schema();
Schema material_db_schema();
Schema materials_schema();
Schema loads_schema();
Schema walldisp_schema();
Schema structure_schema();
Schema strain_schema();

}  // namespace tfmb::formats::detail
