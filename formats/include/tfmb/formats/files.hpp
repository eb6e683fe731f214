// Reading and writing tfmb files: the common header and provenance, the mesh block shared by
// every mesh-bearing kind, the XDMF 3 sidecar, and a generic document model used by tfmb-check,
// by tests (round trips of every kind) and by `tfmb-check --example`.
#pragma once

#include <filesystem>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "tfmb/common/h5.hpp"
#include "tfmb/formats/schema.hpp"

namespace tfmb::formats {

struct Header {
  std::string creator;               // e.g. "tfmb-mesh 0.1.0"
  std::string geometry = "planar";   // or "axisymmetric"
  double depth = 1.0;                // [m]
};

// Root attributes format, format_version (the schema's), creator, created, geometry, depth.
// `created` is "not recorded" unless TFMB_RECORD_TIME=1, so identical runs give identical bytes.
void write_header(h5::Writer& file, const std::string& kind, const Header& header);
Header read_header(const h5::Reader& file);

// What a typed reader returns derives from this: the file it was read from, so that a stage's own
// checks on the contents fail with the same located line as the reader's ("file: /path: what").
struct ReadFrom {
  std::filesystem::path source;  // "" if built in memory
  [[noreturn]] void fail(const std::string& object_path, const std::string& what) const;
};

// The item called `name` in a list of named items (flaps, walls, ...), or nullptr.
template <class Named>
const Named* find_named(const std::vector<Named>& items, const std::string& name) {
  for (const Named& item : items)
    if (item.name == name)
      return &item;
  return nullptr;
}

struct Provenance {
  std::string command_line;
  std::string settings;  // resolved settings, TOML text
  std::vector<std::filesystem::path> inputs;
};
void write_provenance(h5::Writer& file, const Provenance& provenance);

struct Boundary {
  h5::MatrixXiR edges;   // (Ne,2) node ids, ordered head to tail
  std::string kind;      // inflow, farfield, outflow, wall, slip_wall, symmetry, axis, solid_*
  std::string flap;      // walls: the flap ("" if none)
  std::string side;      // walls: inner, outer, end ("" if none)
};

struct Mesh {
  h5::MatrixXdR points;     // (N,2) [m]
  h5::MatrixXiR triangles;  // (Nt,3)
  h5::MatrixXiR quads;      // (Nq,4)
  std::map<std::string, std::vector<std::int64_t>> regions;  // cell ids (triangles first)
  std::map<std::string, Boundary> boundaries;

  std::size_t node_count() const { return static_cast<std::size_t>(points.rows()); }
  std::size_t cell_count() const {
    return static_cast<std::size_t>(triangles.rows() + quads.rows());
  }
};

// Writes /mesh (and the derived XDMF topology stream).
void write_mesh(h5::Writer& file, const Mesh& mesh);
// Reads /mesh of a file already validated against its schema; refuses (BadInput, located) a cell
// with a repeated node, a clockwise or collapsed cell and a boundary edge that is no cell edge.
Mesh read_mesh(const h5::Reader& file);
// How a mesh kind orders its boundary edges: a flow domain's run with the domain on their left
// (flowmesh.md; a boundary may be several chains), a solid mesh's each as one head-to-tail chain
// (solidmesh.md: inner and outer from the flap's start to its end).
enum class EdgeOrder { domain_on_left, one_chain };
// The rules of a mesh's named boundaries: every boundary edge is ordered as `order` says, lies
// on the mesh's boundary (one cell) and is in one boundary only, and every boundary edge of the
// mesh is in a boundary (a missing edge left a gap the solvers took as a wall without
// condition). BadInput, located, otherwise.
void check_boundaries(const h5::Reader& file, const Mesh& mesh, EdgeOrder order);

// Writes "<file minus .h5>.xdmf" next to a committed file that has something to draw, for
// ParaView (formats/README.md, "XDMF sidecars"): a Uniform grid with Mixed topology for a /mesh
// (triangles and quads) or Polyline topology for /beam/points and /beam/segments (structure), with
// every /fields/point/* as a Node attribute and /fields/cell/* as a Cell attribute; a dataset
// whose columns mix units (structure's sectional_strain, sectional_force) as one scalar attribute
// per column named "<component> [<unit>]" (HyperSlabs of the same dataset); and a polyline grid
// per group of ordered points: flow wall traces (/walls/*/x, y), walldisp walls (/walls/*/x0),
// loads and strain flaps (/flaps/*/position), with the group's datasets as Node attributes.
// Several grids form a Spatial collection. Where that is more than meshio 7 reads (one Uniform
// grid of whole datasets), "<file minus .h5>.meshio.xdmf" is written beside it with the mesh or
// beam grid and its datasets as stored. Returns the sidecar path, or an empty path (and writes
// nothing) for a file with nothing to draw.
std::filesystem::path write_xdmf_sidecar(const std::filesystem::path& h5_file);
// "<file minus .h5>.meshio.xdmf".
std::filesystem::path meshio_sidecar_path(const std::filesystem::path& h5_file);
// Writes `output`, a Temporal collection over the files (e.g. the iterates of a two-way run), each
// the grids its sidecar has, at time 1, 2, ... in the order given, referencing the files by paths
// relative to `output`'s folder. BadInput if a file has nothing to draw.
std::filesystem::path write_xdmf_series(const std::filesystem::path& output,
                                        const std::vector<std::filesystem::path>& h5_files);

// Generic in-memory image of a file: every group, dataset and attribute.
struct AttributeValue {
  AttrType type = AttrType::string;
  std::string text;
  double number = 0.0;
  std::int64_t integer = 0;
  std::vector<double> numbers;
  bool operator==(const AttributeValue&) const = default;
};

struct DatasetValue {
  h5::DType dtype = h5::DType::float64;
  std::vector<std::size_t> shape;
  std::vector<double> floats;
  std::vector<std::int64_t> integers;
  std::vector<std::string> strings;
  bool operator==(const DatasetValue&) const = default;
};

struct Document {
  std::set<std::string> groups;
  std::map<std::string, DatasetValue> datasets;
  std::map<std::string, std::map<std::string, AttributeValue>> attributes;  // object -> name -> value
  bool operator==(const Document&) const = default;
};

// Reads everything (no schema check beyond "finite floats").
Document read_document(const h5::Reader& file);
// Writes a document atomically (units attributes are taken from the document).
void write_document(const Document& document, const std::filesystem::path& file);
// A small valid document of a kind: what tfmb-check --example writes and the tests corrupt.
Document example_document(const Schema& schema);

}  // namespace tfmb::formats
