// The model kind's one reader and writer: formats/model.md (schema in schema_model.cpp).
#include "tfmb/formats/model.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "tfmb/common/errors.hpp"
#include "tfmb/common/h5.hpp"
#include "tfmb/formats/schema.hpp"

namespace tfmb::formats {
namespace {

h5::MatrixXdR to_matrix(const Polyline& line) {
  h5::MatrixXdR m(static_cast<Eigen::Index>(line.size()), 2);
  for (std::size_t i = 0; i < line.size(); ++i)
    m.row(static_cast<Eigen::Index>(i)) = line[i].transpose();
  return m;
}
Polyline to_polyline(const h5::MatrixXdR& m) {
  Polyline line;
  for (Eigen::Index i = 0; i < m.rows(); ++i)
    line.emplace_back(m(i, 0), m(i, 1));
  return line;
}
std::vector<double> to_vector(const Point& p) {
  return {p.x(), p.y()};
}
std::string join(const std::vector<std::string>& parts) {
  std::string text;
  for (const auto& p : parts)
    text += (text.empty() ? "" : ",") + p;
  return text;
}
std::vector<std::string> split(const std::string& text) {
  std::vector<std::string> parts;
  std::stringstream stream(text);
  for (std::string p; std::getline(stream, p, ',');)
    parts.push_back(p);
  return parts;
}

// What the schema cannot say: sizes that must agree, a section that is not singular.
void check_flap(const h5::Reader& r, const std::string& g, const Flap& f) {
  if (!(f.thickness > 0.0))
    r.fail(g, "thickness must be positive");
  if (!(f.width > 0.0))
    r.fail(g, "width must be positive");
  if (f.reference_curve.size() != static_cast<std::size_t>(f.elements) + 1)
    r.fail(g + "/reference_curve",
           "expected elements+1 = " + std::to_string(f.elements + 1) + " rows");
  if (f.reference_geometry.size() < 2)
    r.fail(g + "/reference_geometry", "fewer than two points");
  if (f.inner_wall.size() < 2)
    r.fail(g + "/inner_wall", "fewer than two points");
  if (f.outer_wall.size() != f.inner_wall.size())
    r.fail(g + "/outer_wall",
           "must have as many points as inner_wall (" + std::to_string(f.inner_wall.size()) + ")");
  if (f.inner_wall_s.size() != f.inner_wall.size())
    r.fail(g + "/wall_arc_length",
           "must have one entry per wall point (" + std::to_string(f.inner_wall.size()) + ")");
  if (f.solid_outline.size() < 3)
    r.fail(g + "/solid_outline", "fewer than three points");
  for (int i = 0; i < 6; ++i)
    if (!(f.section.stiffness(i, i) > 0.0))
      r.fail(g + "/section_stiffness", "diagonal entry " + std::to_string(i) + " must be > 0");
  if (!(f.section.mass(0, 0) >= 0.0))
    r.fail(g + "/section_mass", "mass per length must be >= 0");
}

// Rows (coefficient, power of sigma, power of |p|) of a custom measure function (model 2.1).
void check_terms(const h5::Reader& r, const std::string& path, const Eigen::MatrixX3d& terms) {
  for (Eigen::Index i = 0; i < terms.rows(); ++i) {
    const double p = terms(i, 1), q = terms(i, 2);
    if (!(p >= 0.0 && q >= 0.0) || p != std::floor(p) || q != std::floor(q))
      r.fail(path, "row " + std::to_string(i) + ": powers must be integers >= 0");
  }
}

// The datasets and values each joint kind needs (model.md, "Joints").
void check_joint(const h5::Reader& r, const std::string& g, const Joint& j) {
  for (const std::string* end : {&j.end_a, &j.end_b})
    if (*end != "start" && *end != "end")
      r.fail(g, "end '" + *end + "' is neither start nor end");
  if (j.kind == "flexible") {
    if (!r.exists(g + "/stiffness_matrix"))
      r.fail(g, "a flexible joint needs /stiffness_matrix");
    // Model 2.0 had constant coefficients that no tool read; refuse them rather than ignore them.
    if ((r.has_attr(g, "measure_lambda") && r.attr_f64(g, "measure_lambda") != 0.0) ||
        (r.has_attr(g, "measure_mu") && r.attr_f64(g, "measure_mu") != 1.0))
      r.fail(g,
             "constant measure_lambda/measure_mu (model 2.0) are not supported; give "
             "measure_functions (model 2.1)");
    if (j.measure_functions == "custom") {
      check_terms(r, g + "/lambda_terms", j.lambda_terms);
      check_terms(r, g + "/mu_terms", j.mu_terms);
    }
  } else if (j.kind == "prismatic") {
    if (!r.exists(g + "/axis"))
      r.fail(g, "a prismatic joint needs /axis");
    if (!(j.axis.norm() > 1e-12))
      r.fail(g + "/axis", "zero sliding direction");
  } else if (j.kind == "prescribed_rotation") {
    if (j.rotation_table.rows() < 1)
      r.fail(g, "prescribed_rotation needs /rotation_table with at least one row");
  } else if (j.kind == "revolute_clearance") {
    if (!(j.outer_radius >= j.inner_radius))
      r.fail(g, "outer_radius must be at least inner_radius (bore around the pin)");
  }
}

}  // namespace

void write_model(const Model& model, const std::filesystem::path& file, const std::string& creator,
                 const Provenance& provenance) {
  h5::Writer w(file);
  Header header;
  header.creator = creator;
  header.geometry = model.geometry;
  header.depth = model.depth;
  write_header(w, "model", header);
  if (!model.title.empty())
    w.set_attr("/", "title", model.title);
  w.create_group("/flaps");
  for (std::size_t i = 0; i < model.flaps.size(); ++i) {
    const Flap& f = model.flaps[i];
    const std::string g = "/flaps/" + f.name;
    w.create_group(g);
    w.set_attr(g, "order", static_cast<std::int64_t>(i));
    w.set_attr(g, "material", f.material);
    w.set_attr(g, "thickness", f.thickness);
    w.set_attr(g, "width", f.width);
    w.set_attr(g, "half", f.half);
    w.set_attr(g, "elements", static_cast<std::int64_t>(f.elements));
    w.set_attr(g, "curves", join(f.curves));
    w.set_attr(g, "section_kind", f.section.kind);
    if (f.section.kind == "rectangle") {
      w.set_attr(g, "youngs_modulus", f.section.youngs_modulus);
      w.set_attr(g, "poisson_ratio", f.section.poisson_ratio);
      w.set_attr(g, "density", f.section.density);
    }
    w.write(g + "/reference_geometry", to_matrix(f.reference_geometry), "m",
            "beam reference line, full resolution");
    w.write(g + "/reference_curve", to_matrix(f.reference_curve), "m", "beam nodes");
    w.write(g + "/section_stiffness", h5::MatrixXdR(f.section.stiffness), "N, N m, N m^2",
            "axial, shear 2, shear 3, torsion, bending 2, bending 3");
    w.write(g + "/section_mass", h5::MatrixXdR(f.section.mass), "kg/m, kg m",
            "same order as the stiffness");
    w.write(g + "/inner_wall", to_matrix(f.inner_wall), "m", "surface facing the axis");
    w.write(g + "/outer_wall", to_matrix(f.outer_wall), "m", "opposite surface");
    w.write(g + "/wall_arc_length", f.inner_wall_s, "m", "arc length of each wall point's foot");
    w.write(g + "/solid_outline", to_matrix(f.solid_outline), "m",
            "thickness region, counter-clockwise");
  }
  w.create_group("/joints");
  for (const Joint& j : model.joints) {
    const std::string g = "/joints/" + j.name;
    w.create_group(g);
    w.set_attr(g, "kind", j.kind);
    w.set_attr(g, "flap_a", j.flap_a);
    w.set_attr(g, "end_a", j.end_a);
    w.set_attr(g, "flap_b", j.flap_b);
    w.set_attr(g, "end_b", j.end_b);
    w.write(g + "/point", to_vector(j.point), "m", "joint location");
    if (j.kind == "revolute_spring") {
      w.set_attr(g, "stiffness", j.stiffness);
      w.set_attr(g, "damping", j.damping);
    } else if (j.kind == "revolute_clearance") {
      w.set_attr(g, "inner_radius", j.inner_radius);
      w.set_attr(g, "outer_radius", j.outer_radius);
      w.set_attr(g, "contact_stiffness", j.contact_stiffness);
      w.set_attr(g, "friction", j.friction);
    } else if (j.kind == "flexible") {
      w.write(g + "/stiffness_matrix", h5::MatrixXdR(j.stiffness_matrix), "N/m, N m/rad",
              "joint stiffness");
      w.set_attr(g, "deformation_measure", j.deformation_measure);
      w.set_attr(g, "measure_functions", j.measure_functions);
      if (j.measure_functions == "custom") {
        w.write(g + "/lambda_terms", h5::MatrixXdR(j.lambda_terms), "1",
                "lambda: rows (coefficient, power of sigma, power of |p|)");
        w.write(g + "/mu_terms", h5::MatrixXdR(j.mu_terms), "1",
                "mu: rows (coefficient, power of sigma, power of |p|)");
      }
    } else if (j.kind == "prismatic") {
      w.write(g + "/axis", to_vector(j.axis), "1", "sliding direction");
    } else if (j.kind == "prescribed_rotation") {
      w.write(g + "/rotation_table", h5::MatrixXdR(j.rotation_table), "s, rad", "time, angle");
    }
  }
  w.create_group("/supports");
  for (const Support& s : model.supports) {
    const std::string g = "/supports/" + s.name;
    w.create_group(g);
    w.set_attr(g, "flap", s.flap);
    w.set_attr(g, "end", s.end);
    w.set_attr(g, "kind", s.kind);
    w.write(g + "/point", to_vector(s.point), "m", "support location");
    if (s.slides())
      w.write(g + "/axis", to_vector(s.axis), "1", "sliding direction");
  }
  const DomainSettings& d = model.domain.settings;
  w.create_group("/domain");
  w.set_attr("/domain", "kind", d.kind);
  if (d.kind == "nozzle") {
    w.set_attr("/domain", "plenum_length", d.plenum_length);
    w.set_attr("/domain", "downstream_length", d.downstream_length);
    w.set_attr("/domain", "farfield_height", d.farfield_height);
    w.set_attr("/domain", "boattail", static_cast<std::int64_t>(d.boattail ? 1 : 0));
  } else if (d.kind == "channel") {
    w.set_attr("/domain", "wall_curve", d.wall_curve);
  } else if (d.kind == "flatplate") {
    w.set_attr("/domain", "plate_length", d.plate_length);
    w.set_attr("/domain", "upstream_length", d.upstream_length);
    w.set_attr("/domain", "farfield_height", d.farfield_height);
  }
  w.create_group("/domain/boundaries");
  for (std::size_t i = 0; i < model.domain.boundaries.size(); ++i) {
    const DomainBoundary& b = model.domain.boundaries[i];
    const std::string g = "/domain/boundaries/" + b.name;
    w.create_group(g);
    w.set_attr(g, "kind", b.kind);
    w.set_attr(g, "order", static_cast<std::int64_t>(i));
    if (!b.flap.empty())
      w.set_attr(g, "flap", b.flap);
    if (!b.side.empty())
      w.set_attr(g, "side", b.side);
    w.write(g + "/points", to_matrix(b.points), "m", "boundary piece, domain on the left");
  }
  const FlowConditions& c = model.flow;
  w.create_group("/conditions");
  w.set_attr("/conditions", "nozzle_pressure_ratio", c.nozzle_pressure_ratio);
  w.set_attr("/conditions", "stagnation_temperature", c.stagnation_temperature);
  w.set_attr("/conditions", "ambient_pressure", c.ambient_pressure);
  w.set_attr("/conditions", "ambient_temperature", c.ambient_temperature);
  w.set_attr("/conditions", "ambient_mach", c.ambient_mach);
  w.set_attr("/conditions", "exit_pressure_ratio", c.exit_pressure_ratio);
  w.set_attr("/conditions", "gamma", c.gamma);
  w.set_attr("/conditions", "gas_constant", c.gas_constant);
  w.set_attr("/conditions", "prandtl", c.prandtl);
  w.set_attr("/conditions", "turbulent_prandtl", c.turbulent_prandtl);
  w.set_attr("/conditions", "turbulence", c.turbulence);
  w.set_attr("/conditions", "reference_length", c.reference_length);
  w.set_attr("/conditions", "yplus_target", c.yplus_target);
  w.set_attr("/conditions", "first_cell_height", c.first_cell_height);
  w.set_attr("/conditions", "viscous_length", c.viscous_length);
  const ThermalSettings& t = model.thermal;
  w.create_group("/thermal");
  w.set_attr("/thermal", "flow_wall", t.flow_wall);
  w.set_attr("/thermal", "wall_temperature", t.wall_temperature);
  w.set_attr("/thermal", "solid_boundary", t.solid_boundary);
  w.set_attr("/thermal", "emissivity", t.emissivity);
  w.set_attr("/thermal", "reference_temperature", t.reference_temperature);
  const MeshControls& m = model.mesh;
  const std::string mc = "/mesh_controls";
  w.create_group(mc);
  w.set_attr(mc, "wall_size", m.wall_size);
  w.set_attr(mc, "far_size", m.far_size);
  w.set_attr(mc, "growth", m.growth);
  w.set_attr(mc, "max_layers", static_cast<std::int64_t>(m.max_layers));
  w.set_attr(mc, "scale", m.scale);
  w.set_attr(mc, "cells_along", static_cast<std::int64_t>(m.cells_along));
  w.set_attr(mc, "cells_across", static_cast<std::int64_t>(m.cells_across));
  w.set_attr(mc, "cells_upstream", static_cast<std::int64_t>(m.cells_upstream));
  w.set_attr(mc, "leading_edge_spacing", m.leading_edge_spacing);
  w.set_attr(mc, "cells_per_circle", static_cast<std::int64_t>(m.cells_per_circle));
  w.set_attr(mc, "end_cells", static_cast<std::int64_t>(m.end_cells));
  w.set_attr(mc, "solid_cells_per_element", static_cast<std::int64_t>(m.solid_cells_per_element));
  w.set_attr(mc, "solid_layers", static_cast<std::int64_t>(m.solid_layers));
  const AnalysisSettings& a = model.analysis;
  w.create_group("/analysis");
  w.set_attr("/analysis", "kind", a.kind);
  w.set_attr("/analysis", "time", a.time);
  w.set_attr("/analysis", "end_time", a.end_time);
  w.set_attr("/analysis", "time_step", a.time_step);
  w.set_attr("/analysis", "load_steps", static_cast<std::int64_t>(a.load_steps));
  w.set_attr("/analysis", "max_coupling_iterations",
             static_cast<std::int64_t>(a.max_coupling_iterations));
  w.set_attr("/analysis", "coupling_tolerance", a.coupling_tolerance);
  w.set_attr("/analysis", "convergence", a.convergence);
  w.set_attr("/analysis", "acceleration", a.acceleration);
  w.set_attr("/analysis", "relaxation", a.relaxation);
  write_provenance(w, provenance);
  w.commit();
}

namespace {

// Flaps, in their 'order'.
void read_flaps(const h5::Reader& r, Model& model) {
  std::vector<std::pair<std::int64_t, Flap>> flaps;
  for (const auto& name : r.children("/flaps")) {
    const std::string g = "/flaps/" + name;
    Flap f;
    f.name = name;
    f.material = r.attr_string(g, "material");
    f.thickness = r.attr_f64(g, "thickness");
    f.width = r.attr_f64(g, "width");
    f.half = r.attr_string(g, "half");
    f.elements = static_cast<int>(r.attr_i64(g, "elements"));
    f.curves = split(r.attr_string(g, "curves"));
    f.section.kind = r.attr_string(g, "section_kind");
    if (r.has_attr(g, "youngs_modulus"))
      f.section.youngs_modulus = r.attr_f64(g, "youngs_modulus");
    if (r.has_attr(g, "poisson_ratio"))
      f.section.poisson_ratio = r.attr_f64(g, "poisson_ratio");
    if (r.has_attr(g, "density"))
      f.section.density = r.attr_f64(g, "density");
    f.reference_geometry = to_polyline(r.read_matrix(g + "/reference_geometry", {}, 2));
    f.reference_curve = to_polyline(r.read_matrix(g + "/reference_curve", {}, 2));
    if (f.reference_curve.size() != static_cast<std::size_t>(f.elements) + 1) {
      r.fail(g + "/reference_curve",
             "expected elements+1 = " + std::to_string(f.elements + 1) + " rows");
    }
    f.section.stiffness = r.read_matrix(g + "/section_stiffness", 6, 6);
    f.section.mass = r.read_matrix(g + "/section_mass", 6, 6);
    f.inner_wall = to_polyline(r.read_matrix(g + "/inner_wall", {}, 2));
    f.outer_wall = to_polyline(r.read_matrix(g + "/outer_wall", {}, 2));
    f.inner_wall_s = r.read_vector(g + "/wall_arc_length");
    f.outer_wall_s = f.inner_wall_s;
    f.solid_outline = to_polyline(r.read_matrix(g + "/solid_outline", {}, 2));
    check_flap(r, g, f);
    flaps.emplace_back(r.attr_i64(g, "order"), std::move(f));
  }
  std::sort(flaps.begin(), flaps.end(),
            [](const auto& a, const auto& b) { return a.first < b.first; });
  for (auto& [order, f] : flaps)
    model.flaps.push_back(std::move(f));
}

// Joints between flap ends; each names flaps that exist.
void read_joints(const h5::Reader& r, Model& model) {
  for (const auto& name :
       r.is_group("/joints") ? r.children("/joints") : std::vector<std::string>{}) {
    const std::string g = "/joints/" + name;
    Joint j;
    j.name = name;
    j.kind = r.attr_string(g, "kind");
    j.flap_a = r.attr_string(g, "flap_a");
    j.end_a = r.attr_string(g, "end_a");
    j.flap_b = r.attr_string(g, "flap_b");
    j.end_b = r.attr_string(g, "end_b");
    const auto p = r.read_vector(g + "/point", 2);
    j.point = Point(p[0], p[1]);
    if (r.has_attr(g, "stiffness"))
      j.stiffness = r.attr_f64(g, "stiffness");
    if (r.has_attr(g, "damping"))
      j.damping = r.attr_f64(g, "damping");
    if (r.has_attr(g, "inner_radius"))
      j.inner_radius = r.attr_f64(g, "inner_radius");
    if (r.has_attr(g, "outer_radius"))
      j.outer_radius = r.attr_f64(g, "outer_radius");
    if (r.has_attr(g, "contact_stiffness"))
      j.contact_stiffness = r.attr_f64(g, "contact_stiffness");
    if (r.has_attr(g, "friction"))
      j.friction = r.attr_f64(g, "friction");
    if (r.has_attr(g, "deformation_measure"))
      j.deformation_measure = r.attr_string(g, "deformation_measure");
    if (r.has_attr(g, "measure_functions"))
      j.measure_functions = r.attr_string(g, "measure_functions");
    if (r.exists(g + "/lambda_terms"))
      j.lambda_terms = r.read_matrix(g + "/lambda_terms", {}, 3);
    if (r.exists(g + "/mu_terms"))
      j.mu_terms = r.read_matrix(g + "/mu_terms", {}, 3);
    if (r.exists(g + "/stiffness_matrix"))
      j.stiffness_matrix = r.read_matrix(g + "/stiffness_matrix", 6, 6);
    if (r.exists(g + "/rotation_table"))
      j.rotation_table = r.read_matrix(g + "/rotation_table", {}, 2);
    if (r.exists(g + "/axis")) {
      const auto a = r.read_vector(g + "/axis", 2);
      j.axis = Point(a[0], a[1]);
    }
    check_joint(r, g, j);
    for (const auto* flap : {&j.flap_a, &j.flap_b}) {
      if (!model.find_flap(*flap))
        r.fail(g, "joint refers to unknown flap '" + *flap + "'");
    }
    model.joints.push_back(j);
  }
}

// Supports to ground; sliding ones with their direction.
void read_supports(const h5::Reader& r, Model& model) {
  for (const auto& name :
       r.is_group("/supports") ? r.children("/supports") : std::vector<std::string>{}) {
    const std::string g = "/supports/" + name;
    Support s;
    s.name = name;
    s.flap = r.attr_string(g, "flap");
    s.end = r.attr_string(g, "end");
    s.kind = r.attr_string(g, "kind");
    const auto p = r.read_vector(g + "/point", 2);
    s.point = Point(p[0], p[1]);
    if (s.slides()) {
      if (!r.exists(g + "/axis"))
        r.fail(g, "a " + s.kind + " support needs /axis");
      const auto a = r.read_vector(g + "/axis", 2);
      s.axis = Point(a[0], a[1]);
      if (!(s.axis.norm() > 1e-12))
        r.fail(g + "/axis", "zero sliding direction");
    }
    if (!model.find_flap(s.flap))
      r.fail(g, "support refers to unknown flap '" + s.flap + "'");
    model.supports.push_back(s);
  }
}

// The flow domain: its kind and sizes, and its boundary loop (closed, in 'order').
void read_domain(const h5::Reader& r, Model& model) {
  DomainSettings& d = model.domain.settings;
  d.kind = r.attr_string("/domain", "kind");
  auto optional_f64 = [&](const std::string& object, const std::string& name, double& target) {
    if (r.has_attr(object, name))
      target = r.attr_f64(object, name);
  };
  optional_f64("/domain", "plenum_length", d.plenum_length);
  optional_f64("/domain", "downstream_length", d.downstream_length);
  optional_f64("/domain", "farfield_height", d.farfield_height);
  optional_f64("/domain", "plate_length", d.plate_length);
  optional_f64("/domain", "upstream_length", d.upstream_length);
  if (r.has_attr("/domain", "boattail"))
    d.boattail = r.attr_i64("/domain", "boattail") != 0;
  if (r.has_attr("/domain", "wall_curve"))
    d.wall_curve = r.attr_string("/domain", "wall_curve");
  if (r.is_group("/domain/boundaries")) {
    std::vector<std::pair<std::int64_t, DomainBoundary>> pieces;
    for (const auto& name : r.children("/domain/boundaries")) {
      const std::string g = "/domain/boundaries/" + name;
      DomainBoundary b;
      b.name = name;
      b.kind = r.attr_string(g, "kind");
      if (r.has_attr(g, "flap"))
        b.flap = r.attr_string(g, "flap");
      if (r.has_attr(g, "side"))
        b.side = r.attr_string(g, "side");
      b.points = to_polyline(r.read_matrix(g + "/points", {}, 2));
      if (b.points.size() < 2)
        r.fail(g + "/points", "a boundary piece needs at least 2 points");
      pieces.emplace_back(r.attr_i64(g, "order"), std::move(b));
    }
    std::sort(pieces.begin(), pieces.end(),
              [](const auto& a, const auto& b) { return a.first < b.first; });
    for (std::size_t i = 0; i < pieces.size(); ++i) {
      if (pieces[i].first != static_cast<std::int64_t>(i)) {
        r.fail("/domain/boundaries", "the 'order' attributes must be 0..n-1 without gaps");
      }
      model.domain.boundaries.push_back(std::move(pieces[i].second));
    }
    for (std::size_t i = 0; i < model.domain.boundaries.size(); ++i) {
      const auto& a = model.domain.boundaries[i];
      const auto& b = model.domain.boundaries[(i + 1) % model.domain.boundaries.size()];
      if ((a.points.back() - b.points.front()).norm() > 1e-9 * (1.0 + a.points.back().norm())) {
        r.fail("/domain/boundaries/" + a.name,
               "does not end where '" + b.name + "' starts: the loop is open");
      }
    }
  }
  // 2.7: an axisymmetric model turns about the x axis, so its domain must reach down to y = 0
  // along an `axis` piece and nothing may lie below it; a planar model has no axis.
  const bool axisymmetric = model.geometry == "axisymmetric";
  if (axisymmetric && d.kind != "channel")
    r.fail("/domain",
           "kind '" + d.kind + "' in an axisymmetric model (only 'channel' has an axis)");
  bool has_axis = false;
  for (const auto& b : model.domain.boundaries) {
    const std::string g = "/domain/boundaries/" + b.name;
    if (b.kind == "axis") {
      if (!axisymmetric)
        r.fail(g, "kind 'axis' in a planar model (root geometry = 'axisymmetric' needed)");
      has_axis = true;
      for (const auto& p : b.points) {
        if (std::abs(p.y()) > 1e-12 * (1.0 + std::abs(p.x())))
          r.fail(g + "/points",
                 "an axis piece must lie on y = 0, found y = " + std::to_string(p.y()));
      }
    }
    for (const auto& p : b.points) {
      if (axisymmetric && p.y() < -1e-12 * (1.0 + std::abs(p.x())))
        r.fail(g + "/points",
               "an axisymmetric domain lies in y >= 0, found y = " + std::to_string(p.y()));
    }
  }
  if (axisymmetric && !has_axis)
    r.fail("/domain/boundaries", "an axisymmetric model needs a boundary of kind 'axis' on y = 0");
}

// Flow conditions, thermal settings, mesh controls and analysis settings: plain attributes.
void read_settings(const h5::Reader& r, Model& model) {
  FlowConditions& c = model.flow;
  const std::string cg = "/conditions";
  c.nozzle_pressure_ratio = r.attr_f64(cg, "nozzle_pressure_ratio");
  c.stagnation_temperature = r.attr_f64(cg, "stagnation_temperature");
  c.ambient_pressure = r.attr_f64(cg, "ambient_pressure");
  c.ambient_temperature = r.attr_f64(cg, "ambient_temperature");
  c.ambient_mach = r.attr_f64(cg, "ambient_mach");
  c.exit_pressure_ratio = r.attr_f64(cg, "exit_pressure_ratio");
  c.gamma = r.attr_f64(cg, "gamma");
  c.gas_constant = r.attr_f64(cg, "gas_constant");
  c.prandtl = r.attr_f64(cg, "prandtl");
  c.turbulent_prandtl = r.attr_f64(cg, "turbulent_prandtl");
  c.turbulence = r.attr_string(cg, "turbulence");
  c.reference_length = r.attr_f64(cg, "reference_length");
  c.yplus_target = r.attr_f64(cg, "yplus_target");
  c.first_cell_height = r.attr_f64(cg, "first_cell_height");
  if (r.has_attr(cg, "viscous_length"))
    c.viscous_length = r.attr_f64(cg, "viscous_length");  // 2.5
  ThermalSettings& t = model.thermal;
  t.flow_wall = r.attr_string("/thermal", "flow_wall");
  t.wall_temperature = r.attr_f64("/thermal", "wall_temperature");
  t.solid_boundary = r.attr_string("/thermal", "solid_boundary");
  t.emissivity = r.attr_f64("/thermal", "emissivity");
  t.reference_temperature = r.attr_f64("/thermal", "reference_temperature");
  MeshControls& m = model.mesh;
  const std::string mc = "/mesh_controls";
  m.wall_size = r.attr_f64(mc, "wall_size");
  m.far_size = r.attr_f64(mc, "far_size");
  m.growth = r.attr_f64(mc, "growth");
  m.max_layers = static_cast<int>(r.attr_i64(mc, "max_layers"));
  m.scale = r.attr_f64(mc, "scale");
  m.cells_along = static_cast<int>(r.attr_i64(mc, "cells_along"));
  m.cells_across = static_cast<int>(r.attr_i64(mc, "cells_across"));
  m.cells_upstream = static_cast<int>(r.attr_i64(mc, "cells_upstream"));
  m.leading_edge_spacing = r.attr_f64(mc, "leading_edge_spacing");
  // 2.2; absent in 2.0/2.1 files (off)
  if (r.has_attr(mc, "cells_per_circle"))
    m.cells_per_circle = static_cast<int>(r.attr_i64(mc, "cells_per_circle"));
  if (r.has_attr(mc, "end_cells"))
    m.end_cells = static_cast<int>(r.attr_i64(mc, "end_cells"));
  m.solid_cells_per_element = static_cast<int>(r.attr_i64(mc, "solid_cells_per_element"));
  m.solid_layers = static_cast<int>(r.attr_i64(mc, "solid_layers"));
  AnalysisSettings& a = model.analysis;
  a.kind = r.attr_string("/analysis", "kind");
  a.time = r.attr_string("/analysis", "time");
  a.end_time = r.attr_f64("/analysis", "end_time");
  a.time_step = r.attr_f64("/analysis", "time_step");
  a.load_steps = static_cast<int>(r.attr_i64("/analysis", "load_steps"));
  a.max_coupling_iterations = static_cast<int>(r.attr_i64("/analysis", "max_coupling_iterations"));
  a.coupling_tolerance = r.attr_f64("/analysis", "coupling_tolerance");
  a.convergence = r.attr_string("/analysis", "convergence");
  a.acceleration = r.attr_string("/analysis", "acceleration");
  a.relaxation = r.attr_f64("/analysis", "relaxation");
}

}  // namespace

Model read_model(const std::filesystem::path& file) {
  const h5::Reader r = open_checked(file, "model");
  Model model;
  model.source = file;
  const Header header = read_header(r);
  model.geometry = header.geometry;
  model.depth = header.depth;
  if (r.has_attr("/", "title"))
    model.title = r.attr_string("/", "title");
  read_flaps(r, model);
  read_joints(r, model);
  read_supports(r, model);
  read_domain(r, model);
  read_settings(r, model);
  return model;
}

}  // namespace tfmb::formats
