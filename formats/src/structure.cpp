// The structure kind's one reader and writer: formats/structure.md (schema in
// schema_structure.cpp).
#include "tfmb/formats/structure.hpp"

#include <limits>

#include "rows.hpp"
#include "tfmb/common/errors.hpp"
#include "tfmb/common/h5.hpp"
#include "tfmb/formats/schema.hpp"

namespace tfmb::formats {
namespace {

// Units of the optional scalar joint outputs (structure.md).
const std::map<std::string, std::string>& joint_scalar_units() {
  static const std::map<std::string, std::string> units = {{"relative_rotation", "rad"},
                                                           {"contact_force", "N"},
                                                           {"gap", "m"},
                                                           {"sliding", "m"},
                                                           {"strain_energy", "J"}};
  return units;
}

std::vector<double> flat(const std::vector<std::vector<Eigen::Vector3d>>& snapshots) {
  std::vector<double> out;
  for (const auto& snapshot : snapshots)
    for (const auto& p : snapshot)
      out.insert(out.end(), {p.x(), p.y(), p.z()});
  return out;
}

// (steps, nodes, 3) stacks: /history/displacement, /modes/displacement.
std::vector<std::vector<Eigen::Vector3d>> read_snapshots(const h5::Reader& r,
                                                         const std::string& path, std::size_t steps,
                                                         std::size_t nodes) {
  std::vector<std::size_t> shape;
  const std::vector<double> values = r.read_f64(path, &shape);
  if (shape != std::vector<std::size_t>{steps, nodes, 3})
    r.fail(path, "shape must be (" + std::to_string(steps) + "," + std::to_string(nodes) + ",3)");
  std::vector<std::vector<Eigen::Vector3d>> out(steps, std::vector<Eigen::Vector3d>(nodes));
  for (std::size_t t = 0; t < steps; ++t)
    for (std::size_t i = 0; i < nodes; ++i) {
      const std::size_t k = 3 * (t * nodes + i);
      out[t][i] = Eigen::Vector3d(values[k], values[k + 1], values[k + 2]);
    }
  return out;
}

void read_flaps(const h5::Reader& r, Structure& s) {
  const auto node_count = static_cast<std::int64_t>(s.points.size());
  const auto segment_count = static_cast<std::int64_t>(s.segments.size());
  for (const std::string& name : r.children("/flaps")) {
    const std::string g = "/flaps/" + name;
    StructureFlap f;
    f.name = name;
    f.nodes = r.read_index_vector(g + "/nodes", std::nullopt, 0, node_count);
    if (f.nodes.size() < 2)
      r.fail(g + "/nodes", "fewer than two beam nodes");
    f.segments = r.read_index_vector(g + "/segments", std::nullopt, 0, segment_count);
    for (std::size_t k = 1; k < f.segments.size(); ++k) {
      if (s.segments[static_cast<std::size_t>(f.segments[k - 1])][1] !=
          s.segments[static_cast<std::size_t>(f.segments[k])][0])
        r.fail(g + "/segments", "segment " + std::to_string(k) + " does not start where segment " +
                                    std::to_string(k - 1) + " ends");
    }
    s.flaps.push_back(std::move(f));
  }
}

void read_joints(const h5::Reader& r, Structure& s) {
  if (!r.is_group("/joints"))
    return;
  for (const std::string& name : r.children("/joints")) {
    const std::string g = "/joints/" + name;
    StructureJoint j;
    j.name = name;
    const std::vector<double> reaction = r.read_vector(g + "/reaction", 6);
    j.reaction = Eigen::Map<const Vector6>(reaction.data());
    for (const auto& [scalar, units] : joint_scalar_units()) {
      (void)units;
      if (r.exists(g + "/" + scalar))
        j.scalars[scalar] = r.read_vector(g + "/" + scalar, 1)[0];
    }
    if (r.exists(g + "/deformation")) {
      const std::vector<double> d = r.read_vector(g + "/deformation", 6);
      j.deformation = Eigen::Map<const Vector6>(d.data());
    }
    s.joints.push_back(std::move(j));
  }
}

void read_restart(const h5::Reader& r, Structure& s) {
  if (!r.exists("/restart/velocity"))
    return;
  const std::size_t n = s.points.size();
  StructureRestart restart;
  restart.velocity = detail::read_rows<3>(r, "/restart/velocity", n);
  if (!r.exists("/restart/angular_velocity"))
    r.fail("/restart", "angular_velocity missing beside velocity");
  restart.angular_velocity = detail::read_rows<3>(r, "/restart/angular_velocity", n);
  if (r.exists("/restart/joint_dofs")) {
    restart.joint_dofs = r.read_vector("/restart/joint_dofs");
    restart.joint_rates = r.read_vector("/restart/joint_rates", restart.joint_dofs.size());
  }
  if (r.has_attr("/restart", "time"))
    restart.time = r.attr_f64("/restart", "time");
  s.restart = std::move(restart);
}

// /path (1.3): optional as a whole; once load_factor is there the rest must be whole too.
void read_path(const h5::Reader& r, Structure& s) {
  if (!r.exists("/path/load_factor")) {
    if (r.exists("/path"))
      r.fail("/path", "load_factor missing");
    return;
  }
  StructurePath p;
  p.load_factor = r.read_vector("/path/load_factor");
  const std::size_t rows = p.load_factor.size();
  if (rows == 0)
    r.fail("/path/load_factor", "empty (row 0 is the unloaded start)");
  p.arc_length = r.read_vector("/path/arc_length", rows);
  for (std::size_t i = 0; i < rows; ++i)
    if (p.arc_length[i] < (i == 0 ? 0.0 : p.arc_length[i - 1]))
      r.fail("/path/arc_length", "row " + std::to_string(i) + " decreases or is negative (" +
                                     std::to_string(p.arc_length[i]) + "); expected a path length");
  p.max_displacement = r.read_vector("/path/max_displacement", rows);
  p.characteristic_displacement = r.read_vector("/path/characteristic_displacement", rows);
  p.iterations =
      r.read_index_vector("/path/iterations", rows, 0, std::numeric_limits<std::int64_t>::max());
  const auto limit = static_cast<std::int64_t>(rows);
  p.limit_points_load = r.read_index_vector("/path/limit_points_load", std::nullopt, 0, limit);
  p.limit_points_displacement =
      r.read_index_vector("/path/limit_points_displacement", std::nullopt, 0, limit);
  if (r.exists("/path/node_displacement"))
    p.node_displacement = detail::read_rows<3>(r, "/path/node_displacement", rows);
  if (r.has_attr("/path", "method"))
    p.method = r.attr_string("/path", "method");
  if (p.method != "load_stepping" && p.method != "arc_length")
    r.fail("/path", "attribute method '" + p.method + "' is neither load_stepping nor arc_length");
  if (r.has_attr("/path", "monitor"))
    p.monitor = r.attr_string("/path", "monitor");
  s.path = std::move(p);
}

}  // namespace

void write_structure(const std::filesystem::path& file, const Structure& s,
                     const Provenance& provenance) {
  h5::Writer w(file);
  write_header(w, "structure", s.header);
  w.set_attr("/", "analysis", s.analysis);
  w.set_attr("/", "converged", static_cast<std::int64_t>(s.converged ? 1 : 0));
  w.write("/beam/points", detail::rows(s.points), "m", "beam node reference positions");
  h5::MatrixXiR segments(static_cast<Eigen::Index>(s.segments.size()), 2);
  for (std::size_t k = 0; k < s.segments.size(); ++k)
    segments.row(static_cast<Eigen::Index>(k)) << s.segments[k][0], s.segments[k][1];
  w.write("/beam/segments", segments, "1", "display segments (two per quadratic element)");
  w.write("/fields/point/displacement", detail::rows(s.displacement), "m");
  w.write("/fields/point/rotation", detail::rows(s.rotation), "1",
          "Wiener-Milenkovic rotation parameters");
  w.write("/fields/cell/sectional_strain", detail::rows(s.sectional_strain), "1, 1/m",
          "per segment (Gauss point of the element half): axial, 2 shear, torsion, 2 curvatures");
  w.write("/fields/cell/sectional_force", detail::rows(s.sectional_force), "N, N m",
          "axial, 2 shear forces, torsion, 2 bending moments");
  for (const StructureFlap& f : s.flaps) {
    w.write("/flaps/" + f.name + "/nodes", f.nodes);
    w.write("/flaps/" + f.name + "/segments", f.segments);
  }
  for (const StructureJoint& j : s.joints) {
    const std::string g = "/joints/" + j.name;
    w.write(g + "/reaction", std::vector<double>(j.reaction.data(), j.reaction.data() + 6),
            "N, N m", "force and moment on the structure from the joint");
    for (const auto& [name, value] : j.scalars) {
      const auto units = joint_scalar_units().find(name);
      if (units == joint_scalar_units().end())
        throw InternalError("structure: unknown joint output '" + name + "'");
      w.write(g + "/" + name, std::vector<double>{value}, units->second);
    }
    if (j.deformation)
      w.write(g + "/deformation",
              std::vector<double>(j.deformation->data(), j.deformation->data() + 6), "m, 1",
              "stretch (3) and wryness (3) in the joint frame");
  }
  const std::size_t n = s.points.size();
  if (!s.history_time.empty()) {
    w.write("/history/time", s.history_time, "s");
    w.write_array("/history/displacement", flat(s.history_displacement),
                  {s.history_time.size(), n, 3}, "m");
  }
  if (!s.mode_frequency.empty()) {
    w.write("/modes/frequency", s.mode_frequency, "Hz",
            "natural frequencies about the reference state");
    w.write_array(
        "/modes/displacement", flat(s.mode_displacement), {s.mode_frequency.size(), n, 3}, "1",
        "nodal translations of each mode, divided by the largest entry of the mode vector");
  }
  if (s.restart) {
    w.write("/restart/velocity", detail::rows(s.restart->velocity), "m/s",
            "nodal velocity at the end of the run");
    w.write("/restart/angular_velocity", detail::rows(s.restart->angular_velocity), "rad/s",
            "nodal angular velocity, material frame");
    if (!s.restart->joint_dofs.empty()) {
      w.write("/restart/joint_dofs", s.restart->joint_dofs, "rad",
              "joint unknowns (e.g. revolute relative angles)");
      w.write("/restart/joint_rates", s.restart->joint_rates, "rad/s",
              "rates of the joint unknowns");
    }
    w.set_attr("/restart", "time", s.restart->time);
  }
  if (s.path) {
    const StructurePath& p = *s.path;
    const std::size_t rows = p.load_factor.size();
    if (rows == 0 || p.arc_length.size() != rows || p.max_displacement.size() != rows ||
        p.characteristic_displacement.size() != rows || p.iterations.size() != rows ||
        (!p.node_displacement.empty() && p.node_displacement.size() != rows))
      throw InternalError("structure: /path columns of unequal length");
    w.write("/path/load_factor", p.load_factor, "1", "load factor; row 0 the unloaded start");
    w.write("/path/arc_length", p.arc_length, "m", "path length in the nodal translations");
    w.write("/path/max_displacement", p.max_displacement, "m", "largest nodal displacement");
    w.write(
        "/path/characteristic_displacement", p.characteristic_displacement, "m",
        "the monitored node's displacement along the monitor's direction, else max_displacement");
    if (!p.node_displacement.empty())
      w.write("/path/node_displacement", detail::rows(p.node_displacement), "m",
              "displacement of the monitored node");
    w.write("/path/iterations", p.iterations, "1", "Newton iterations of the step");
    w.write("/path/limit_points_load", p.limit_points_load, "1",
            "rows where the load-factor increment changes sign");
    w.write("/path/limit_points_displacement", p.limit_points_displacement, "1",
            "rows where the characteristic displacement's increment changes sign");
    w.set_attr("/path", "method", p.method);
    if (!p.monitor.empty())
      w.set_attr("/path", "monitor", p.monitor);
  }
  write_provenance(w, provenance);
  w.commit();
  write_xdmf_sidecar(file);
}

Structure read_structure(const std::filesystem::path& file) {
  const h5::Reader r = open_checked(file, "structure");
  Structure s;
  s.source = file;
  s.header = read_header(r);
  s.analysis = r.attr_string("/", "analysis");
  s.converged = r.attr_i64("/", "converged") == 1;
  const auto n = static_cast<std::size_t>(r.info("/beam/points").shape.at(0));
  s.points = detail::read_rows<3>(r, "/beam/points", n);
  const h5::MatrixXiR segments =
      r.read_index_matrix("/beam/segments", std::nullopt, 2, 0, static_cast<std::int64_t>(n));
  for (Eigen::Index k = 0; k < segments.rows(); ++k)
    s.segments.push_back({segments(k, 0), segments(k, 1)});
  s.displacement = detail::read_rows<3>(r, "/fields/point/displacement", n);
  s.rotation = detail::read_rows<3>(r, "/fields/point/rotation", n);
  s.sectional_strain = detail::read_rows<6>(r, "/fields/cell/sectional_strain", s.segments.size());
  s.sectional_force = detail::read_rows<6>(r, "/fields/cell/sectional_force", s.segments.size());
  read_flaps(r, s);
  read_joints(r, s);
  if (r.exists("/history/time")) {
    s.history_time = r.read_vector("/history/time");
    s.history_displacement = read_snapshots(r, "/history/displacement", s.history_time.size(), n);
  }
  if (r.exists("/modes/frequency")) {
    s.mode_frequency = r.read_vector("/modes/frequency");
    s.mode_displacement = read_snapshots(r, "/modes/displacement", s.mode_frequency.size(), n);
  }
  read_restart(r, s);
  read_path(r, s);
  return s;
}

}  // namespace tfmb::formats
