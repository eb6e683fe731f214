#include "tfmb-beam/run.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <optional>
#include <sstream>

#include "tfmb-beam/assembly.hpp"
#include "tfmb-beam/dynamic_solver.hpp"
#include "tfmb-beam/errors.hpp"
#include "tfmb-beam/flexible_joint.hpp"
#include "tfmb-beam/modal.hpp"
#include "tfmb-beam/rotation_wm.hpp"
#include "tfmb-beam/static_solver.hpp"
#include "tfmb/common/errors.hpp"
#include "tfmb/common/h5.hpp"
#include "tfmb/common/log.hpp"
#include "tfmb/common/options.hpp"
#include "tfmb/formats/files.hpp"
#include "tfmb/formats/loads.hpp"
#include "tfmb/formats/materials.hpp"
#include "tfmb/formats/model.hpp"
#include "tfmb/formats/schema.hpp"
#include "tfmb/formats/structure.hpp"

namespace tfmb::beam {
namespace {

int end_node(const FileModel& fm, const formats::Model& in, const std::string& flap,
             const std::string& end, const std::string& where) {
  const auto it = fm.flap_nodes.find(flap);
  if (it == fm.flap_nodes.end())
    in.fail(where, "refers to flap '" + flap + "', which is not in /flaps");
  return end == "start" ? it->second.front() : it->second.back();
}

// Rows (coefficient, power of sigma, power of |p|); the reader checked the powers.
MeasureFunction measure_terms(const Eigen::MatrixX3d& rows) {
  MeasureFunction fn;  // no rows: identically zero
  for (Eigen::Index r = 0; r < rows.rows(); ++r)
    fn.terms.push_back({rows(r, 0), static_cast<int>(rows(r, 1)), static_cast<int>(rows(r, 2))});
  return fn;
}

/// Flexible joint of a planar model: stiffness in the global axes (x, y in the plane, z out of it).
std::shared_ptr<const FlexibleJointLaw> flexible_law(const formats::Model& in,
                                                     const formats::Joint& joint,
                                                     const std::string& g) {
  auto law = std::make_shared<FlexibleJointLaw>();
  law->stiffness = joint.stiffness_matrix;
  law->measure =
      joint.deformation_measure == "typical" ? FlexibleMeasure::typical : FlexibleMeasure::proposed;
  try {
    if (joint.measure_functions == "custom") {
      law->functions.name = "custom";
      law->functions.lambda = measure_terms(joint.lambda_terms);
      law->functions.mu = measure_terms(joint.mu_terms);
    } else {
      law->functions = seed_measure_functions(joint.measure_functions);
    }
    if (law->measure == FlexibleMeasure::proposed) check_measure_functions(law->functions);
  } catch (const std::invalid_argument& e) {
    in.fail(g, e.what());
  }
  return law;
}

// One flap's beam: each two-node element of the model becomes a quadratic element with a
// mid-node; node frames from the reference line's tangent.
void add_flap(FileModel& fm, const formats::Model& in, const formats::Flap& flap) {
  Model& m = fm.model;
  const std::string g = "/flaps/" + flap.name;
  fm.flap_names.push_back(flap.name);
  const auto& curve = flap.reference_curve;
  Section sec;
  sec.stiffness = flap.section.stiffness;
  sec.mass_per_length = flap.section.mass(0, 0);
  sec.inertia_per_length = flap.section.mass.block<3, 3>(3, 3);
  const int section = static_cast<int>(m.sections.size());
  m.sections.push_back(sec);
  std::vector<int>& nodes = fm.flap_nodes[flap.name];
  auto add_node = [&](const Eigen::Vector2d& p, const Eigen::Vector2d& t) {
    Node n;
    n.position = Eigen::Vector3d(p.x(), p.y(), 0.0);
    const Eigen::Vector3d e1 = Eigen::Vector3d(t.x(), t.y(), 0.0).normalized();
    n.frame.col(0) = e1;
    n.frame.col(1) = Eigen::Vector3d::UnitZ().cross(e1);
    n.frame.col(2) = Eigen::Vector3d::UnitZ();
    nodes.push_back(static_cast<int>(m.nodes.size()));
    m.nodes.push_back(n);
  };
  const std::size_t nr = curve.size();
  for (std::size_t i = 0; i < nr; ++i) {
    const Eigen::Vector2d& p = curve[i];
    // Node tangent: average of the adjacent segment directions (the exact arc tangent is not
    // known from the polyline).
    Eigen::Vector2d t = Eigen::Vector2d::Zero();
    if (i > 0)
      t += (curve[i] - curve[i - 1]).normalized();
    if (i + 1 < nr)
      t += (curve[i + 1] - curve[i]).normalized();
    if (t.norm() < 1e-12)
      in.fail(g + "/reference_curve", "repeated or reversing points at row " + std::to_string(i));
    if (i > 0)
      add_node(0.5 * (curve[i - 1] + p), p - curve[i - 1]);
    add_node(p, t);
  }
  for (std::size_t e = 0; e + 1 < nr; ++e) {
    Element el;
    el.nodes = {nodes[2 * e], nodes[2 * e + 1], nodes[2 * e + 2]};
    el.section = section;
    fm.flap_elements[flap.name].push_back(static_cast<int>(m.elements.size()));
    m.elements.push_back(el);
  }
}

// A support: a joint to ground at a flap end.
JointSpec support_joint(const FileModel& fm, const formats::Model& in,
                        const formats::Support& support) {
  const std::string g = "/supports/" + support.name;
  JointSpec j;
  j.name = support.name;
  j.node_b = end_node(fm, in, support.flap, support.end, g);
  j.node_a = -1;
  if (support.kind == "clamp") {
    j.kind = JointKind::clamp;
  } else if (support.kind == "pinned") {
    j.kind = JointKind::revolute;
  } else if (support.slides()) {
    // A clamp or a hinge whose end slides along the axis (model 2.4): the ground prismatic pair
    // or the pin in a slot.
    j.kind = support.kind == "sliding_clamp" ? JointKind::prismatic : JointKind::pin_in_slot;
    j.axis = Eigen::Vector3d(support.axis.x(), support.axis.y(), 0.0);
  } else {
    in.fail(g, "support kind '" + support.kind + "' is not supported by this tfmb-beam version");
  }
  return j;
}

// A joint between two flap ends.
JointSpec flap_joint(const FileModel& fm, const formats::Model& in, const formats::Joint& joint) {
  const Model& m = fm.model;
  const std::string g = "/joints/" + joint.name;
  JointSpec j;
  j.name = joint.name;
  j.node_a = end_node(fm, in, joint.flap_a, joint.end_a, g);
  j.node_b = end_node(fm, in, joint.flap_b, joint.end_b, g);
  if (joint.kind == "rigid") {
    j.kind = JointKind::rigid;
  } else if (joint.kind == "revolute" || joint.kind == "revolute_spring") {
    j.kind = JointKind::revolute;
    // the spring is revolute_spring's (formats/model.md): a plain revolute joint is an ideal
    // hinge even if the file carries a stiffness meant for another kind
    if (joint.kind == "revolute_spring") {
      j.spring_stiffness = joint.stiffness;
      j.damping = joint.damping;
    }
  } else if (joint.kind == "prescribed_rotation") {
    j.kind = JointKind::revolute;
    j.prescribed = true;
    for (Eigen::Index r = 0; r < joint.rotation_table.rows(); ++r)
      j.prescribed_table.push_back({joint.rotation_table(r, 0), joint.rotation_table(r, 1)});
  } else if (joint.kind == "revolute_clearance") {
    j.kind = JointKind::clearance;
    j.pin_radius = joint.inner_radius;
    j.hole_radius = joint.outer_radius;
    j.contact_stiffness = joint.contact_stiffness;
    j.friction_coefficient = joint.friction;
  } else if (joint.kind == "prismatic") {
    j.kind = JointKind::prismatic;
    j.axis = Eigen::Vector3d(joint.axis.x(), joint.axis.y(), 0.0);
  } else if (joint.kind == "flexible") {
    j.kind = JointKind::flexible;
    j.flexible_law = flexible_law(in, joint, g);
  } else {
    in.fail(g, "joint kind '" + joint.kind + "' is not supported by this tfmb-beam version");
  }
  // Coincident flap ends are required by the hinge joints.
  if (j.kind != JointKind::rigid &&
      (m.nodes[j.node_a].position - m.nodes[j.node_b].position).norm() >
          1e-9 * (1.0 + m.nodes[j.node_a].position.norm()))
    in.fail(g, "the flap ends it joins are not at the same point");
  return j;
}

}  // namespace

FileModel read_model(const Options& options) {
  FileModel fm;
  Model& m = fm.model;
  const formats::Model in = formats::read_model(options.model);
  if (in.geometry != "planar")
    in.fail("/", "geometry '" + in.geometry + "': tfmb-beam supports planar models only");
  fm.analysis = in.analysis;
  for (const formats::Flap& flap : in.flaps)
    add_flap(fm, in, flap);
  // Supports and joints, each in the file's (name) order.
  for (const formats::Support& support : in.supports) {
    m.joints.push_back(support_joint(fm, in, support));
    fm.joint_names.push_back(support.name);
  }
  for (const formats::Joint& joint : in.joints) {
    m.joints.push_back(flap_joint(fm, in, joint));
    fm.joint_names.push_back(joint.name);
  }
  add_planar_constraints(m);
  fm.joint_names.resize(m.joints.size());

  for (const std::string& spec : options.point_loads) {
    const auto c1 = spec.find(':'), c2 = spec.find(':', c1 == std::string::npos ? c1 : c1 + 1);
    if (c1 == std::string::npos || c2 == std::string::npos)
      throw UsageError("--point-load '" + spec + "': expected flap:start|end:fx,fy[,mz]");
    const std::string flap = spec.substr(0, c1), end = spec.substr(c1 + 1, c2 - c1 - 1);
    std::vector<double> v;
    std::stringstream ss(spec.substr(c2 + 1));
    std::string item;
    while (std::getline(ss, item, ',')) {
      try {
        v.push_back(std::stod(item));
      } catch (...) {
        throw UsageError("--point-load '" + spec + "': '" + item + "' is not a number");
      }
    }
    if (!fm.flap_nodes.count(flap)) throw UsageError("--point-load '" + spec + "': no flap '" + flap + "' in the model");
    if ((end != "start" && end != "end") || v.size() < 2 || v.size() > 3)
      throw UsageError("--point-load '" + spec + "': expected flap:start|end:fx,fy[,mz]");
    NodalLoad l;
    l.node = end == "start" ? fm.flap_nodes[flap].front() : fm.flap_nodes[flap].back();
    l.force = Eigen::Vector3d(v[0], v[1], 0.0);
    if (v.size() == 3) l.moment = Eigen::Vector3d(0.0, 0.0, v[2]);
    m.nodal_loads.push_back(l);
    // The first point load's node and direction are the load path's monitor (structure.h5 /path).
    if (fm.monitor.node < 0 && l.force.norm() > 0.0) {
      fm.monitor = {l.node, l.force.normalized()};
      std::ostringstream name;
      name << flap << ":" << end << " (" << fm.monitor.direction.x() << ", "
           << fm.monitor.direction.y() << ", " << fm.monitor.direction.z() << ")";
      fm.monitor_name = name.str();
    }
  }

  // Loads: the file's consistent nodal forces and moments at the flap nodes (the end nodes of
  // the quadratic elements), what tfmb-loads integrated from the wall traces (formats/loads.md:
  // "prefer nodal_force/nodal_moment in the beam"); the distributed forces beside them are a
  // projection for plotting and are not read.
  if (!options.loads.empty()) {
    const formats::Loads loads = formats::read_loads(options.loads);
    // Every flap of the model has its group (zeros where it is unloaded): a missing one would
    // be taken as unloaded, silently (found by the mutation suite: a group removed ran to exit 0
    // with another result).
    for (const auto& [name, elements] : fm.flap_elements) {
      const bool present = std::any_of(loads.flaps.begin(), loads.flaps.end(),
                                       [&](const formats::LoadsFlap& f) { return f.name == name; });
      if (!present)
        loads.fail("/flaps",
                   "no group for the model's flap '" + name +
                       "' (a loads file has every flap, with zeros where one is unloaded)");
    }
    for (const formats::LoadsFlap& flap : loads.flaps) {
      const std::string g = "/flaps/" + flap.name;
      if (!fm.flap_elements.count(flap.name))
        loads.fail(g, "flap '" + flap.name + "' is not in the model " + options.model.string());
      const std::size_t nodes = fm.flap_elements[flap.name].size() + 1;
      if (flap.s.size() != nodes)
        loads.fail(g + "/s", std::to_string(flap.s.size()) + " nodes, but the model's flap has " +
                                 std::to_string(nodes));
      for (std::size_t i = 0; i < nodes; ++i) {
        if (flap.nodal_force[i].norm() == 0.0 && flap.nodal_moment[i].norm() == 0.0)
          continue;
        NodalLoad load;
        load.node = fm.flap_nodes[flap.name][2 * i];
        load.force = flap.nodal_force[i];
        load.moment = flap.nodal_moment[i];
        // Follower loads (pressure turns with the wall) are given in the node's reference frame.
        load.follower = !options.dead_loads;
        if (load.follower) {
          load.force = m.nodes[load.node].frame.transpose() * load.force;
          load.moment = m.nodes[load.node].frame.transpose() * load.moment;
        }
        m.nodal_loads.push_back(load);
      }
    }
  }
  // Materials: per element section stiffness and mass at the element temperature, thermal
  // strain (thickness mean) and thermal curvature as initial strains.
  if (!options.materials.empty()) {
    const formats::Materials materials = formats::read_materials(options.materials);
    for (const formats::MaterialsFlap& flap : materials.flaps) {
      const std::string g = "/flaps/" + flap.name;
      if (!fm.flap_elements.count(flap.name))
        materials.fail(g, "flap '" + flap.name + "' is not in the model " + options.model.string());
      const auto& els = fm.flap_elements[flap.name];
      const formats::MaterialElements& props = flap.elements;
      if (props.size() != els.size())
        materials.fail(g + "/temperature", std::to_string(props.size()) +
                                               " elements, but the model's flap has " +
                                               std::to_string(els.size()));
      for (std::size_t e = 0; e < els.size(); ++e) {
        Element& el = m.elements[els[e]];
        Section s;
        s.stiffness = props.section_stiffness[e];
        s.mass_per_length = props.section_mass[e](0, 0);
        s.inertia_per_length = props.section_mass[e].block<3, 3>(3, 3);
        el.section = static_cast<int>(m.sections.size());
        m.sections.push_back(s);
        // Bending strain is -k3 y2 (y2 along e2, the left of the reference direction); the free
        // thermal strain grows towards the outer wall by kappa per unit length, so
        // k3_thermal = -kappa * outer_normal_sign.
        el.initial_strain.setZero();
        el.initial_strain(0) = props.thermal_strain[e];
        el.initial_strain(5) = -props.thermal_curvature[e] * flap.outer_normal_sign;
      }
    }
  }
  return fm;
}

namespace {

/// The static solve's path as structure.h5 /path (formats/structure.md 1.3).
formats::StructurePath structure_path(const StaticResult& r, const std::string& method,
                                      const FileModel& fm) {
  formats::StructurePath p;
  p.method = method;
  p.monitor = fm.monitor_name;
  for (const PathPoint& row : r.path) {
    p.load_factor.push_back(row.load_factor);
    p.arc_length.push_back(row.arc_length);
    p.max_displacement.push_back(row.max_displacement);
    p.characteristic_displacement.push_back(row.characteristic_displacement);
    if (fm.monitor.node >= 0)
      p.node_displacement.push_back(row.node_displacement);
    p.iterations.push_back(row.iterations);
  }
  const LimitPoints limits = find_limit_points(r.path);
  p.limit_points_load.assign(limits.load.begin(), limits.load.end());
  p.limit_points_displacement.assign(limits.displacement.begin(), limits.displacement.end());
  return p;
}

void write_structure(const Options& options, const FileModel& fm, const Assembly& asmb,
                     const State& state, const std::string& analysis, bool converged,
                     const std::vector<double>& times,
                     const std::vector<std::vector<Eigen::Vector3d>>& history,
                     const ModalResult* modes, const Motion* motion = nullptr,
                     double end_time = 0.0,
                     std::optional<formats::StructurePath> path = std::nullopt) {
  const Model& m = fm.model;
  formats::Structure out;
  out.header.creator = "tfmb-beam " TFMB_BEAM_VERSION;
  out.analysis = analysis;
  out.converged = converged;
  const std::size_t n = m.nodes.size();
  for (std::size_t i = 0; i < n; ++i) {
    out.points.push_back(m.nodes[i].position);
    out.displacement.push_back(state.position[i] - m.nodes[i].position);
    out.rotation.push_back(state.rotation[i]);
  }
  // Two display segments per quadratic element, each with its half's Gauss point values.
  std::vector<ElementResult> er;
  asmb.element_results(state, er);
  for (std::size_t e = 0; e < m.elements.size(); ++e)
    for (int half = 0; half < 2; ++half) {
      out.segments.push_back({m.elements[e].nodes[half], m.elements[e].nodes[half + 1]});
      out.sectional_strain.push_back(er[e].strain[half]);
      out.sectional_force.push_back(er[e].stress[half]);
    }
  for (const auto& name : fm.flap_names) {
    formats::StructureFlap flap;
    flap.name = name;
    flap.nodes.assign(fm.flap_nodes.at(name).begin(), fm.flap_nodes.at(name).end());
    for (int e : fm.flap_elements.at(name))
      flap.segments.insert(flap.segments.end(), {2 * e, 2 * e + 1});
    out.flaps.push_back(std::move(flap));
  }
  for (std::size_t j = 0; j < m.joints.size(); ++j) {
    if (m.joints[j].kind == JointKind::planar) continue;
    formats::StructureJoint joint;
    joint.name = fm.joint_names[j];
    const auto outputs = asmb.joint_outputs(state, static_cast<int>(j));
    auto get = [&](const std::string& key) -> std::optional<double> {
      for (const auto& o : outputs)
        if (o.name == key)
          return o.value;
      return std::nullopt;
    };
    const char* reaction_keys[] = {"reaction_force_x",  "reaction_force_y",  "reaction_force_z",
                                   "reaction_moment_x", "reaction_moment_y", "reaction_moment_z"};
    for (int k = 0; k < 6; ++k)
      joint.reaction(k) = get(reaction_keys[k]).value_or(0.0);
    for (const char* key : {"relative_rotation", "contact_force", "gap", "sliding"})
      if (const auto v = get(key))
        joint.scalars[key] = *v;
    if (m.joints[j].kind == JointKind::flexible) {
      const char* names[] = {"stretch_1", "stretch_2", "stretch_3", "wryness_1", "wryness_2", "wryness_3"};
      formats::Vector6 deformation;
      for (int k = 0; k < 6; ++k)
        deformation(k) = get(names[k]).value_or(0.0);
      joint.deformation = deformation;
      if (const auto v = get("strain_energy"))
        joint.scalars["strain_energy"] = *v;
    }
    out.joints.push_back(std::move(joint));
  }
  out.history_time = times;
  for (const auto& snapshot : history) {
    std::vector<Eigen::Vector3d> displacement(n);
    for (std::size_t i = 0; i < n; ++i)
      displacement[i] = snapshot[i] - m.nodes[i].position;
    out.history_displacement.push_back(std::move(displacement));
  }
  if (modes) {
    const Eigen::VectorXd& f = modes->frequencies_hz;
    out.mode_frequency.assign(f.data(), f.data() + f.size());
    for (Eigen::Index k = 0; k < f.size(); ++k) {
      const double peak = modes->mode_shapes.col(k).cwiseAbs().maxCoeff();
      std::vector<Eigen::Vector3d> shape(n);
      for (std::size_t i = 0; i < n; ++i)
        shape[i] = modes->mode_shapes.block<3, 1>(6 * static_cast<Eigen::Index>(i), k) /
                   (peak > 0 ? peak : 1.0);
      out.mode_displacement.push_back(std::move(shape));
    }
  }
  if (motion) {
    // What a later dynamic run needs to continue this one (--initial-state): the positions and
    // rotations are the fields, the rates and joint unknowns are here.
    formats::StructureRestart restart;
    restart.velocity = motion->velocity;
    restart.angular_velocity = motion->angular_velocity;
    restart.joint_dofs.assign(state.joint_dofs.data(),
                              state.joint_dofs.data() + state.joint_dofs.size());
    restart.joint_rates.assign(motion->joint_rates.data(),
                               motion->joint_rates.data() + motion->joint_rates.size());
    restart.time = end_time;
    out.restart = std::move(restart);
  }
  out.path = std::move(path);
  formats::Provenance prov;
  prov.command_line = options.command_line;
  // Every option as given (declared once in main.cpp), then the analysis the model resolved.
  prov.settings = options.settings_toml + "\n[resolved]\nanalysis = " + cli::toml_string(analysis) + "\n";
  prov.inputs.push_back(options.model);
  if (!options.loads.empty()) prov.inputs.push_back(options.loads);
  if (!options.materials.empty()) prov.inputs.push_back(options.materials);
  formats::write_structure(options.output, out, prov);
}

}  // namespace

namespace {

/// Start state and motion from an earlier dynamic structure.h5 of the same model (--initial-state).
void continue_from(const std::filesystem::path& file, const FileModel& fm, const Assembly& asmb, State& state,
                   DynamicSolver& solver) {
  const formats::Structure earlier = formats::read_structure(file);
  const Model& m = fm.model;
  const std::size_t n = m.nodes.size();
  if (!earlier.restart)
    earlier.fail("/restart", "missing: the file is not from a dynamic run");
  if (earlier.points.size() != n)
    earlier.fail("/beam/points", std::to_string(earlier.points.size()) + " nodes, the model has " +
                                     std::to_string(n));
  for (std::size_t i = 0; i < n; ++i) {
    if ((earlier.points[i] - m.nodes[i].position).norm() >
        1e-9 * (1.0 + m.nodes[i].position.norm()))
      earlier.fail("/beam/points",
                   "node " + std::to_string(i) + " is not where the model puts it: another model");
  }
  for (std::size_t i = 0; i < n; ++i) {
    state.position[i] = m.nodes[i].position + earlier.displacement[i];
    state.rotation[i] = earlier.rotation[i];
  }
  solver.set_initial_velocity(earlier.restart->velocity, earlier.restart->angular_velocity);
  const auto nj = static_cast<std::size_t>(asmb.num_joint_dofs());
  if (nj > 0) {
    if (earlier.restart->joint_dofs.size() != nj)
      earlier.fail("/restart/joint_dofs", std::to_string(earlier.restart->joint_dofs.size()) +
                                              " joint unknowns, the model has " +
                                              std::to_string(nj));
    const auto& dofs = earlier.restart->joint_dofs;
    const auto& rates = earlier.restart->joint_rates;
    state.joint_dofs = Eigen::Map<const Eigen::VectorXd>(dofs.data(), static_cast<Eigen::Index>(nj));
    solver.set_initial_joint_rates(Eigen::Map<const Eigen::VectorXd>(rates.data(), static_cast<Eigen::Index>(nj)));
  }
}

}  // namespace

int run(const Options& options, const Logger& log) {
  const auto t0 = std::chrono::steady_clock::now();
  FileModel fm = read_model(options);
  std::string analysis = options.analysis.empty() ? fm.analysis.time : options.analysis;
  if (analysis != "static" && analysis != "dynamic" && analysis != "modal")
    throw UsageError("--analysis must be static, dynamic or modal, got '" + analysis + "'");
  std::unique_ptr<Assembly> asmb;
  try {
    asmb = std::make_unique<Assembly>(fm.model);
  } catch (const ModelError& e) {
    throw BadInput(options.model.string() + ": " + e.what());
  }
  log.info("model: " + std::to_string(fm.model.nodes.size()) + " nodes, " + std::to_string(fm.model.elements.size()) +
           " quadratic elements, " + std::to_string(asmb->num_multipliers()) + " constraint equations");
  std::vector<double> times;
  std::vector<std::vector<Eigen::Vector3d>> history;
  try {
    if (analysis == "static") {
      StaticOptions so;
      so.initial_steps = options.load_steps > 0 ? options.load_steps : fm.analysis.load_steps;
      // Load steps done, counted in the nominal step (cut-backs take fractions of one).
      Progress progress(log, "static", static_cast<std::size_t>(std::max(so.initial_steps, 0)),
                        {.unit = "load steps"});
      so.on_step = [&](double load_factor, const State&) {
        progress.update(static_cast<std::size_t>(std::lround(load_factor * so.initial_steps)));
      };
      so.monitor = fm.monitor;
      StaticResult r;
      if (options.arc_length) {
        ArcLengthOptions ao;
        ao.initial_load_increment = 1.0 / std::max(so.initial_steps, 1);
        ao.final_load_factor = 1.0;
        ao.monitor = fm.monitor;
        r = solve_arc_length(*asmb, asmb->initial_state(), ao);
      } else {
        r = solve_static(*asmb, asmb->initial_state(), so);
      }
      progress.finish();
      write_structure(options, fm, *asmb, r.state, analysis, r.converged, times, history, nullptr,
                      nullptr, 0.0,
                      structure_path(r, options.arc_length ? "arc_length" : "load_stepping", fm));
      const LimitPoints limits = find_limit_points(r.path);
      if (!limits.load.empty() || !limits.displacement.empty())
        log.info("load path: " + std::to_string(limits.load.size()) + " limit point(s) in load, " +
                 std::to_string(limits.displacement.size()) +
                 " in displacement (structure.h5 /path)");
      log.summary("static: " + std::string(r.converged ? "converged" : "NOT converged") + " at load factor " +
                  std::to_string(r.load_factor) + ", " + std::to_string(r.steps) + " steps, " +
                  std::to_string(r.iterations) + " Newton iterations");
      if (!r.converged)
        throw NotConverged("Newton failed at load factor " + std::to_string(r.load_factor) +
                           " after cut-backs; the last converged state was written to " + options.output.string());
    } else if (analysis == "dynamic") {
      DynamicOptions dopt;
      dopt.end_time = options.end_time > 0 ? options.end_time : fm.analysis.end_time;
      dopt.time_step = options.time_step > 0 ? options.time_step : fm.analysis.time_step;
      dopt.rho_infinity = options.rho_infinity;
      Progress progress(
          log, "dynamic",
          dopt.time_step > 0.0 && dopt.end_time > 0.0
              ? static_cast<std::size_t>(std::ceil(dopt.end_time / dopt.time_step - 1e-9))
              : 0,
          {.unit = "time steps"});
      dopt.on_step = [&](double t, const State& s) {
        times.push_back(t);
        history.push_back(s.position);
        progress.update(static_cast<std::size_t>(std::lround(t / dopt.time_step)));
      };
      DynamicSolver solver(*asmb, dopt);
      State initial = asmb->initial_state();
      if (!options.initial_state.empty()) continue_from(options.initial_state, fm, *asmb, initial, solver);
      const DynamicResult r = solver.run(initial);
      progress.finish();
      write_structure(options, fm, *asmb, r.state, analysis, r.completed, times, history, nullptr, &solver.motion(),
                      r.time);
      log.summary(
          "dynamic: " + std::to_string(r.steps) + " steps to t = " + std::to_string(r.time) +
          " s, " + std::to_string(r.iterations) + " Newton iterations, " +
          std::to_string(r.cutbacks) + " step cut-backs" + (r.completed ? "" : " (NOT completed)"));
      if (!r.completed) throw NotConverged("Newton failed at t = " + std::to_string(r.time) + " s");
    } else {
      const ModalResult r = modal_analysis(*asmb, asmb->initial_state(), options.modes);
      write_structure(options, fm, *asmb, asmb->initial_state(), analysis, true, times, history, &r);
      std::ostringstream s;
      s << "modal: first frequencies [Hz]:";
      for (Eigen::Index i = 0; i < r.frequencies_hz.size(); ++i) s << " " << r.frequencies_hz(i);
      log.summary(s.str());
    }
  } catch (const ModelError& e) {
    throw BadInput(options.model.string() + ": " + e.what());
  }
  log.verbose("time " + std::to_string(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count()) + " s");
  return 0;
}

}  // namespace tfmb::beam
