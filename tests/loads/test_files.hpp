// Test inputs written with h5::Writer following the schemas of the stages tfmb-loads,
// tfmb-matmap and tfmb-strain read (formats/src/schema_{model,flow,structure,thermal}.cpp).
// Shared by tests/loads, tests/matmap and tests/strain.
#pragma once

#include <unistd.h>

#include <Eigen/Core>
#include <cmath>
#include <filesystem>
#include <functional>
#include <map>
#include <string>
#include <system_error>
#include <vector>

#include "tfmb/common/h5.hpp"
#include "tfmb/formats/files.hpp"

namespace tfmb::testfiles {

using Vec2 = Eigen::Vector2d;

// This process's own folder under the system's temporary folder, removed when the process exits:
// two test processes that run at once never share a file, and no run leaves files behind.
inline const std::filesystem::path& process_temp_root() {
  struct Root {
    std::filesystem::path path =
        std::filesystem::temp_directory_path() / ("tfmb-iface-" + std::to_string(::getpid()));
    Root() { std::filesystem::create_directories(path); }
    ~Root() {
      std::error_code ignored;
      std::filesystem::remove_all(path, ignored);
    }
  };
  static const Root root;
  return root.path;
}

inline std::filesystem::path temp_dir(const std::string& name) {
  auto dir = process_temp_root() / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

inline h5::MatrixXdR matrix(const std::vector<Vec2>& v, int cols = 2) {
  h5::MatrixXdR m = h5::MatrixXdR::Zero(static_cast<Eigen::Index>(v.size()), cols);
  for (std::size_t i = 0; i < v.size(); ++i) {
    m(static_cast<Eigen::Index>(i), 0) = v[i].x();
    m(static_cast<Eigen::Index>(i), 1) = v[i].y();
  }
  return m;
}

struct TestFlap {
  std::string name = "flap";
  std::string material = "Ti-6Al-4V";
  double thickness = 0.004;  // [m]
  double width = 0.5;        // [m]
  std::vector<Vec2> reference_curve;
  std::vector<Vec2> inner_wall;
  std::vector<Vec2> outer_wall;
};

// Straight flap from `start` at `angle` [rad], length L, n beam nodes; the reference line at
// mid-thickness, outer wall on its left (+normal), inner wall on its right; walls with
// `wall_points` points each.
inline TestFlap straight_flap(std::string name, Vec2 start, double angle, double length, int beam_nodes,
                              int wall_points, double thickness = 0.004, double width = 0.5) {
  TestFlap f;
  f.name = std::move(name);
  f.thickness = thickness;
  f.width = width;
  const Vec2 t(std::cos(angle), std::sin(angle));
  const Vec2 n(-t.y(), t.x());
  for (int i = 0; i < beam_nodes; ++i) f.reference_curve.push_back(start + length * i / (beam_nodes - 1.0) * t);
  for (int i = 0; i < wall_points; ++i) {
    const Vec2 r = start + length * i / (wall_points - 1.0) * t;
    f.inner_wall.push_back(r - 0.5 * thickness * n);
    f.outer_wall.push_back(r + 0.5 * thickness * n);
  }
  return f;
}

// Arc flap about `centre`, beam radius R from angle a0 to a1 (counter-clockwise); the inner
// wall at R - t/2 (towards the centre), the outer at R + t/2.
inline TestFlap arc_flap(std::string name, Vec2 centre, double radius, double a0, double a1, int beam_nodes,
                         int wall_points, double thickness = 0.004, double width = 0.5) {
  TestFlap f;
  f.name = std::move(name);
  f.thickness = thickness;
  f.width = width;
  auto at = [&](double r, double a) { return Vec2(centre + r * Vec2(std::cos(a), std::sin(a))); };
  for (int i = 0; i < beam_nodes; ++i) f.reference_curve.push_back(at(radius, a0 + (a1 - a0) * i / (beam_nodes - 1.0)));
  for (int i = 0; i < wall_points; ++i) {
    const double a = a0 + (a1 - a0) * i / (wall_points - 1.0);
    f.inner_wall.push_back(at(radius - 0.5 * thickness, a));
    f.outer_wall.push_back(at(radius + 0.5 * thickness, a));
  }
  return f;
}

inline void write_root(h5::Writer& w, const std::string& kind) {
  formats::Header header;
  header.creator = "test";
  formats::write_header(w, kind, header);
}

// The example document of a kind (valid for the schema this build has), with the subtree
// "<parent>/sample" cloned once per name and the sample removed: tests then set what they
// need, and the files stay valid when a schema gains attributes the tools do not read.
inline formats::Document example_with(const std::string& kind, const std::string& parent,
                                      const std::vector<std::string>& names) {
  formats::Document doc = formats::example_document(*formats::find_schema(kind));
  const std::string sample = parent + "/sample";
  auto rename = [&](const std::string& path, const std::string& name) {
    return parent + "/" + name + path.substr(sample.size());
  };
  auto under = [&](const std::string& path) {
    return path == sample || path.rfind(sample + "/", 0) == 0;
  };
  formats::Document out;
  for (const auto& g : doc.groups) {
    if (!under(g)) out.groups.insert(g);
    else for (const auto& n : names) out.groups.insert(rename(g, n));
  }
  for (const auto& [path, value] : doc.datasets) {
    if (!under(path)) out.datasets[path] = value;
    else for (const auto& n : names) out.datasets[rename(path, n)] = value;
  }
  for (const auto& [path, value] : doc.attributes) {
    if (!under(path)) out.attributes[path] = value;
    else for (const auto& n : names) out.attributes[rename(path, n)] = value;
  }
  if (names.empty()) out.groups.insert(parent);
  return out;
}

inline void set_f64(formats::Document& doc, const std::string& path, std::vector<std::size_t> shape,
                    std::vector<double> values, const std::string& units) {
  formats::DatasetValue v;
  v.dtype = h5::DType::float64;
  v.shape = std::move(shape);
  v.floats = std::move(values);
  doc.datasets[path] = v;
  formats::AttributeValue u;
  u.text = units;
  doc.attributes[path]["units"] = u;
}

inline void set_points(formats::Document& doc, const std::string& path, const std::vector<Vec2>& points) {
  std::vector<double> values;
  for (const auto& p : points) {
    values.push_back(p.x());
    values.push_back(p.y());
  }
  set_f64(doc, path, {points.size(), 2}, values, "m");
}

inline void set_attr(formats::Document& doc, const std::string& object, const std::string& name, const std::string& text) {
  formats::AttributeValue a;
  a.type = formats::AttrType::string;
  a.text = text;
  doc.attributes[object][name] = a;
}

inline void set_attr(formats::Document& doc, const std::string& object, const std::string& name, double number) {
  auto& a = doc.attributes[object][name];
  if (a.type == formats::AttrType::int64) {
    a.integer = static_cast<std::int64_t>(number);
  } else {
    a.type = formats::AttrType::float64;
    a.number = number;
  }
}

// Removes everything below `parent` (keeping the group itself).
inline void erase_below(formats::Document& doc, const std::string& parent) {
  const std::string prefix = parent + "/";
  std::erase_if(doc.groups, [&](const std::string& g) { return g.rfind(prefix, 0) == 0; });
  std::erase_if(doc.datasets, [&](const auto& kv) { return kv.first.rfind(prefix, 0) == 0; });
  std::erase_if(doc.attributes, [&](const auto& kv) { return kv.first.rfind(prefix, 0) == 0; });
}

inline void write_model(const std::filesystem::path& file, const std::vector<TestFlap>& flaps) {
  std::vector<std::string> names;
  for (const auto& f : flaps) names.push_back(f.name);
  formats::Document doc = example_with("model", "/flaps", names);
  // The example's joint, support and domain pieces name its flap 'sample': the stages these
  // files feed (loads, matmap, strain) read flaps only, and the model reader refuses references to
  // a flap the file does not have.
  for (const char* parent : {"/joints", "/supports", "/domain/boundaries"})
    erase_below(doc, parent);
  for (const auto& f : flaps) {
    const std::string g = "/flaps/" + f.name;
    set_points(doc, g + "/reference_curve", f.reference_curve);
    set_points(doc, g + "/inner_wall", f.inner_wall);
    set_points(doc, g + "/outer_wall", f.outer_wall);
    if (doc.datasets.count(g + "/reference_geometry")) {
      std::vector<Vec2> middle;
      std::vector<double> arc;
      double length = 0.0;
      for (std::size_t i = 0; i < f.inner_wall.size(); ++i) {
        middle.push_back(0.5 * (f.inner_wall[i] + f.outer_wall[i]));
        if (i > 0) length += (middle[i] - middle[i - 1]).norm();
        arc.push_back(length);
      }
      set_points(doc, g + "/reference_geometry", middle);
      if (doc.datasets.count(g + "/wall_arc_length")) set_f64(doc, g + "/wall_arc_length", {arc.size()}, arc, "m");
    }
    if (doc.datasets.count(g + "/solid_outline")) {
      std::vector<Vec2> outline(f.inner_wall);
      outline.insert(outline.end(), f.outer_wall.rbegin(), f.outer_wall.rend());
      set_points(doc, g + "/solid_outline", outline);
    }
    set_attr(doc, g, "material", f.material);
    set_attr(doc, g, "thickness", f.thickness);
    set_attr(doc, g, "width", f.width);
    if (doc.attributes[g].count("elements")) set_attr(doc, g, "elements", static_cast<double>(f.reference_curve.size() - 1));
  }
  // A real stress-free temperature (the example's is a placeholder).
  if (doc.attributes.count("/thermal") && doc.attributes["/thermal"].count("reference_temperature")) {
    set_attr(doc, "/thermal", "reference_temperature", 293.15);
  }
  formats::write_document(doc, file);
}

struct TestTrace {
  std::string name, flap, side;
  std::vector<Vec2> points;
  std::vector<double> pressure, wall_shear;
  // Which side of the wall the fluid is on: +1 = left of the point order.
  double fluid_side = 1.0;
};

// A trace on a polyline with values from functions of the point.
inline TestTrace make_trace(std::string name, std::string flap, std::string side, std::vector<Vec2> points,
                            const std::function<double(const Vec2&)>& p,
                            const std::function<double(const Vec2&)>& tau, double fluid_side) {
  TestTrace t{std::move(name), std::move(flap), std::move(side), std::move(points), {}, {}, fluid_side};
  for (const auto& x : t.points) {
    t.pressure.push_back(p(x));
    t.wall_shear.push_back(tau(x));
  }
  return t;
}

// A flow file whose mesh is one row of quads on the fluid side of each trace plus one triangle,
// with each trace's normals leaving the fluid (flow 1.4), as tfmb-flow writes them.
inline void write_flow(const std::filesystem::path& file, const std::vector<TestTrace>& traces) {
  std::vector<Vec2> points;
  std::vector<std::array<std::int64_t, 4>> quads;
  std::map<std::string, std::vector<std::int64_t>> nodes;
  for (const auto& t : traces) {
    const auto base = static_cast<std::int64_t>(points.size());
    const std::size_t n = t.points.size();
    for (std::size_t i = 0; i < n; ++i) points.push_back(t.points[i]);
    for (std::size_t i = 0; i < n; ++i) {
      const std::size_t a = i == 0 ? 0 : i - 1, b = i + 1 < n ? i + 1 : i;
      const Vec2 e = (t.points[b] - t.points[a]).normalized();
      points.push_back(t.points[i] + 1e-4 * t.fluid_side * Vec2(-e.y(), e.x()));
    }
    for (std::size_t i = 0; i < n; ++i) nodes[t.name].push_back(base + static_cast<std::int64_t>(i));
    for (std::size_t i = 0; i + 1 < n; ++i) {
      const auto k = static_cast<std::int64_t>(i);
      const auto off = base + static_cast<std::int64_t>(n) + k;  // offset node of point k
      // counter-clockwise, as the flowmesh spec has cells: the offset row is on the trace's
      // left for fluid_side +1 and on its right for -1
      if (t.fluid_side > 0)
        quads.push_back({base + k, base + k + 1, off + 1, off});
      else
        quads.push_back({base + k, off, off + 1, base + k + 1});
    }
  }
  const auto N = static_cast<Eigen::Index>(points.size());
  h5::Writer w(file);
  write_root(w, "flow");
  w.write("/mesh/points", matrix(points), "m");
  h5::MatrixXiR tri(1, 3);
  const auto first_offset = static_cast<std::int64_t>(traces.front().points.size());
  if (traces.front().fluid_side > 0)
    tri << 0, 1, first_offset;
  else
    tri << 0, first_offset, 1;
  w.write("/mesh/cells/triangle", tri);
  h5::MatrixXiR q(static_cast<Eigen::Index>(quads.size()), 4);
  for (std::size_t c = 0; c < quads.size(); ++c) {
    for (int a = 0; a < 4; ++a) q(static_cast<Eigen::Index>(c), a) = quads[c][static_cast<std::size_t>(a)];
  }
  w.write("/mesh/cells/quad", q);
  std::vector<double> ones(static_cast<std::size_t>(N), 1.0);
  w.write("/fields/point/density", ones, "kg/m^3");
  w.write("/fields/point/velocity", h5::MatrixXdR(h5::MatrixXdR::Zero(N, 3)), "m/s");
  w.write("/fields/point/pressure", ones, "Pa");
  w.write("/fields/point/temperature", ones, "K");
  w.write("/fields/point/mach", ones, "1");
  for (const auto& t : traces) {
    const auto& ids = nodes[t.name];
    h5::MatrixXiR edges(static_cast<Eigen::Index>(ids.size() - 1), 2);
    for (std::size_t i = 0; i + 1 < ids.size(); ++i) {
      edges(static_cast<Eigen::Index>(i), 0) = ids[i];
      edges(static_cast<Eigen::Index>(i), 1) = ids[i + 1];
    }
    const std::string b = "/mesh/boundaries/" + t.name;
    w.write(b + "/edges", edges);
    w.set_attr(b, "kind", "wall");
    if (!t.flap.empty()) {
      w.set_attr(b, "flap", t.flap);
      w.set_attr(b, "side", t.side);
    }
    const std::string g = "/walls/" + t.name;
    std::vector<double> x, y, s, temperature(ids.size(), 300.0), flux(ids.size(), 0.0);
    double length = 0.0;
    for (std::size_t i = 0; i < t.points.size(); ++i) {
      if (i > 0) length += (t.points[i] - t.points[i - 1]).norm();
      x.push_back(t.points[i].x());
      y.push_back(t.points[i].y());
      s.push_back(length);
    }
    w.write(g + "/node", ids);
    w.write(g + "/s", s, "m");
    w.write(g + "/x", x, "m");
    w.write(g + "/y", y, "m");
    w.write(g + "/pressure", t.pressure, "Pa");
    w.write(g + "/temperature", temperature, "K");
    w.write(g + "/wall_shear", t.wall_shear, "Pa");
    w.write(g + "/heat_flux", flux, "W/m^2");
    // flow 1.4: the unit normal leaving the fluid, i.e. away from the fluid side of the points.
    h5::MatrixXdR normal(static_cast<Eigen::Index>(t.points.size()), 2);
    for (std::size_t i = 0; i < t.points.size(); ++i) {
      const std::size_t a = i == 0 ? 0 : i - 1, b = i + 1 < t.points.size() ? i + 1 : i;
      const Vec2 e = (t.points[b] - t.points[a]).normalized();
      normal.row(static_cast<Eigen::Index>(i)) = -t.fluid_side * Vec2(-e.y(), e.x()).transpose();
    }
    w.write(g + "/normal", normal, "1");
  }
  for (const char* name : {"mass_flow", "thrust_x", "thrust_y", "thrust_angle", "discharge_coefficient"}) {
    w.set_attr("/integrals", name, 0.5);
  }
  w.set_attr("/conditions", "stagnation_pressure", 2e5);
  w.set_attr("/conditions", "stagnation_temperature", 300.0);
  w.set_attr("/conditions", "ambient_pressure", 1e5);
  w.set_attr("/conditions", "gamma", 1.4);
  w.set_attr("/conditions", "gas_constant", 287.0);
  w.set_attr("/convergence", "converged", std::int64_t{1});
  w.set_attr("/convergence", "criterion", "test");
  w.set_attr("/convergence", "iterations", std::int64_t{1});
  w.write("/convergence/residual_history", h5::MatrixXdR(h5::MatrixXdR::Ones(1, 4)), "1");
  w.commit();
}

// Structure file: per flap its beam nodes (in order) with displacement, Wiener-Milenkovic
// rotation about z and per segment sectional strain and force.
struct TestStructureFlap {
  std::string name;
  std::vector<Vec2> points;
  std::vector<Vec2> displacement;
  std::vector<double> rotation_angle;                 // [rad]
  std::vector<std::array<double, 6>> sectional_strain;  // per segment
  std::vector<std::array<double, 6>> sectional_force;
};

inline void write_structure(const std::filesystem::path& file, const std::vector<TestStructureFlap>& flaps) {
  std::vector<Vec2> points, displacement;
  std::vector<double> rz;
  std::vector<std::array<double, 6>> strain, force;
  std::vector<std::array<std::int64_t, 2>> segments;
  h5::Writer w(file);
  write_root(w, "structure");
  w.set_attr("/", "analysis", "static");
  w.set_attr("/", "converged", std::int64_t{1});
  for (const auto& f : flaps) {
    const auto base = static_cast<std::int64_t>(points.size());
    const auto seg0 = static_cast<std::int64_t>(segments.size());
    std::vector<std::int64_t> ids, segs;
    for (std::size_t i = 0; i < f.points.size(); ++i) {
      points.push_back(f.points[i]);
      displacement.push_back(i < f.displacement.size() ? f.displacement[i] : Vec2::Zero());
      rz.push_back(i < f.rotation_angle.size() ? f.rotation_angle[i] : 0.0);
      ids.push_back(base + static_cast<std::int64_t>(i));
    }
    for (std::size_t e = 0; e + 1 < f.points.size(); ++e) {
      segments.push_back({base + static_cast<std::int64_t>(e), base + static_cast<std::int64_t>(e) + 1});
      strain.push_back(e < f.sectional_strain.size() ? f.sectional_strain[e] : std::array<double, 6>{});
      force.push_back(e < f.sectional_force.size() ? f.sectional_force[e] : std::array<double, 6>{});
      segs.push_back(seg0 + static_cast<std::int64_t>(e));
    }
    w.write("/flaps/" + f.name + "/nodes", ids);
    w.write("/flaps/" + f.name + "/segments", segs);
  }
  const auto N = static_cast<Eigen::Index>(points.size());
  const auto E = static_cast<Eigen::Index>(segments.size());
  w.write("/beam/points", matrix(points, 3), "m");
  h5::MatrixXiR seg(E, 2);
  h5::MatrixXdR s6(E, 6), f6(E, 6);
  for (Eigen::Index e = 0; e < E; ++e) {
    seg(e, 0) = segments[static_cast<std::size_t>(e)][0];
    seg(e, 1) = segments[static_cast<std::size_t>(e)][1];
    for (int k = 0; k < 6; ++k) {
      s6(e, k) = strain[static_cast<std::size_t>(e)][static_cast<std::size_t>(k)];
      f6(e, k) = force[static_cast<std::size_t>(e)][static_cast<std::size_t>(k)];
    }
  }
  w.write("/beam/segments", seg);
  w.write("/fields/point/displacement", matrix(displacement, 3), "m");
  h5::MatrixXdR rot = h5::MatrixXdR::Zero(N, 3);
  for (Eigen::Index i = 0; i < N; ++i) rot(i, 2) = 4.0 * std::tan(rz[static_cast<std::size_t>(i)] / 4.0);
  w.write("/fields/point/rotation", rot, "1");
  w.write("/fields/cell/sectional_strain", s6, "1");
  w.write("/fields/cell/sectional_force", f6, "N");
  w.commit();
}

// Thermal file: per flap the mean temperature and through-thickness difference of each beam
// element (the solid mesh is one triangle: tfmb-matmap reads only /beam).
inline void write_thermal(const std::filesystem::path& file,
                          const std::map<std::string, std::pair<std::vector<double>, std::vector<double>>>& beams) {
  h5::Writer w(file);
  write_root(w, "thermal");
  h5::MatrixXdR p(3, 2);
  p << 0, 0, 1, 0, 0, 1;
  w.write("/mesh/points", p, "m");
  h5::MatrixXiR tri(1, 3);
  tri << 0, 1, 2;
  w.write("/mesh/cells/triangle", tri);
  w.write("/mesh/cells/quad", h5::MatrixXiR(0, 4));
  w.write("/fields/point/temperature", std::vector<double>{300, 300, 300}, "K");
  for (const auto& [flap, values] : beams) {
    w.write_array("/beam/" + flap + "/mean_temperature", values.first, {values.first.size()}, "K");
    w.write_array("/beam/" + flap + "/delta_temperature", values.second, {values.second.size()}, "K");
  }
  w.commit();
}

}  // namespace tfmb::testfiles
