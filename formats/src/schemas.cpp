// The list of every file kind this build knows, in pipeline order. Each kind's layout is in
// schema_<kind>.cpp; changing one means: bump its version, update formats/<kind>.md (the table
// there is `tfmb-check --spec <kind>`), its reader/writer and tests.
#include "schema_rules.hpp"

namespace tfmb::formats {

const std::vector<Schema>& all_schemas() {
  static const std::vector<Schema> schemas = {
      detail::model_schema(),
      detail::flowmesh_schema(),
      detail::solidmesh_schema(),
      detail::flow_schema(),
      detail::thermal_schema(),
      detail::material_db_schema(),
      detail::materials_schema(),
      detail::loads_schema(),
      detail::walldisp_schema(),
      detail::structure_schema(),
      detail::strain_schema(),
};
  return schemas;
}

}  // namespace tfmb::formats
