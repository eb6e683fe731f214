// XDMF 3 sidecars of tfmb files (formats/README.md, "XDMF sidecars"): the grids a file holds,
// written as XML that references the file's datasets, so ParaView (and meshio, for the one-grid
// variant) open the file without project code and the HDF5 layout stays the contract.
#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <iomanip>
#include <map>
#include <sstream>

#include "tfmb/common/errors.hpp"
#include "tfmb/common/text_file.hpp"
#include "tfmb/formats/files.hpp"

namespace tfmb::formats {
namespace {

// File names and dataset names are free text (a run directory named "R&D", a field written by
// an external tool): copied as they stand, `&` or `<` made the sidecar ill-formed XML, which
// every XML parser (meshio's, ParaView's) refuses. Escaped, the parser hands back the exact name.
std::string xml_escape(const std::string& text) {
  std::string escaped;
  escaped.reserve(text.size());
  for (char c : text) {
    switch (c) {
      case '&':
        escaped += "&amp;";
        break;
      case '<':
        escaped += "&lt;";
        break;
      case '>':
        escaped += "&gt;";
        break;
      case '"':
        escaped += "&quot;";
        break;
      case '\'':
        escaped += "&apos;";
        break;
      default:
        escaped += c;
    }
  }
  return escaped;
}

struct Component {
  const char* name;
  const char* unit;
};

// Datasets on a grid whose columns carry different units (structure.md; order of model.md's
// section stiffness: axial, shear 2 in plane, shear 3, torsion, bending 2 out of plane, bending 3
// in plane). Shown whole, ParaView labels the six columns XX..XZ as one tensor and its colour map
// and range mix strains with curvatures and forces with moments; each column becomes its own
// scalar array with its unit in its name instead.
const std::map<std::string, std::vector<Component>>& split_datasets() {
  static const std::map<std::string, std::vector<Component>> table = {
      {"/fields/cell/sectional_strain",
       {{"axial_strain", "1"},
        {"shear_strain", "1"},
        {"shear_strain_out_of_plane", "1"},
        {"twist", "1/m"},
        {"curvature_out_of_plane", "1/m"},
        {"curvature", "1/m"}}},
      {"/fields/cell/sectional_force",
       {{"axial_force", "N"},
        {"shear_force", "N"},
        {"shear_force_out_of_plane", "N"},
        {"torque", "N m"},
        {"bending_moment_out_of_plane", "N m"},
        {"bending_moment", "N m"}}},
  };
  return table;
}

enum class Reader {
  paraview,  // everything: split components, line grids, collections
  meshio,    // meshio 7's subset: one Uniform grid of whole datasets
};

// Builds the grids of one file. `data_file` is how the XML names the file (relative to the
// sidecar).
class GridWriter {
 public:
  GridWriter(const h5::Reader& file, std::string data_file, Reader reader)
      : file_(file), data_file_(xml_escape(data_file)), reader_(reader) {}

  // The grids of the file, each a complete <Grid> element; the file's main grid is `name`.
  std::vector<std::string> grids(const std::string& name);
  bool used_beyond_meshio() const { return beyond_meshio_; }

 private:
  std::string item(const std::string& path, const std::vector<std::size_t>& dimensions,
                   const char* type) const {
    std::string text = "<DataItem Dimensions=\"" + dims(dimensions) + "\" NumberType=\"" + type +
                       "\" Precision=\"8\" Format=\"HDF\">" + data_file_ + ":" + xml_escape(path) +
                       "</DataItem>";
    return text;
  }
  static std::string dims(const std::vector<std::size_t>& dimensions) {
    std::string text;
    for (std::size_t d : dimensions)
      text += (text.empty() ? "" : " ") + std::to_string(d);
    return text;
  }
  void attributes(std::ostringstream& xml, const std::string& group, const char* center,
                  std::size_t rows, const std::vector<std::string>& skip = {});
  std::string mesh_grid(const std::string& name);
  std::string beam_grid(const std::string& name);
  // A polyline through the rows of `group`'s coordinates (one (n,2) dataset, or x and y), with
  // every float64 and int64 dataset of n rows of the group as a Node attribute.
  std::string line_grid(const std::string& name, const std::string& group,
                        const std::vector<std::string>& coordinates);
  // A mesh boundary (rows of two point ids into `points`) as its own polyline grid named after
  // it, with the mesh point id of each of its nodes as `node`.
  std::string boundary_grid(const std::string& name, const h5::MatrixXiR& edges,
                            const h5::MatrixXdR& points);

  const h5::Reader& file_;
  std::string data_file_;
  Reader reader_;
  bool beyond_meshio_ = false;
};

void GridWriter::attributes(std::ostringstream& xml, const std::string& group, const char* center,
                            std::size_t rows, const std::vector<std::string>& skip) {
  if (!file_.is_group(group))
    return;
  for (const auto& name : file_.children(group)) {
    if (std::find(skip.begin(), skip.end(), name) != skip.end())
      continue;
    const std::string path = group + "/" + name;
    if (!file_.is_dataset(path))
      continue;
    const auto info = file_.info(path);
    const bool integer = info.dtype == h5::DType::int64;
    if ((info.dtype != h5::DType::float64 && !integer) || info.shape.empty() ||
        info.shape[0] != rows || info.shape.size() > 2 || (integer && info.shape.size() != 1)) {
      continue;  // not displayable on this grid (e.g. a history)
    }
    const std::size_t components = info.shape.size() == 2 ? info.shape[1] : 1;
    const auto split = split_datasets().find(path);
    if (reader_ == Reader::paraview && split != split_datasets().end() &&
        split->second.size() == components) {
      // Column k of the (rows, components) dataset, as the XDMF 3 library's hyperslab of a
      // heavy-data reference: "file:path|start:stride:count:dataspace", here start (0 k),
      // stride (1 1), count (rows 1) of (rows components). ParaView 5.11 reads no attribute
      // made of an ItemType="HyperSlab" or "Function" item (it skips it as of type None).
      beyond_meshio_ = true;
      for (std::size_t k = 0; k < components; ++k) {
        const Component& c = split->second[k];
        xml << "      <Attribute Name=\"" << xml_escape(std::string(c.name) + " [" + c.unit + "]")
            << "\" AttributeType=\"Scalar\" Center=\"" << center << "\">\n"
            << "        <DataItem Dimensions=\"" << rows
            << "\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">" << data_file_ << ":"
            << xml_escape(path) << "|0 " << k << ":1 1:" << rows << " 1:" << rows << " "
            << components << "</DataItem>\n      </Attribute>\n";
      }
      continue;
    }
    // Two columns are a planar vector (a wall normal, a wall displacement): ParaView shows its
    // magnitude and components; three are a vector for Warp By Vector.
    const char* type = components == 1 ? "Scalar" : components <= 3 ? "Vector" : "Matrix";
    xml << "      <Attribute Name=\"" << xml_escape(name) << "\" AttributeType=\"" << type
        << "\" Center=\"" << center << "\">\n        "
        << item(path, info.shape, integer ? "Int" : "Float") << "\n      </Attribute>\n";
  }
}

std::string GridWriter::mesh_grid(const std::string& name) {
  const auto points = file_.info("/mesh/points");
  const std::size_t cells =
      file_.info("/mesh/cells/triangle").shape.at(0) + file_.info("/mesh/cells/quad").shape.at(0);
  std::ostringstream xml;
  xml << "    <Grid Name=\"" << xml_escape(name) << "\" GridType=\"Uniform\">\n"
      << "      <Topology TopologyType=\"Mixed\" NumberOfElements=\"" << cells << "\">\n        "
      << item("/mesh/topology_xdmf_mixed", file_.info("/mesh/topology_xdmf_mixed").shape, "Int")
      << "\n      </Topology>\n      <Geometry GeometryType=\"XY\">\n        "
      << item("/mesh/points", points.shape, "Float") << "\n      </Geometry>\n";
  attributes(xml, "/fields/point", "Node", points.shape.at(0));
  attributes(xml, "/fields/cell", "Cell", cells);
  xml << "    </Grid>\n";
  return xml.str();
}

std::string GridWriter::beam_grid(const std::string& name) {
  const auto points = file_.info("/beam/points");
  const auto segments = file_.info("/beam/segments");
  std::ostringstream xml;
  xml << "    <Grid Name=\"" << xml_escape(name) << "\" GridType=\"Uniform\">\n"
      << "      <Topology TopologyType=\"Polyline\" NodesPerElement=\"2\" NumberOfElements=\""
      << segments.shape.at(0) << "\">\n        " << item("/beam/segments", segments.shape, "Int")
      << "\n      </Topology>\n      <Geometry GeometryType=\"XYZ\">\n        "
      << item("/beam/points", points.shape, "Float") << "\n      </Geometry>\n";
  attributes(xml, "/fields/point", "Node", points.shape.at(0));
  attributes(xml, "/fields/cell", "Cell", segments.shape.at(0));
  xml << "    </Grid>\n";
  return xml.str();
}

std::string GridWriter::line_grid(const std::string& name, const std::string& group,
                                  const std::vector<std::string>& coordinates) {
  beyond_meshio_ = true;
  const std::size_t n = file_.info(group + "/" + coordinates.front()).shape.at(0);
  std::ostringstream xml;
  // The files store a line's points in order and no connectivity: segment k joins rows k and
  // k+1, written inline (a few hundred numbers for a wall).
  xml << "    <Grid Name=\"" << xml_escape(name) << "\" GridType=\"Uniform\">\n"
      << "      <Topology TopologyType=\"Polyline\" NodesPerElement=\"2\" NumberOfElements=\""
      << n - 1 << "\">\n        <DataItem Dimensions=\"" << n - 1
      << " 2\" NumberType=\"Int\" Format=\"XML\">";
  for (std::size_t k = 0; k + 1 < n; ++k)
    xml << (k ? " " : "") << k << " " << k + 1;
  xml << "</DataItem>\n      </Topology>\n";
  if (coordinates.size() == 1) {
    xml << "      <Geometry GeometryType=\"XY\">\n        "
        << item(group + "/" + coordinates[0], {n, 2}, "Float") << "\n      </Geometry>\n";
  } else {
    // Separate x and y datasets (flow wall traces): ParaView 5.11's XDMF reader crashes on an
    // X_Y geometry and on Function items, and reads no points from X_Y_Z, so the coordinates are
    // copied into the sidecar as text, exactly (17 significant digits). The fields still
    // reference the file.
    const std::vector<double> x = file_.read_vector(group + "/" + coordinates[0]);
    const std::vector<double> y = file_.read_vector(group + "/" + coordinates[1]);
    xml << "      <Geometry GeometryType=\"XY\">\n        <DataItem Dimensions=\"" << n
        << " 2\" NumberType=\"Float\" Precision=\"8\" Format=\"XML\">" << std::setprecision(17);
    for (std::size_t k = 0; k < n; ++k)
      xml << (k ? " " : "") << x.at(k) << " " << y.at(k);
    xml << "</DataItem>\n      </Geometry>\n";
  }
  attributes(xml, group, "Node", n, coordinates);
  xml << "    </Grid>\n";
  return xml.str();
}

std::string GridWriter::boundary_grid(const std::string& name, const h5::MatrixXiR& edges,
                                      const h5::MatrixXdR& points) {
  beyond_meshio_ = true;
  // The boundary's own points, in the order its edges first reach them, copied into the sidecar
  // as text (exact doubles; a few hundred for a wall): a grid on the file's /mesh/points would
  // hand ParaView every mesh point once more per boundary, and it cannot read a selection of
  // rows (its reader skips Function and HyperSlab items of an attribute).
  std::vector<std::int64_t> used;
  std::map<std::int64_t, std::size_t> local;
  for (Eigen::Index e = 0; e < edges.rows(); ++e) {
    for (Eigen::Index k = 0; k < 2; ++k) {
      if (local.emplace(edges(e, k), used.size()).second)
        used.push_back(edges(e, k));
    }
  }
  std::ostringstream xml;
  xml << "    <Grid Name=\"" << xml_escape(name) << "\" GridType=\"Uniform\">\n"
      << "      <Topology TopologyType=\"Polyline\" NodesPerElement=\"2\" NumberOfElements=\""
      << edges.rows() << "\">\n        <DataItem Dimensions=\"" << edges.rows()
      << " 2\" NumberType=\"Int\" Format=\"XML\">";
  for (Eigen::Index e = 0; e < edges.rows(); ++e)
    xml << (e ? " " : "") << local.at(edges(e, 0)) << " " << local.at(edges(e, 1));
  xml << "</DataItem>\n      </Topology>\n      <Geometry GeometryType=\"XY\">\n        <DataItem "
      << "Dimensions=\"" << used.size() << " 2\" NumberType=\"Float\" Precision=\"8\" "
      << "Format=\"XML\">" << std::setprecision(17);
  for (std::size_t k = 0; k < used.size(); ++k) {
    const auto row = static_cast<Eigen::Index>(used[k]);
    xml << (k ? " " : "") << points(row, 0) << " " << points(row, 1);
  }
  xml << "</DataItem>\n      </Geometry>\n      <Attribute Name=\"node\" AttributeType=\"Scalar\" "
      << "Center=\"Node\">\n        <DataItem Dimensions=\"" << used.size()
      << "\" NumberType=\"Int\" Precision=\"8\" Format=\"XML\">";
  for (std::size_t k = 0; k < used.size(); ++k)
    xml << (k ? " " : "") << used[k];
  xml << "</DataItem>\n      </Attribute>\n    </Grid>\n";
  return xml.str();
}

std::vector<std::string> GridWriter::grids(const std::string& name) {
  std::vector<std::string> out;
  if (file_.exists("/mesh/points")) {
    // A 2D mesh of triangles and quads (flowmesh, solidmesh, flow, thermal).
    out.push_back(mesh_grid(name));
  } else if (file_.exists("/beam/points")) {
    // The beams as polylines of display segments (structure).
    out.push_back(beam_grid(name));
  }
  if (reader_ == Reader::meshio)
    return out;
  // Lines of points stored per group, each its own grid named after the group: a flow file's
  // wall traces (x, y), a walldisp file's walls (x0), a loads (1.2) or strain file's flaps
  // (position). A line needs two points.
  auto lines = [&](const std::string& root, const std::vector<std::string>& coordinates) {
    if (!file_.is_group(root))
      return;
    for (const auto& group_name : file_.children(root)) {
      const std::string group = root + "/" + group_name;
      bool present = file_.is_group(group);
      for (const auto& c : coordinates)
        present = present && file_.is_dataset(group + "/" + c);
      if (!present || file_.info(group + "/" + coordinates.front()).shape.at(0) < 2)
        continue;
      out.push_back(line_grid(group_name, group, coordinates));
    }
  };
  lines("/walls", {"x", "y"});
  lines("/walls", {"x0"});
  lines("/flaps", {"position"});
  // The mesh's boundaries, each its own polyline named after it, so that ParaView lists every
  // wall by its flap and side ("upper_convergent_inner") and every far-field piece by its name. A
  // flow file shows its walls as the traces above, with their fields, and no boundaries besides.
  if (file_.exists("/mesh/points") && file_.is_group("/mesh/boundaries") &&
      !file_.is_group("/walls")) {
    const h5::MatrixXdR points = file_.read_matrix("/mesh/points", {}, 2);
    for (const auto& boundary : file_.children("/mesh/boundaries")) {
      const std::string edges_path = "/mesh/boundaries/" + boundary + "/edges";
      if (!file_.is_dataset(edges_path))
        continue;
      const auto edges = file_.read_index_matrix(edges_path, {}, 2, 0, points.rows());
      if (edges.rows() > 0)
        out.push_back(boundary_grid(boundary, edges, points));
    }
  }
  return out;
}

// Indents every line of a block by `spaces` more.
std::string indented(const std::string& block, std::size_t spaces) {
  std::string out;
  std::istringstream lines(block);
  for (std::string line; std::getline(lines, line);)
    out += std::string(spaces, ' ') + line + "\n";
  return out;
}

// One grid as it stands, several as a spatial collection (ParaView: a multiblock dataset).
std::string grid_or_collection(const std::vector<std::string>& grids, const std::string& name,
                               const std::string& time) {
  if (grids.size() == 1) {
    std::string grid = grids.front();
    if (!time.empty())
      grid.insert(grid.find('\n') + 1, "      " + time + "\n");
    return grid;
  }
  std::string xml = "    <Grid Name=\"" + xml_escape(name) +
                    "\" GridType=\"Collection\" CollectionType=\"Spatial\">\n";
  if (!time.empty())
    xml += "      " + time + "\n";
  for (const auto& grid : grids)
    xml += indented(grid, 2);
  return xml + "    </Grid>\n";
}

const char* kHead = "<?xml version=\"1.0\" ?>\n<Xdmf Version=\"3.0\">\n  <Domain>\n";
const char* kTail = "  </Domain>\n</Xdmf>\n";

// How a sidecar at `sidecar` names `h5_file`: relative to the sidecar's folder.
std::string reference(const std::filesystem::path& h5_file, const std::filesystem::path& sidecar) {
  const auto base = std::filesystem::absolute(sidecar).lexically_normal().parent_path();
  return std::filesystem::absolute(h5_file).lexically_normal().lexically_relative(base).string();
}

}  // namespace

std::filesystem::path meshio_sidecar_path(const std::filesystem::path& h5_file) {
  std::filesystem::path path = h5_file;
  path.replace_extension(".meshio.xdmf");
  return path;
}

std::filesystem::path write_xdmf_sidecar(const std::filesystem::path& h5_file) {
  h5::Reader file(h5_file);
  std::filesystem::path sidecar = h5_file;
  sidecar.replace_extension(".xdmf");
  const std::string name = h5_file.stem().string();
  GridWriter paraview(file, h5_file.filename().string(), Reader::paraview);
  const std::vector<std::string> grids = paraview.grids(name);
  if (grids.empty())
    return {};
  write_text_atomically(sidecar, kHead + grid_or_collection(grids, name, "") + kTail);
  // meshio 7 reads one Uniform grid of whole HDF5 datasets and stops at anything else (a
  // HyperSlab, a second grid): where the sidecar needs more, a variant for it is written beside
  // it with the grid of the file and its datasets as stored.
  if (paraview.used_beyond_meshio()) {
    GridWriter meshio(file, h5_file.filename().string(), Reader::meshio);
    const std::vector<std::string> grid = meshio.grids(name);
    if (grid.size() == 1)
      write_text_atomically(meshio_sidecar_path(h5_file), kHead + grid[0] + kTail);
  }
  return sidecar;
}

std::filesystem::path write_xdmf_series(const std::filesystem::path& output,
                                        const std::vector<std::filesystem::path>& h5_files) {
  if (h5_files.empty())
    throw UsageError("an XDMF series needs at least one file");
  std::string xml = kHead;
  xml += "    <Grid Name=\"" + xml_escape(output.stem().string()) +
         "\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  for (std::size_t k = 0; k < h5_files.size(); ++k) {
    h5::Reader file(h5_files[k]);
    GridWriter writer(file, reference(h5_files[k], output), Reader::paraview);
    const std::string name = h5_files[k].parent_path().filename().string();
    const std::vector<std::string> grids = writer.grids(name.empty() ? "step" : name);
    if (grids.empty())
      throw BadInput(h5_files[k].string() + ": /: nothing to draw (no mesh, beam or lines)");
    // Time is the position in the series: the iteration number of a two-way run's iterates.
    const std::string time = "<Time Value=\"" + std::to_string(k + 1) + "\"/>";
    xml += indented(grid_or_collection(grids, name, time), 2);
  }
  xml += "    </Grid>\n";
  xml += kTail;
  write_text_atomically(output, xml);
  return output;
}

}  // namespace tfmb::formats
