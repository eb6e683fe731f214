#include "tfmb/formats/files.hpp"

#include <cstdlib>
#include <ctime>
#include <functional>
#include <sstream>
#include <unordered_map>
#include <unordered_set>

#include "tfmb/common/errors.hpp"
#include "tfmb/common/hash.hpp"

namespace tfmb::formats {

void ReadFrom::fail(const std::string& object_path, const std::string& what) const {
  throw BadInput(source.string() + ": " + object_path + ": " + what);
}

void write_header(h5::Writer& file, const std::string& kind, const Header& header) {
  const Schema* schema = find_schema(kind);
  if (!schema) throw InternalError("write_header: unknown file kind '" + kind + "'");
  file.set_attr("/", "format", schema->format);
  file.set_attr("/", "format_version", schema->version());
  file.set_attr("/", "creator", header.creator);
  std::string created = "not recorded";
  if (const char* record = std::getenv("TFMB_RECORD_TIME"); record && std::string(record) == "1") {
    const std::time_t now = std::time(nullptr);
    char text[32];
    std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
    created = text;
  }
  file.set_attr("/", "created", created);
  bool geometric = false;
  for (const auto& rule : schema->attributes) geometric |= rule.object_path == "/" && rule.name == "geometry";
  if (geometric) {
    file.set_attr("/", "geometry", header.geometry);
    file.set_attr("/", "depth", header.depth);
  }
}

Header read_header(const h5::Reader& file) {
  Header header;
  header.creator = file.attr_string("/", "creator");
  if (file.has_attr("/", "geometry")) header.geometry = file.attr_string("/", "geometry");
  if (file.has_attr("/", "depth")) header.depth = file.attr_f64("/", "depth");
  return header;
}

void write_provenance(h5::Writer& file, const Provenance& provenance) {
  file.create_group("/provenance");
  file.set_attr("/provenance", "command_line", provenance.command_line);
  file.set_attr("/provenance", "settings", provenance.settings);
  std::vector<std::string> names, hashes;
  for (const auto& input : provenance.inputs) {
    names.push_back(input.string());
    hashes.push_back(sha256_file(input));
  }
  file.write_strings("/provenance/input_files", names, "input files as given");
  file.write_strings("/provenance/input_sha256", hashes, "SHA-256 of each input file");
}

namespace {
std::vector<std::int64_t> xdmf_mixed_topology(const Mesh& mesh) {
  std::vector<std::int64_t> stream;
  stream.reserve(static_cast<std::size_t>(4 * mesh.triangles.rows() + 5 * mesh.quads.rows()));
  for (Eigen::Index c = 0; c < mesh.triangles.rows(); ++c) {
    stream.push_back(4);  // XDMF Mixed code of a triangle
    for (int k = 0; k < 3; ++k) stream.push_back(mesh.triangles(c, k));
  }
  for (Eigen::Index c = 0; c < mesh.quads.rows(); ++c) {
    stream.push_back(5);  // XDMF Mixed code of a quadrilateral
    for (int k = 0; k < 4; ++k) stream.push_back(mesh.quads(c, k));
  }
  return stream;
}
}  // namespace

void write_mesh(h5::Writer& file, const Mesh& mesh) {
  h5::MatrixXiR triangles = mesh.triangles.rows() ? mesh.triangles : h5::MatrixXiR(0, 3);
  h5::MatrixXiR quads = mesh.quads.rows() ? mesh.quads : h5::MatrixXiR(0, 4);
  file.write("/mesh/points", mesh.points, "m", "node coordinates x, y");
  file.write("/mesh/cells/triangle", triangles, "1", "node ids, counter-clockwise");
  file.write("/mesh/cells/quad", quads, "1", "node ids, counter-clockwise");
  file.write("/mesh/topology_xdmf_mixed", xdmf_mixed_topology(mesh), "1",
             "derived: XDMF Mixed topology stream for the sidecar");
  file.create_group("/mesh/regions");
  for (const auto& [name, cells] : mesh.regions) file.write("/mesh/regions/" + name, cells, "1");
  file.create_group("/mesh/boundaries");
  for (const auto& [name, boundary] : mesh.boundaries) {
    const std::string group = "/mesh/boundaries/" + name;
    h5::MatrixXiR edges = boundary.edges.rows() ? boundary.edges : h5::MatrixXiR(0, 2);
    file.write(group + "/edges", edges, "1", "node ids, ordered along the curve");
    file.set_attr(group, "kind", boundary.kind);
    if (!boundary.flap.empty()) file.set_attr(group, "flap", boundary.flap);
    if (!boundary.side.empty()) file.set_attr(group, "side", boundary.side);
  }
}

namespace {

std::uint64_t edge_key(std::int64_t from, std::int64_t to) {
  return (static_cast<std::uint64_t>(from) << 32) ^ static_cast<std::uint64_t>(to);
}

// Every cell's nodes distinct and counter-clockwise, its area positive (the specs' cell tables
// say so). A repeated node or a clockwise cell (two nodes swapped) passed the index checks and
// changed the flow silently: the median-dual areas take the magnitude of a signed area, the
// heat FE Jacobians its sign.
void check_cells(const h5::Reader& file, const h5::MatrixXiR& cells, const h5::MatrixXdR& points,
                 const std::string& path) {
  const Eigen::Index k = cells.cols();
  for (Eigen::Index c = 0; c < cells.rows(); ++c) {
    double twice_area = 0.0;
    for (Eigen::Index i = 0; i < k; ++i) {
      const std::int64_t a = cells(c, i);
      const std::int64_t b = cells(c, (i + 1) % k);
      for (Eigen::Index j = i + 1; j < k; ++j) {
        if (cells(c, j) == a)
          file.fail(path, "cell row " + std::to_string(c) + " repeats node " + std::to_string(a) +
                              " (a degenerate cell)");
      }
      twice_area += points(a, 0) * points(b, 1) - points(b, 0) * points(a, 1);
    }
    if (!(twice_area > 0.0)) {
      std::ostringstream what;
      what << "cell row " << c << " is " << (twice_area < 0.0 ? "clockwise" : "collapsed")
           << " (signed area " << 0.5 * twice_area << " m^2); cells are counter-clockwise";
      file.fail(path, what.str());
    }
  }
}

// The directed edges of the cells (each cell's nodes in their counter-clockwise order), each
// with the number of cells it belongs to as an undirected edge.
struct CellEdges {
  std::unordered_set<std::uint64_t> directed;
  std::unordered_map<std::uint64_t, int> undirected;
};

CellEdges cell_edges(const Mesh& mesh) {
  CellEdges edges;
  auto add = [&](const h5::MatrixXiR& cells) {
    const Eigen::Index k = cells.cols();
    for (Eigen::Index c = 0; c < cells.rows(); ++c) {
      for (Eigen::Index i = 0; i < k; ++i) {
        const std::int64_t a = cells(c, i);
        const std::int64_t b = cells(c, (i + 1) % k);
        edges.directed.insert(edge_key(a, b));
        ++edges.undirected[edge_key(std::min(a, b), std::max(a, b))];
      }
    }
  };
  add(mesh.triangles);
  add(mesh.quads);
  return edges;
}

std::string edge_text(const h5::MatrixXiR& edges, Eigen::Index row) {
  return "edge row " + std::to_string(row) + " (" + std::to_string(edges(row, 0)) + ", " +
         std::to_string(edges(row, 1)) + ")";
}

}  // namespace

void check_boundaries(const h5::Reader& file, const Mesh& mesh, EdgeOrder order) {
  const CellEdges edges = cell_edges(mesh);
  std::unordered_set<std::uint64_t> named;
  for (const auto& [name, boundary] : mesh.boundaries) {
    const std::string path = "/mesh/boundaries/" + name + "/edges";
    for (Eigen::Index e = 0; e < boundary.edges.rows(); ++e) {
      const std::int64_t a = boundary.edges(e, 0);
      const std::int64_t b = boundary.edges(e, 1);
      if (order == EdgeOrder::domain_on_left && !edges.directed.count(edge_key(a, b)))
        file.fail(path, edge_text(boundary.edges, e) +
                            " does not run with the domain on its left (as the counter-clockwise "
                            "cell beside it gives it)");
      if (order == EdgeOrder::one_chain && e > 0 && boundary.edges(e - 1, 1) != a)
        file.fail(path, edge_text(boundary.edges, e) + " does not start where edge row " +
                            std::to_string(e - 1) + " ends (edges run head to tail)");
      const auto key = edge_key(std::min(a, b), std::max(a, b));
      if (const auto it = edges.undirected.find(key);
          it == edges.undirected.end() || it->second != 1)
        file.fail(path,
                  edge_text(boundary.edges, e) + " is an inner edge, not on the mesh's boundary");
      if (!named.insert(key).second)
        file.fail(path, edge_text(boundary.edges, e) + " is in a boundary already");
    }
  }
  for (const auto& [key, count] : edges.undirected) {
    if (count == 1 && !named.count(key)) {
      file.fail("/mesh/boundaries", "the mesh's boundary edge (" + std::to_string(key >> 32) +
                                        ", " + std::to_string(key & 0xffffffffu) +
                                        ") is in no boundary; every boundary edge needs one (its "
                                        "condition comes from the boundary's kind)");
    }
  }
}

Mesh read_mesh(const h5::Reader& file) {
  Mesh mesh;
  mesh.points = file.read_matrix("/mesh/points", {}, 2);
  const auto n = static_cast<std::int64_t>(mesh.points.rows());
  mesh.triangles = file.read_index_matrix("/mesh/cells/triangle", {}, 3, 0, n);
  mesh.quads = file.read_index_matrix("/mesh/cells/quad", {}, 4, 0, n);
  const auto cells = static_cast<std::int64_t>(mesh.cell_count());
  if (file.is_group("/mesh/regions")) {
    for (const auto& name : file.children("/mesh/regions")) {
      mesh.regions[name] = file.read_index_vector("/mesh/regions/" + name, {}, 0, cells);
    }
  }
  // The schema makes boundaries optional (a mesh of one region may have none named).
  const std::vector<std::string> boundary_names = file.is_group("/mesh/boundaries")
                                                      ? file.children("/mesh/boundaries")
                                                      : std::vector<std::string>{};
  for (const auto& name : boundary_names) {
    const std::string group = "/mesh/boundaries/" + name;
    Boundary boundary;
    boundary.edges = file.read_index_matrix(group + "/edges", {}, 2, 0, n);
    boundary.kind = file.attr_string(group, "kind");
    if (file.has_attr(group, "flap")) boundary.flap = file.attr_string(group, "flap");
    if (file.has_attr(group, "side")) boundary.side = file.attr_string(group, "side");
    mesh.boundaries[name] = std::move(boundary);
  }
  check_cells(file, mesh.triangles, mesh.points, "/mesh/cells/triangle");
  check_cells(file, mesh.quads, mesh.points, "/mesh/cells/quad");
  // A boundary's edges are edges of cells with distinct nodes: a repeated node or an edge
  // between two nodes no cell joins (an index changed in place) was taken as a wall piece.
  const CellEdges edges = cell_edges(mesh);
  for (const auto& [name, boundary] : mesh.boundaries) {
    for (Eigen::Index e = 0; e < boundary.edges.rows(); ++e) {
      const std::int64_t a = boundary.edges(e, 0);
      const std::int64_t b = boundary.edges(e, 1);
      if (!edges.undirected.count(edge_key(std::min(a, b), std::max(a, b))))
        file.fail("/mesh/boundaries/" + name + "/edges",
                  edge_text(boundary.edges, e) + " is not an edge of a cell");
    }
  }
  return mesh;
}

// ---------------------------------------------------------------------------------------------
// Generic documents

Document read_document(const h5::Reader& file) {
  Document document;
  std::function<void(const std::string&)> visit = [&](const std::string& object) {
    for (const auto& name : file.attr_names(object)) {
      AttributeValue value;
      switch (file.attr_dtype(object, name)) {
        case h5::DType::string:
          value.type = AttrType::string;
          value.text = file.attr_string(object, name);
          break;
        case h5::DType::int64:
          value.type = AttrType::int64;
          value.integer = file.attr_i64(object, name);
          break;
        case h5::DType::float64:
          if (file.attr_size(object, name) == 1) {
            value.type = AttrType::float64;
            value.number = file.attr_f64(object, name);
          } else {
            value.type = AttrType::float64_vector;
            value.numbers = file.attr_f64_vector(object, name);
          }
          break;
        default: file.fail(object, "attribute '" + name + "' has an unsupported dtype");
      }
      document.attributes[object][name] = value;
    }
    if (file.is_dataset(object)) {
      const auto info = file.info(object);
      DatasetValue value;
      value.dtype = info.dtype;
      switch (info.dtype) {
        case h5::DType::float64: value.floats = file.read_f64(object, &value.shape); break;
        case h5::DType::int64: value.integers = file.read_i64(object, &value.shape); break;
        case h5::DType::string:
          value.strings = file.read_strings(object);
          value.shape = info.shape;
          break;
        default: file.fail(object, "unsupported dtype " + info.dtype_name);
      }
      document.datasets[object] = std::move(value);
      return;
    }
    document.groups.insert(object);
    for (const auto& child : file.children(object)) {
      visit(object == "/" ? "/" + child : object + "/" + child);
    }
  };
  visit("/");
  return document;
}

void write_document(const Document& document, const std::filesystem::path& path) {
  h5::Writer file(path);
  for (const auto& group : document.groups) file.create_group(group);
  for (const auto& [object, value] : document.datasets) {
    std::string units = "1";
    if (auto it = document.attributes.find(object); it != document.attributes.end()) {
      if (auto u = it->second.find("units"); u != it->second.end()) units = u->second.text;
    }
    switch (value.dtype) {
      case h5::DType::float64: file.write_array(object, value.floats, value.shape, units); break;
      case h5::DType::int64: file.write_array(object, value.integers, value.shape, units); break;
      case h5::DType::string: file.write_strings(object, value.strings); break;
      default: throw InternalError(object + ": unsupported dtype");
    }
  }
  for (const auto& [object, attributes] : document.attributes) {
    for (const auto& [name, value] : attributes) {
      switch (value.type) {
        case AttrType::string: file.set_attr(object, name, value.text); break;
        case AttrType::float64: file.set_attr(object, name, value.number); break;
        case AttrType::int64: file.set_attr(object, name, value.integer); break;
        case AttrType::float64_vector: file.set_attr(object, name, value.numbers); break;
      }
    }
  }
  file.commit();
}

namespace {
std::string concrete(const std::string& pattern) {
  std::string path = pattern;
  for (std::size_t pos; (pos = path.find('*')) != std::string::npos;) path.replace(pos, 1, "sample");
  return path;
}
}  // namespace

Document example_document(const Schema& schema) {
  Document document;
  document.groups.insert("/");
  std::map<std::string, std::size_t> symbols;
  // A mesh-bearing example holds a real mesh (below): a 3 x 2 grid of nodes, one quad and two
  // triangles, so that it meets the topology rules read_mesh and check_boundaries apply.
  if (schema.mesh_bearing)
    symbols = {{"N", 6}, {"Nt", 2}, {"Nq", 1}};
  auto extent = [&](const std::string& expression) -> std::size_t {
    if (expression == "*") return 3;
    std::size_t total = 0;
    std::stringstream stream(expression);
    std::string term;
    while (std::getline(stream, term, '+')) {
      if (!term.empty() && std::isdigit(static_cast<unsigned char>(term[0]))) {
        total += std::stoull(term);
      } else {
        total += symbols.emplace(term, 4).first->second;
      }
    }
    return total;
  };
  for (const AttributeRule& rule : schema.attributes) {
    const std::string object = concrete(rule.object_path);
    if (!document.datasets.count(object)) document.groups.insert(object);
    AttributeValue value;
    value.type = rule.type;
    switch (rule.type) {
      case AttrType::string:
        value.text = rule.allowed.empty() ? "sample" : rule.allowed.front();
        if (rule.name == "format_version") value.text = schema.version();
        break;
      case AttrType::float64:
      case AttrType::int64: {
        double number = 1.0;
        if (rule.minimum && rule.maximum) number = 0.5 * (*rule.minimum + *rule.maximum);
        else if (rule.minimum) number = *rule.minimum + 1.0;
        else if (rule.maximum) number = *rule.maximum - 1.0;
        if (rule.type == AttrType::int64) {
          value.integer = static_cast<std::int64_t>(number);
        } else {
          value.number = number;
        }
        break;
      }
      case AttrType::float64_vector: value.numbers = {1.0, 2.0, 3.0}; break;
    }
    document.attributes[object][rule.name] = value;
  }
  for (const DatasetRule& rule : schema.datasets) {
    const std::string path = concrete(rule.path);
    DatasetValue value;
    value.dtype = rule.dtype;
    for (const auto& e : rule.shape) {
      if (e != "?") value.shape.push_back(extent(e));
    }
    std::size_t count = 1;
    for (auto d : value.shape) count *= d;
    if (rule.dtype == h5::DType::float64) {
      for (std::size_t i = 0; i < count; ++i) value.floats.push_back(0.5 + 0.25 * static_cast<double>(i));
    } else if (rule.dtype == h5::DType::int64) {
      const std::size_t bound = rule.index_bound.empty() ? 1000 : extent(rule.index_bound);
      for (std::size_t i = 0; i < count; ++i) {
        value.integers.push_back(rule.index_lower + static_cast<std::int64_t>(i % bound));
      }
    } else {
      for (std::size_t i = 0; i < count; ++i) value.strings.push_back("sample" + std::to_string(i));
    }
    document.groups.erase(path);
    document.datasets[path] = value;
    AttributeValue units;
    units.text = rule.units == "*" ? "1" : rule.units;
    document.attributes[path]["units"] = units;
  }
  // Parent groups of every object.
  std::set<std::string> parents;
  auto add_parents = [&](const std::string& path) {
    for (std::size_t pos = path.find('/', 1); pos != std::string::npos; pos = path.find('/', pos + 1)) {
      parents.insert(path.substr(0, pos));
    }
  };
  for (const auto& [path, value] : document.datasets) add_parents(path);
  for (const auto& group : document.groups) add_parents(group);
  document.groups.insert(parents.begin(), parents.end());
  // A mesh-bearing example gets the grid above, counter-clockwise cells, one boundary running
  // round it with the domain on its left, and a consistent XDMF topology stream.
  if (schema.mesh_bearing) {
    //  3 --- 4 --- 5
    //  |  q  | t1 /|
    //  |     |  / t0
    //  0 --- 1 --- 2
    auto& points = document.datasets["/mesh/points"];
    points.floats = {0.0, 0.0, 0.1, 0.0, 0.2, 0.0, 0.0, 0.1, 0.1, 0.1, 0.2, 0.1};
    auto& tri = document.datasets["/mesh/cells/triangle"];
    tri.integers = {1, 2, 5, 1, 5, 4};
    auto& quad = document.datasets["/mesh/cells/quad"];
    quad.integers = {0, 1, 4, 3};
    for (auto& [path, value] : document.datasets) {
      if (path.starts_with("/mesh/boundaries/") && path.ends_with("/edges")) {
        value.integers = {0, 1, 1, 2, 2, 5, 5, 4, 4, 3, 3, 0};
        value.shape = {6, 2};
      }
    }
    Mesh mesh;
    mesh.triangles = Eigen::Map<const h5::MatrixXiR>(tri.integers.data(), static_cast<Eigen::Index>(tri.shape[0]), 3);
    mesh.quads = Eigen::Map<const h5::MatrixXiR>(quad.integers.data(), static_cast<Eigen::Index>(quad.shape[0]), 4);
    auto& topology = document.datasets["/mesh/topology_xdmf_mixed"];
    topology.integers = xdmf_mixed_topology(mesh);
    topology.shape = {topology.integers.size()};
  }
  // A loads example's beam nodes lie on a straight line at their arc lengths, as the loads
  // reader requires of s and position.
  if (schema.kind == "loads") {
    for (auto& [path, value] : document.datasets) {
      if (!path.ends_with("/position"))
        continue;
      const auto s = document.datasets.find(path.substr(0, path.size() - 9) + "/s");
      if (s == document.datasets.end())
        continue;
      value.floats.assign(2 * s->second.floats.size(), 0.0);
      for (std::size_t i = 0; i < s->second.floats.size(); ++i)
        value.floats[2 * i] = s->second.floats[i];
    }
  }
  return document;
}

}  // namespace tfmb::formats
