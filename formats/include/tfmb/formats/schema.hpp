// The file contract in code: one Schema per file kind (formats/<kind>.md is its prose spec; the
// table in each spec is printed from these schemas by `tfmb-check --spec <kind>`, and a test
// keeps the two identical).
//
// A schema lists the attributes and datasets of a kind. Paths may contain "*" segments that
// match any child name (e.g. "/mesh/boundaries/*/edges"). Shapes are lists of extents: a number
// ("2"), a symbol ("N") bound at its first appearance and checked at every later one, a sum of
// bound symbols ("Nt+Nq"), "*" (any extent) or "?" (an optional last dimension of any extent, so
// "(N,)" and "(N,k)" both pass). Symbols starting with a lower-case letter are local to the names
// matched by the wildcards of the path (each wall trace has its own "n").
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "tfmb/common/h5.hpp"

namespace tfmb::formats {

enum class AttrType { string, float64, int64, float64_vector };

struct AttributeRule {
  std::string object_path;  // may contain "*"
  std::string name;
  AttrType type = AttrType::string;
  bool required = true;
  // Not required on its own, but on every object that has this other attribute (e.g. a
  // boundary's `side` wherever it names a `flap`, and the reverse).
  std::string required_with;
  std::vector<std::string> allowed;    // for strings: allowed values (empty: any)
  std::optional<double> minimum;       // for numbers: inclusive bounds
  std::optional<double> maximum;
  std::string units;                   // for numbers
  std::string meaning;
};

struct DatasetRule {
  std::string path;  // may contain "*"
  h5::DType dtype = h5::DType::float64;
  std::vector<std::string> shape;
  std::string units;  // required value of the "units" attribute; "*" = any (still required)
  bool required = true;
  // int64 only: values must lie in [index_lower, bound) where bound is this shape expression.
  std::string index_bound;
  std::int64_t index_lower = 0;
  std::string meaning;
};

struct Schema {
  std::string kind;            // e.g. "flowmesh"
  std::string format;          // root attribute "format", e.g. "tfmb/flowmesh"
  int major = 1;
  int minor = 0;
  std::string summary;         // one line: what the file holds
  bool mesh_bearing = false;   // has /mesh and gets an XDMF sidecar
  std::vector<AttributeRule> attributes;
  std::vector<DatasetRule> datasets;

  std::string version() const { return std::to_string(major) + "." + std::to_string(minor); }
};

// All kinds this build knows, in pipeline order.
const std::vector<Schema>& all_schemas();
// The schema of a kind by name ("flowmesh") or format string ("tfmb/flowmesh"); nullptr if none.
const Schema* find_schema(const std::string& kind_or_format);
// The schema of an open file, by its root `format` attribute; BadInput "<file>: /: ..." when the
// attribute is missing (not a tfmb file) or names no kind of this build.
const Schema& schema_of(const h5::Reader& file);

struct Problem {
  std::string object_path;
  std::string message;
};

// Validates an open file against a schema. With stop_at_first, returns after the first problem
// (what readers use); tfmb-check collects them all. Checks: format and major version, required
// attributes and their types/values, required datasets, dtype, shape and symbol consistency,
// units attribute, finite floats, index ranges. A file HDF5 cannot read throws h5::DamagedFile
// (a BadInput) at the first damage instead: what follows it would be its consequences.
std::vector<Problem> validate(const h5::Reader& file, const Schema& schema,
                              bool stop_at_first = false);

// Opens `file`, checks it is the expected kind and valid; throws BadInput
// "<file>: <path>: <message>" at the first problem. Returns the open reader.
h5::Reader open_checked(const std::filesystem::path& file, const std::string& kind);

// The Markdown table of a schema (group/dataset, dtype, shape, units, meaning).
std::string markdown_table(const Schema& schema);

}  // namespace tfmb::formats
