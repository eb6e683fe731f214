#include "geometry_io.hpp"

#include <gmsh.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <map>
#include <sstream>

#include "tfmb/common/errors.hpp"
#include "tfmb/common/gmsh_session.hpp"
#include "tfmb/common/text_file.hpp"

namespace tfmb::input {

namespace {

std::string lower_extension(const std::filesystem::path& file) {
  std::string ext = file.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  return ext;
}

std::vector<Curve> read_csv(const std::filesystem::path& file, double scale) {
  std::ifstream in(file);
  if (!in) throw BadInput(file.string() + ": cannot open geometry file");
  std::vector<Curve> curves;
  std::map<std::string, std::size_t> index;
  std::string line;
  int number = 0;
  bool header_seen = false;
  while (std::getline(in, line)) {
    ++number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty() || line[0] == '#') continue;
    std::vector<std::string> fields;
    std::stringstream stream(line);
    for (std::string f; std::getline(stream, f, ',');) {
      f.erase(0, f.find_first_not_of(" \t"));
      f.erase(f.find_last_not_of(" \t") + 1);
      fields.push_back(f);
    }
    const std::string where = file.string() + ":" + std::to_string(number) + ": ";
    if (!header_seen) {
      if (fields.size() != 3 || fields[0] != "curve" || fields[1] != "x" || fields[2] != "y") {
        throw BadInput(where + "expected the header 'curve,x,y'");
      }
      header_seen = true;
      continue;
    }
    if (fields.size() != 3) throw BadInput(where + "expected 3 fields 'curve,x,y'");
    double x = 0, y = 0;
    try {
      std::size_t used = 0;
      x = std::stod(fields[1], &used);
      if (used != fields[1].size()) throw std::invalid_argument("x");
      y = std::stod(fields[2], &used);
      if (used != fields[2].size()) throw std::invalid_argument("y");
    } catch (const std::exception&) {
      throw BadInput(where + "x and y must be numbers");
    }
    // stod reads "nan" and "inf": a curve through them has no length and no place, and the
    // message further on ("zero length") would name neither the file nor the line.
    if (!std::isfinite(x) || !std::isfinite(y))
      throw BadInput(where + "x and y must be finite");
    auto [it, inserted] = index.try_emplace(fields[0], curves.size());
    if (inserted) curves.push_back({fields[0], {}});
    else if (it->second + 1 != curves.size()) {
      throw BadInput(where + "points of curve '" + fields[0] + "' must be consecutive rows");
    }
    std::vector<geometry::Point>& points = curves[it->second].points;
    const geometry::Point point(x * scale, y * scale);
    if (!points.empty() && points.back() == point) {
      throw BadInput(where + "repeats the previous point of curve '" + fields[0] +
                     "' (a zero-length segment)");
    }
    points.push_back(point);
  }
  if (!header_seen) throw BadInput(file.string() + ": empty geometry file (expected 'curve,x,y')");
  for (const auto& c : curves) {
    if (c.points.size() < 2) throw BadInput(file.string() + ": curve '" + c.name + "' has fewer than 2 points");
  }
  return curves;
}

std::vector<Curve> read_cad(const std::filesystem::path& file, double scale, int samples,
                            bool is_geo) {
  GmshSession session;
  try {
    if (is_geo) {
      gmsh::open(file.string());
    } else {
      gmsh::vectorpair imported;
      gmsh::model::occ::importShapes(file.string(), imported);
      gmsh::model::occ::synchronize();
    }
  } catch (...) {
    throw BadInput(file.string() + ": gmsh could not read this geometry file");
  }
  gmsh::vectorpair entities;
  gmsh::model::getEntities(entities, 1);
  if (entities.empty()) {
    throw BadInput(file.string() + ": the geometry holds no curves (points and lines are needed; "
                   "surfaces or solids alone are not read)");
  }
  // Names: a physical curve group holding exactly one curve names it; else the entity name;
  // else the entity tag.
  std::map<int, std::string> names;
  gmsh::vectorpair groups;
  gmsh::model::getPhysicalGroups(groups, 1);
  for (const auto& [dim, tag] : groups) {
    std::vector<int> members;
    gmsh::model::getEntitiesForPhysicalGroup(dim, tag, members);
    std::string name;
    gmsh::model::getPhysicalName(dim, tag, name);
    if (members.size() == 1 && !name.empty()) names[members[0]] = name;
  }
  std::vector<Curve> curves;
  for (const auto& [dim, tag] : entities) {
    Curve curve;
    if (auto it = names.find(tag); it != names.end()) curve.name = it->second;
    if (curve.name.empty()) gmsh::model::getEntityName(dim, tag, curve.name);
    if (curve.name.empty()) curve.name = std::to_string(tag);
    std::string type;
    gmsh::model::getType(dim, tag, type);
    std::vector<double> lo, hi;
    gmsh::model::getParametrizationBounds(dim, tag, lo, hi);
    const int n = type == "Line" ? 2 : samples;
    std::vector<double> params(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) params[static_cast<std::size_t>(i)] = lo[0] + (hi[0] - lo[0]) * i / (n - 1);
    std::vector<double> xyz;
    gmsh::model::getValue(dim, tag, params, xyz);
    for (int i = 0; i < n; ++i) {
      curve.points.emplace_back(xyz[3 * i] * scale, xyz[3 * i + 1] * scale);
      if (std::abs(xyz[3 * i + 2]) > 1e-9 * (1.0 + std::abs(xyz[3 * i]))) {
        throw BadInput(file.string() + ": curve '" + curve.name +
                       "' leaves the z = 0 plane; tfmb geometry is planar (x, y)");
      }
    }
    curves.push_back(std::move(curve));
  }
  return curves;
}

}  // namespace

std::vector<Curve> read_geometry(const std::filesystem::path& file, double scale, int curve_samples) {
  if (!std::filesystem::exists(file)) {
    throw BadInput(file.string() + ": geometry file not found (check geometry.file in case.toml)");
  }
  const std::string ext = lower_extension(file);
  if (ext == ".csv") return read_csv(file, scale);
  if (ext == ".step" || ext == ".stp" || ext == ".iges" || ext == ".igs") {
    return read_cad(file, scale, curve_samples, false);
  }
  if (ext == ".geo") return read_cad(file, scale, curve_samples, true);
  throw BadInput(file.string() + ": unknown geometry file type '" + ext +
                 "' (expected .csv, .step/.stp, .iges/.igs or .geo)");
}

void write_curves_csv(const std::vector<Curve>& curves, const std::filesystem::path& file) {
  std::ostringstream out;
  out << "curve,x,y\n" << std::setprecision(17);
  for (const auto& c : curves) {
    for (const auto& p : c.points) out << c.name << "," << p.x() << "," << p.y() << "\n";
  }
  write_text_atomically(file, out.str());  // whole or not at all (a full disk: exit 4)
}

}  // namespace tfmb::input
