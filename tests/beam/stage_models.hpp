// model.h5 documents for the file-stage tests of tfmb-beam, built from the model format's
// example document with a physically meaningful structure put in: a cantilever and Lee's frame.
#pragma once

#include <filesystem>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include <Eigen/Dense>

#include "tfmb-beam/run.hpp"
#include "tfmb/common/h5.hpp"
#include "tfmb/common/log.hpp"
#include "tfmb/formats/files.hpp"
#include "tfmb/formats/schema.hpp"
#include "tfmb/formats/structure.hpp"

namespace beam_test {

namespace fs = std::filesystem;
using namespace tfmb;

inline constexpr double kEI = 100.0, kGA = 1e6, kLength = 1.0;

inline void set_matrix(formats::DatasetValue& d, const std::vector<std::vector<double>>& rows) {
  d.shape = {rows.size(), rows.empty() ? 0 : rows[0].size()};
  d.floats.clear();
  for (const auto& r : rows)
    d.floats.insert(d.floats.end(), r.begin(), r.end());
}

inline void erase_prefix(formats::Document& doc, const std::string& prefix) {
  std::erase_if(doc.datasets, [&](const auto& kv) { return kv.first.rfind(prefix, 0) == 0; });
  std::erase_if(doc.attributes, [&](const auto& kv) { return kv.first.rfind(prefix, 0) == 0; });
  std::erase_if(doc.groups, [&](const std::string& g) { return g.rfind(prefix, 0) == 0; });
}

/// Cantilever of 1 m along +x in 3 two-node model elements, clamped at its start.
inline fs::path write_cantilever_model(const fs::path& dir, const std::string& joint_kind = "") {
  formats::Document doc = formats::example_document(*formats::find_schema("model"));
  std::vector<std::vector<double>> line, inner, outer;
  std::vector<double> arc;
  for (int i = 0; i < 4; ++i) {
    line.push_back({kLength * i / 3.0, 0.0});
    inner.push_back({kLength * i / 3.0, -0.005});
    outer.push_back({kLength * i / 3.0, 0.005});
    arc.push_back(kLength * i / 3.0);
  }
  doc.attributes["/flaps/sample"]["elements"].integer = 3;
  set_matrix(doc.datasets["/flaps/sample/reference_curve"], line);
  set_matrix(doc.datasets["/flaps/sample/reference_geometry"], line);
  set_matrix(doc.datasets["/flaps/sample/inner_wall"], inner);
  set_matrix(doc.datasets["/flaps/sample/outer_wall"], outer);
  doc.datasets["/flaps/sample/wall_arc_length"].shape = {4};
  doc.datasets["/flaps/sample/wall_arc_length"].floats = arc;
  set_matrix(doc.datasets["/flaps/sample/solid_outline"],
             {{0.0, -0.005}, {kLength, -0.005}, {kLength, 0.005}, {0.0, 0.005}});
  std::vector<std::vector<double>> k(6, std::vector<double>(6, 0.0)),
      m(6, std::vector<double>(6, 0.0));
  const double diag_k[6] = {1e7, kGA, kGA, 50.0, kEI, kEI},
               diag_m[6] = {1.0, 1.0, 1.0, 2e-4, 1e-4, 1e-4};
  for (int i = 0; i < 6; ++i) {
    k[i][i] = diag_k[i];
    m[i][i] = diag_m[i];
  }
  set_matrix(doc.datasets["/flaps/sample/section_stiffness"], k);
  set_matrix(doc.datasets["/flaps/sample/section_mass"], m);
  erase_prefix(doc, "/domain/boundaries");  // a structure-only model: no flow domain
  if (joint_kind.empty()) {
    erase_prefix(doc, "/joints");
  } else {
    doc.attributes["/joints/sample"]["kind"].text = joint_kind;
  }
  doc.attributes["/supports/sample"]["flap"].text = "sample";
  doc.attributes["/supports/sample"]["end"].text = "start";
  doc.attributes["/supports/sample"]["kind"].text = "clamp";
  doc.attributes["/analysis"]["time"].text = "static";
  doc.attributes["/analysis"]["load_steps"].integer = 2;
  const fs::path file = dir / "model.h5";
  formats::write_document(doc, file);
  return file;
}

inline fs::path scratch(const std::string& name) {
  const fs::path dir = fs::path(TFMB_BINARY_DIR) / "test-beam-stage" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

/// Copies every object under `from` (datasets, attributes, groups) to `to`.
inline void copy_prefix(formats::Document& doc, const std::string& from, const std::string& to) {
  auto renamed = [&](const std::string& path) { return to + path.substr(from.size()); };
  const auto datasets = doc.datasets;
  for (const auto& [path, value] : datasets)
    if (path.rfind(from + "/", 0) == 0)
      doc.datasets[renamed(path)] = value;
  const auto attributes = doc.attributes;
  for (const auto& [path, value] : attributes)
    if (path == from || path.rfind(from + "/", 0) == 0)
      doc.attributes[renamed(path)] = value;
  const auto groups = doc.groups;
  for (const auto& g : groups)
    if (g == from || g.rfind(from + "/", 0) == 0)
      doc.groups.insert(renamed(g));
}

/// Adds flap `name`, straight from a to b in `elements` elements, with the diagonal section
/// stiffness (EA, GA, GA, GJ = 2 EI, EI, EI) [N, N m^2], copied from the example flap "sample"
/// (which the caller erases when done).
inline void add_straight_flap(formats::Document& doc, const std::string& name, int order,
                              Eigen::Vector2d a, Eigen::Vector2d b, int elements, double ea,
                              double ga, double ei) {
  const std::string g = "/flaps/" + name;
  copy_prefix(doc, "/flaps/sample", g);
  doc.attributes[g]["order"].integer = order;
  doc.attributes[g]["elements"].integer = elements;
  const Eigen::Vector2d t = (b - a).normalized(), n(-t.y(), t.x());
  std::vector<std::vector<double>> line, inner, outer;
  std::vector<double> arc;
  for (int i = 0; i <= elements; ++i) {
    const double s = static_cast<double>(i) / elements;
    const Eigen::Vector2d x = a + s * (b - a);
    line.push_back({x.x(), x.y()});
    inner.push_back({x.x() - 0.005 * n.x(), x.y() - 0.005 * n.y()});
    outer.push_back({x.x() + 0.005 * n.x(), x.y() + 0.005 * n.y()});
    arc.push_back(s * (b - a).norm());
  }
  set_matrix(doc.datasets[g + "/reference_curve"], line);
  set_matrix(doc.datasets[g + "/reference_geometry"], line);
  set_matrix(doc.datasets[g + "/inner_wall"], inner);
  set_matrix(doc.datasets[g + "/outer_wall"], outer);
  doc.datasets[g + "/wall_arc_length"].shape = {arc.size()};
  doc.datasets[g + "/wall_arc_length"].floats = arc;
  set_matrix(doc.datasets[g + "/solid_outline"],
             {inner.front(), inner.back(), outer.back(), outer.front()});
  std::vector<std::vector<double>> k(6, std::vector<double>(6, 0.0));
  const double diag_k[6] = {ea, ga, ga, 2.0 * ei, ei, ei};
  for (int i = 0; i < 6; ++i)
    k[i][i] = diag_k[i];
  set_matrix(doc.datasets[g + "/section_stiffness"], k);
}

/// Lee's frame through model.h5 (cases::lee_frame scaled to members of 1.2 m with the same
/// slenderness: EI = 100 N m^2, EA = 43200 EI / L^2, GA = EA / 2.6 * 5 / 6): a column, the beam
/// split at 1/5 of its length from the corner into flaps "short" and "long", joined rigidly, the
/// column's foot and the beam's far end pinned. The dead load goes on short:end. The published
/// limit load scales to 18.532 EI / L^2 = 1287 N.
inline fs::path write_lee_frame_model(const fs::path& dir) {
  const fs::path file = write_cantilever_model(dir, "rigid");
  formats::Document doc = formats::read_document(h5::Reader(file));
  const double length = 1.2, ei = 100.0, ea = 43200.0 * ei / (length * length),
               ga = ea / 2.6 * 5.0 / 6.0;
  add_straight_flap(doc, "column", 0, {0, 0}, {0, length}, 10, ea, ga, ei);
  add_straight_flap(doc, "short", 1, {0, length}, {0.2 * length, length}, 2, ea, ga, ei);
  add_straight_flap(doc, "long", 2, {0.2 * length, length}, {length, length}, 8, ea, ga, ei);
  erase_prefix(doc, "/flaps/sample");
  auto rigid = [&](const std::string& name, const std::string& a, const std::string& b,
                   Eigen::Vector2d at) {
    const std::string g = "/joints/" + name;
    copy_prefix(doc, "/joints/sample", g);
    doc.attributes[g]["kind"].text = "rigid";
    doc.attributes[g]["flap_a"].text = a;
    doc.attributes[g]["end_a"].text = "end";
    doc.attributes[g]["flap_b"].text = b;
    doc.attributes[g]["end_b"].text = "start";
    doc.datasets[g + "/point"].floats = {at.x(), at.y()};
  };
  rigid("corner", "column", "short", {0, length});
  rigid("load_point", "short", "long", {0.2 * length, length});
  erase_prefix(doc, "/joints/sample");
  copy_prefix(doc, "/supports/sample", "/supports/foot");
  copy_prefix(doc, "/supports/sample", "/supports/far");
  erase_prefix(doc, "/supports/sample");
  for (const auto& [name, flap, end, x, y] :
       {std::tuple<std::string, std::string, std::string, double, double>{"foot", "column", "start",
                                                                          0.0, 0.0},
        {"far", "long", "end", length, length}}) {
    doc.attributes["/supports/" + name]["flap"].text = flap;
    doc.attributes["/supports/" + name]["end"].text = end;
    doc.attributes["/supports/" + name]["kind"].text = "pinned";
    doc.datasets["/supports/" + name + "/point"].floats = {x, y};
  }
  formats::write_document(doc, file);
  return file;
}

/// tfmb-beam through the file stage on `model`: the dead point load `point_load` (as
/// --point-load) by arc length from 10 load steps, written to `output`; returns the load path
/// it wrote (structure.h5 /path). Throws if the run fails or writes no path.
inline formats::StructurePath run_arc_length_path(const fs::path& model,
                                                  const std::string& point_load,
                                                  const fs::path& output) {
  beam::Options o;
  o.model = model;
  o.point_loads = {point_load};
  o.dead_loads = true;
  o.arc_length = true;
  o.load_steps = 10;
  o.output = output;
  const Logger log("tfmb-beam", Verbosity::quiet);
  if (beam::run(o, log) != 0)
    throw std::runtime_error("tfmb-beam on " + model.string() + " did not finish");
  formats::Structure s = formats::read_structure(output);
  if (!s.path)
    throw std::runtime_error(output.string() + ": no /path");
  return *s.path;
}

}  // namespace beam_test
