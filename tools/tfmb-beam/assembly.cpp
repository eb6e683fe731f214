#include "tfmb-beam/assembly.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "tfmb-beam/errors.hpp"
#include "tfmb-beam/rotation_wm.hpp"

namespace tfmb::beam {

Assembly::Assembly(const Model& model) : model_(model) {
  const int nn = num_nodes();
  const int ns = static_cast<int>(model.sections.size());
  geometry_.reserve(model.elements.size());
  element_loads_.assign(model.elements.size(), ElementLoads{});
  for (size_t e = 0; e < model.elements.size(); ++e) {
    const Element& el = model.elements[e];
    for (int id : el.nodes)
      if (id < 0 || id >= nn)
        throw ModelError("element " + std::to_string(e) + ": node id " + std::to_string(id) + " is out of range 0.." +
                         std::to_string(nn - 1));
    if (el.section < 0 || el.section >= ns)
      throw ModelError("element " + std::to_string(e) + ": section id " + std::to_string(el.section) +
                       " is out of range 0.." + std::to_string(ns - 1));
    std::array<Eigen::Vector3d, 3> x;
    std::array<Eigen::Matrix3d, 3> f;
    for (int j = 0; j < 3; ++j) {
      x[j] = model.nodes[el.nodes[j]].position;
      f[j] = model.nodes[el.nodes[j]].frame;
    }
    geometry_.push_back(make_element_geometry(x, f));
    if (!(geometry_.back().length > 0.0) || !std::isfinite(geometry_.back().length))
      throw ModelError("element " + std::to_string(e) + " has zero or invalid length; check its node positions");
    element_loads_[e].dead_force_per_length = model.sections[el.section].mass_per_length * model.gravity;
  }
  for (const DistributedLoad& d : model.distributed_loads) {
    if (d.element < 0 || d.element >= static_cast<int>(model.elements.size()))
      throw ModelError("distributed load on element " + std::to_string(d.element) + ": no such element");
    if (d.follower)
      element_loads_[d.element].follower_force_per_length += d.force_per_length;
    else
      element_loads_[d.element].dead_force_per_length += d.force_per_length;
  }
  for (const NodalLoad& l : model.nodal_loads)
    if (l.node < 0 || l.node >= nn) throw ModelError("nodal load on node " + std::to_string(l.node) + ": no such node");
  int dof = 6 * nn;
  int mult = 0;
  for (const JointSpec& spec : model.joints) {
    try {
      joints_.push_back(make_joint(model, spec));
    } catch (const std::invalid_argument& e) {
      throw ModelError(e.what());
    }
    joints_.back()->set_offsets(dof, mult);
    dof += joints_.back()->num_internal_dofs();
    mult += joints_.back()->num_equations();
  }
  num_joint_dofs_ = dof - 6 * nn;
  num_multipliers_ = mult;
  constraint_scale_ = typical_stiffness();
  if (!model.nodes.empty()) {
    Eigen::Vector3d lo = model.nodes[0].position, hi = lo;
    for (const Node& nd : model.nodes) {
      lo = lo.cwiseMin(nd.position);
      hi = hi.cwiseMax(nd.position);
    }
    step_limit_ = 1e6 * std::max(1.0, (hi - lo).norm());
  }
}

State Assembly::initial_state() const {
  State s;
  s.position.resize(model_.nodes.size());
  for (size_t i = 0; i < model_.nodes.size(); ++i) s.position[i] = model_.nodes[i].position;
  s.rotation.assign(model_.nodes.size(), Eigen::Vector3d::Zero());
  s.joint_dofs.setZero(num_joint_dofs_);
  s.multipliers.setZero(num_multipliers_);
  return s;
}

Eigen::Matrix3d Assembly::frame(const State& state, int node) const {
  return wm_rotation<double>(state.rotation[node]) * model_.nodes[node].frame;
}

ElementState Assembly::element_state(const State& state, int e) const {
  ElementState es;
  for (int j = 0; j < 3; ++j) {
    const int id = model_.elements[e].nodes[j];
    es.position[j] = state.position[id];
    es.frame[j] = frame(state, id);
  }
  return es;
}

double Assembly::typical_stiffness() const {
  if (model_.elements.empty()) return 1.0;
  const State s = initial_state();
  double sum = 0.0;
  int count = 0;
  ElementResult r;
  for (size_t e = 0; e < model_.elements.size(); ++e) {
    evaluate_beam_element(geometry_[e], model_.sections[model_.elements[e].section], Vector6d::Zero(),
                          element_state(s, static_cast<int>(e)), ElementLoads{}, true, r);
    sum += r.tangent.diagonal().cwiseAbs().sum();
    count += 18;
  }
  return count > 0 && sum > 0.0 ? sum / count : 1.0;
}

void Assembly::assemble(const State& state, double load_factor, Eigen::VectorXd& residual, Triplets* tangent,
                        double* force_scale, const RateInfo* rates) const {
  const int n = size();
  residual.setZero(n);
  if (tangent) tangent->clear();
  double scale2 = 0.0;
  ElementResult r;
  for (size_t e = 0; e < model_.elements.size(); ++e) {
    const Element& el = model_.elements[e];
    ElementLoads loads = element_loads_[e];
    loads.dead_force_per_length *= load_factor;
    loads.follower_force_per_length *= load_factor;
    evaluate_beam_element(geometry_[e], model_.sections[el.section], el.initial_strain * load_factor,
                          element_state(state, static_cast<int>(e)), loads, tangent != nullptr, r);
    scale2 += r.force.squaredNorm();
    for (int a = 0; a < 3; ++a) {
      residual.segment<6>(6 * el.nodes[a]) += r.force.segment<6>(6 * a);
      if (!tangent) continue;
      for (int b = 0; b < 3; ++b)
        for (int i = 0; i < 6; ++i)
          for (int j = 0; j < 6; ++j)
            tangent->emplace_back(6 * el.nodes[a] + i, 6 * el.nodes[b] + j, r.tangent(6 * a + i, 6 * b + j));
    }
  }
  for (const NodalLoad& l : model_.nodal_loads) {
    Eigen::Vector3d f = load_factor * l.force;
    Eigen::Vector3d m = load_factor * l.moment;
    if (l.follower) {
      const Eigen::Matrix3d fr = frame(state, l.node);
      f = fr * f;
      m = fr * m;
      if (tangent)
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j) {
            const Eigen::Matrix3d sf = skew<double>(f), sm = skew<double>(m);
            tangent->emplace_back(6 * l.node + i, 6 * l.node + 3 + j, sf(i, j));
            tangent->emplace_back(6 * l.node + 3 + i, 6 * l.node + 3 + j, sm(i, j));
          }
    }
    residual.segment<3>(6 * l.node) -= f;
    residual.segment<3>(6 * l.node + 3) -= m;
    scale2 += f.squaredNorm() + m.squaredNorm();
  }
  const double s = constraint_scale_;
  const int mult0 = 6 * num_nodes() + num_joint_dofs_;
  JointContext ctx{model_, state, load_factor};
  if (rates) {
    ctx.joint_rates = rates->joint_rates;
    ctx.node_velocity = rates->node_velocity;
    ctx.node_angular_velocity = rates->node_angular_velocity;
    ctx.rate_factor = rates->rate_factor;
  }
  JointEval je;
  for (const auto& joint : joints_) {
    const int m = joint->num_equations();
    const Eigen::VectorXd lambda = s * state.multipliers.segment(joint->first_multiplier(), m);
    joint->evaluate(ctx, lambda, je);
    const int nv = static_cast<int>(je.dofs.size());
    Eigen::VectorXd f = je.force + je.jacobian.transpose() * lambda;
    scale2 += f.squaredNorm();
    for (int p = 0; p < nv; ++p) residual(je.dofs[p]) += f(p);
    for (int i = 0; i < m; ++i) residual(mult0 + joint->first_multiplier() + i) = s * je.phi(i);
    if (!tangent) continue;
    Eigen::MatrixXd k = je.stiffness + je.hessian_lambda;
    for (int b : je.rotation_blocks) k.block<3, 3>(b, b) -= 0.5 * skew<double>(Eigen::Vector3d(f.segment<3>(b)));
    for (int p = 0; p < nv; ++p)
      for (int q = 0; q < nv; ++q) tangent->emplace_back(je.dofs[p], je.dofs[q], k(p, q));
    for (int i = 0; i < m; ++i)
      for (int p = 0; p < nv; ++p) {
        const int row = mult0 + joint->first_multiplier() + i;
        tangent->emplace_back(row, je.dofs[p], s * je.jacobian(i, p));
        tangent->emplace_back(je.dofs[p], row, s * je.jacobian(i, p));
      }
  }
  if (force_scale) *force_scale = std::sqrt(scale2);
}

void Assembly::apply_increment(State& state, const Eigen::VectorXd& dx) const {
  for (int i = 0; i < num_nodes(); ++i) {
    state.position[i] += dx.segment<3>(6 * i);
    state.rotation[i] = wm_compose<double>(state.rotation[i], Eigen::Vector3d(dx.segment<3>(6 * i + 3)));
  }
  state.joint_dofs += dx.segment(6 * num_nodes(), num_joint_dofs_);
  state.multipliers += dx.segment(6 * num_nodes() + num_joint_dofs_, num_multipliers_);
}

void Assembly::element_results(const State& state, std::vector<ElementResult>& results) const {
  results.resize(model_.elements.size());
  for (size_t e = 0; e < model_.elements.size(); ++e) {
    const Element& el = model_.elements[e];
    evaluate_beam_element(geometry_[e], model_.sections[el.section], el.initial_strain,
                          element_state(state, static_cast<int>(e)), ElementLoads{}, false, results[e]);
  }
}

double Assembly::strain_energy(const State& state) const {
  std::vector<ElementResult> r;
  element_results(state, r);
  double w = 0.0;
  for (const auto& x : r) w += x.strain_energy;
  return w;
}

Eigen::VectorXd Assembly::joint_multipliers(const State& state, int j) const {
  const Joint& joint = *joints_[j];
  return constraint_scale_ * state.multipliers.segment(joint.first_multiplier(), joint.num_equations());
}

std::vector<JointOutput> Assembly::joint_outputs(const State& state, int j, double load_factor) const {
  JointContext ctx{model_, state, load_factor};
  return joints_[j]->outputs(ctx, joint_multipliers(state, j));
}

std::string Assembly::dof_name(int i) const {
  static const char* names[] = {"displacement x", "displacement y", "displacement z",
                                "rotation about x", "rotation about y", "rotation about z"};
  if (i < 6 * num_nodes()) return "node " + std::to_string(i / 6) + " " + names[i % 6];
  const int jd = i - 6 * num_nodes();
  if (jd < num_joint_dofs_) {
    for (const auto& j : joints_)
      if (j->num_internal_dofs() > 0 && i >= j->first_internal_dof() && i < j->first_internal_dof() + j->num_internal_dofs())
        return "relative rotation of joint '" + j->spec().name + "'";
    return "joint unknown " + std::to_string(jd);
  }
  const int m = jd - num_joint_dofs_;
  for (const auto& j : joints_)
    if (m >= j->first_multiplier() && m < j->first_multiplier() + j->num_equations())
      return "constraint " + j->equation_name(m - j->first_multiplier()) + " (redundant)";
  return "unknown " + std::to_string(i);
}

}  // namespace tfmb::beam
