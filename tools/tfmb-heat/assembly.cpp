#include "tfmb-heat/assembly.hpp"

#include "tfmb/common/assert.hpp"
#include "tfmb-heat/boundary_geometry.hpp"
#include "tfmb-heat/boundary_terms.hpp"
#include "tfmb-heat/contact.hpp"
#include "tfmb-heat/element_conduction.hpp"
#include "tfmb-heat/reference_element.hpp"

#include <cmath>
#include <limits>
#include <numeric>
#include <sstream>
#include <stdexcept>

namespace tfmb::heat {

struct Assembler::Impl {
  const ThermalProblem* problem = nullptr;
  bool transient = false;
  std::vector<std::int64_t> dof_of_node;
  std::size_t dof_count = 0;
  Eigen::VectorXd dirichlet;                 // per dof, NaN where free
  std::vector<bool> is_dirichlet;            // per dof
  std::vector<int> dirichlet_boundary;       // per dof: index of the claiming condition, or -1
  std::vector<bool> used;                    // per dof: touched by an element
  std::vector<ReferenceElement> references;  // per block
  std::vector<BoundaryPoint> boundary_points;
  std::vector<GapPoint> gap_points;
  Eigen::SparseMatrix<double> pattern;

  void build_dofs(const std::vector<std::pair<std::int64_t, std::int64_t>>& ties);
  void build_pattern();
  void add_entry(Eigen::SparseMatrix<double>& matrix, std::int64_t row, std::int64_t col,
                 double value) const {
    // element and boundary dofs come from dof_of_node, which numbers every node
    TFMB_ASSERT(row >= 0 && col >= 0 && row < static_cast<std::int64_t>(dof_count) &&
                    col < static_cast<std::int64_t>(dof_count),
                "matrix entry (" << row << ", " << col << ") outside " << dof_count << " dofs");
    if (is_dirichlet[row] || is_dirichlet[col])
      return;
    matrix.coeffRef(row, col) += value;
  }
};

namespace {

std::string available_boundaries(const SolidMesh& mesh) {
  std::string names;
  for (const auto& [name, curve] : mesh.boundaries)
    names += (names.empty() ? "" : ", ") + name;
  return names.empty() ? "none" : names;
}

const BoundaryCurve& find_boundary(const SolidMesh& mesh, const std::string& name,
                                   const std::string& context) {
  const auto it = mesh.boundaries.find(name);
  if (it == mesh.boundaries.end()) {
    throw std::invalid_argument(context + ": the solid mesh has no boundary '" + name +
                                "' (available: " + available_boundaries(mesh) + ")");
  }
  return it->second;
}

std::int64_t find_root(std::vector<std::int64_t>& parent, std::int64_t i) {
  while (parent[i] != i) {
    parent[i] = parent[parent[i]];
    i = parent[i];
  }
  return i;
}

}  // namespace

void Assembler::Impl::build_dofs(const std::vector<std::pair<std::int64_t, std::int64_t>>& ties) {
  const auto n_nodes = problem->mesh->node_count();
  std::vector<std::int64_t> parent(n_nodes);
  std::iota(parent.begin(), parent.end(), 0);
  for (const auto& [a, b] : ties) {
    const auto ra = find_root(parent, a), rb = find_root(parent, b);
    if (ra != rb)
      parent[std::max(ra, rb)] = std::min(ra, rb);
  }
  dof_of_node.assign(n_nodes, -1);
  std::vector<std::int64_t> dof_of_root(n_nodes, -1);
  dof_count = 0;
  for (std::size_t i = 0; i < n_nodes; ++i) {
    const auto root = find_root(parent, static_cast<std::int64_t>(i));
    if (dof_of_root[root] < 0)
      dof_of_root[root] = static_cast<std::int64_t>(dof_count++);
    dof_of_node[i] = dof_of_root[root];
  }
}

void Assembler::Impl::build_pattern() {
  using Triplet = Eigen::Triplet<double, std::int64_t>;
  std::vector<Triplet> triplets;
  const auto& mesh = *problem->mesh;
  std::size_t estimate = dof_count;
  for (const auto& block : mesh.blocks) {
    const auto npe = nodes_per_element(block.type);
    estimate += block.size() * npe * npe;
  }
  triplets.reserve(estimate);
  auto add = [&](std::int64_t r, std::int64_t c) {
    if (!is_dirichlet[r] && !is_dirichlet[c]) {
      triplets.emplace_back(r, c, 0.0);
    }
  };
  for (std::size_t d = 0; d < dof_count; ++d) {
    triplets.emplace_back(static_cast<std::int64_t>(d), static_cast<std::int64_t>(d), 0.0);
  }
  for (const auto& block : mesh.blocks) {
    for (std::size_t e = 0; e < block.size(); ++e) {
      const auto nodes = block.element(e);
      for (auto a : nodes) {
        for (auto b : nodes)
          add(dof_of_node[a], dof_of_node[b]);
      }
    }
  }
  for (const auto& p : gap_points) {
    std::vector<std::int64_t> dofs;
    for (int k = 0; k < p.a_count; ++k)
      dofs.push_back(dof_of_node[p.a_nodes[k]]);
    for (int k = 0; k < p.b_count; ++k)
      dofs.push_back(dof_of_node[p.b_nodes[k]]);
    for (auto a : dofs) {
      for (auto b : dofs)
        add(a, b);
    }
  }
  const auto n = static_cast<Eigen::Index>(dof_count);
  pattern.resize(n, n);
  pattern.setFromTriplets(triplets.begin(), triplets.end());
  pattern.makeCompressed();
}

Assembler::Assembler(const ThermalProblem& problem, bool transient)
    : impl_(std::make_unique<Impl>()) {
  auto& im = *impl_;
  im.problem = &problem;
  im.transient = transient;
  if (!problem.mesh)
    throw std::invalid_argument("thermal problem: no mesh");
  const auto& mesh = *problem.mesh;
  if (problem.materials.empty())
    throw std::invalid_argument("thermal problem: no materials");
  for (const auto& material : problem.materials)
    validate_material(material, transient);
  validate_mesh(mesh, problem.materials.size());

  // Contacts: perfect ties change the dof numbering, gap points couple dofs.
  std::vector<std::pair<std::int64_t, std::int64_t>> ties;
  for (std::size_t c = 0; c < problem.contacts.size(); ++c) {
    const auto& contact = problem.contacts[c];
    const std::string context =
        "contact '" + contact.boundary_a + "' - '" + contact.boundary_b + "'";
    const auto& a = find_boundary(mesh, contact.boundary_a, context);
    const auto& b = find_boundary(mesh, contact.boundary_b, context);
    if (!contact.gap_conductance) {
      const auto pairs = perfect_contact_pairs(mesh, a, b, context);
      ties.insert(ties.end(), pairs.begin(), pairs.end());
    } else {
      if (!(*contact.gap_conductance > 0.0) || !std::isfinite(*contact.gap_conductance)) {
        throw std::invalid_argument(context + ": gap conductance " +
                                    std::to_string(*contact.gap_conductance) +
                                    " W/(m^2 K) must be positive (omit it for perfect contact)");
      }
      const auto points =
          gap_contact_points(mesh, a, b, *contact.gap_conductance, static_cast<int>(c));
      im.gap_points.insert(im.gap_points.end(), points.begin(), points.end());
    }
  }
  im.build_dofs(ties);

  im.used.assign(im.dof_count, false);
  for (const auto& block : mesh.blocks) {
    for (auto node : block.nodes)
      im.used[im.dof_of_node[node]] = true;
    im.references.push_back(make_reference_element(block.type, stiffness_rule(block.type)));
  }

  im.dirichlet = Eigen::VectorXd::Constant(static_cast<Eigen::Index>(im.dof_count),
                                           std::numeric_limits<double>::quiet_NaN());
  im.is_dirichlet.assign(im.dof_count, false);
  im.dirichlet_boundary.assign(im.dof_count, -1);
  Eigen::VectorXd dirichlet_sum = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(im.dof_count));
  std::vector<int> dirichlet_hits(im.dof_count, 0);
  for (std::size_t i = 0; i < problem.boundary_conditions.size(); ++i) {
    const auto& spec = problem.boundary_conditions[i];
    const std::string context =
        "boundary '" + spec.boundary + "' (" + condition_name(spec.condition) + ")";
    const auto& curve = find_boundary(mesh, spec.boundary, context);
    try {
      const bool needs_arc_length = std::holds_alternative<ImposedTemperature>(spec.condition) ||
                                    std::holds_alternative<Convection>(spec.condition) ||
                                    std::holds_alternative<ImposedHeatFlux>(spec.condition);
      const auto arc_length = needs_arc_length ? boundary_arc_length(mesh, curve)
                                               : std::vector<double>(curve.nodes.size(), 0.0);
      if (const auto* imposed = std::get_if<ImposedTemperature>(&spec.condition)) {
        for (const auto& [node, value] :
             imposed_temperatures(curve, arc_length, *imposed, problem.trace_tolerance)) {
          const auto d = im.dof_of_node[node];
          im.is_dirichlet[d] = true;
          if (im.dirichlet_boundary[d] < 0)
            im.dirichlet_boundary[d] = static_cast<int>(i);
          dirichlet_sum[static_cast<Eigen::Index>(d)] += value;
          ++dirichlet_hits[d];
        }
      } else {
        const auto points = boundary_points(mesh, curve, arc_length, spec.condition,
                                            static_cast<int>(i), problem.trace_tolerance);
        im.boundary_points.insert(im.boundary_points.end(), points.begin(), points.end());
      }
    } catch (const std::invalid_argument& error) {
      throw std::invalid_argument(context + ": " + error.what());
    }
  }
  // A node on two imposed-temperature walls (a corner) takes the mean of both traces.
  for (std::size_t d = 0; d < im.dof_count; ++d) {
    if (dirichlet_hits[d] > 0)
      im.dirichlet[static_cast<Eigen::Index>(d)] =
          dirichlet_sum[static_cast<Eigen::Index>(d)] / dirichlet_hits[d];
  }
  im.build_pattern();
}

Assembler::~Assembler() = default;

std::size_t Assembler::node_count() const {
  return impl_->problem->mesh->node_count();
}
std::size_t Assembler::dof_count() const {
  return impl_->dof_count;
}
const std::vector<std::int64_t>& Assembler::dof_of_node() const {
  return impl_->dof_of_node;
}
const Eigen::VectorXd& Assembler::dirichlet_values() const {
  return impl_->dirichlet;
}
bool Assembler::has_dirichlet() const {
  for (bool b : impl_->is_dirichlet) {
    if (b)
      return true;
  }
  return false;
}
const ThermalProblem& Assembler::problem() const {
  return *impl_->problem;
}

void Assembler::assemble(const Eigen::VectorXd& t, const TimeTerm& time_term,
                         Eigen::VectorXd& residual, Eigen::SparseMatrix<double>* tangent,
                         Tangent kind) const {
  const auto& im = *impl_;
  const auto& mesh = *im.problem->mesh;
  residual.setZero(static_cast<Eigen::Index>(im.dof_count));
  if (tangent) {
    if (tangent->nonZeros() != im.pattern.nonZeros() || tangent->rows() != im.pattern.rows())
      *tangent = im.pattern;
    tangent->coeffs().setZero();
  }
  std::size_t cell = 0;
  ElementVector te, he, re;
  ElementMatrix ke;
  ElementCoordinates xy;
  std::vector<std::int64_t> dofs(9);
  for (std::size_t b = 0; b < mesh.blocks.size(); ++b) {
    const auto& block = mesh.blocks[b];
    const auto& ref = im.references[b];
    const auto npe = static_cast<Eigen::Index>(ref.node_count);
    te.resize(npe);
    he.resize(npe);
    re.resize(npe);
    xy.resize(npe, 2);
    if (tangent)
      ke.resize(npe, npe);
    for (std::size_t e = 0; e < block.size(); ++e, ++cell) {
      const auto nodes = block.element(e);
      for (Eigen::Index a = 0; a < npe; ++a) {
        const auto node = nodes[a];
        dofs[a] = im.dof_of_node[node];
        te[a] = t[dofs[a]];
        if (time_term.history)
          he[a] = (*time_term.history)[dofs[a]];
        xy(a, 0) = mesh.points(node, 0);
        xy(a, 1) = mesh.points(node, 1);
      }
      re.setZero();
      if (tangent)
        ke.setZero();
      const ElementTimeTerm element_time{time_term.rate_factor, time_term.history ? &he : nullptr};
      add_conduction_element(ref, xy, te, im.problem->materials[mesh.cell_material[cell]],
                             element_time, im.problem->volumetric_source, kind, re,
                             tangent ? &ke : nullptr);
      for (Eigen::Index a = 0; a < npe; ++a) {
        residual[dofs[a]] += re[a];
        if (!tangent)
          continue;
        for (Eigen::Index c = 0; c < npe; ++c) {
          im.add_entry(*tangent, dofs[a], dofs[c], ke(a, c));
        }
      }
    }
  }
  for (const auto& p : im.boundary_points) {
    std::int64_t d[3];
    double temperature = 0.0;
    for (int a = 0; a < p.count; ++a) {
      d[a] = im.dof_of_node[p.nodes[a]];
      temperature += p.n[a] * t[d[a]];
    }
    const double flux = p.flux_out(temperature) * p.weight;
    const double slope = p.flux_out_slope(temperature) * p.weight;
    for (int a = 0; a < p.count; ++a) {
      residual[d[a]] += p.n[a] * flux;
      if (!tangent)
        continue;
      for (int c = 0; c < p.count; ++c) {
        im.add_entry(*tangent, d[a], d[c], p.n[a] * p.n[c] * slope);
      }
    }
  }
  for (const auto& p : im.gap_points) {
    // Side a loses h_c (T_a - T_b) per unit length, side b gains it.
    std::int64_t d[6];
    double n[6];
    double jump = 0.0;
    for (int k = 0; k < p.a_count; ++k) {
      d[k] = im.dof_of_node[p.a_nodes[k]];
      n[k] = p.a_n[k];
      jump += n[k] * t[d[k]];
    }
    for (int k = 0; k < p.b_count; ++k) {
      d[p.a_count + k] = im.dof_of_node[p.b_nodes[k]];
      n[p.a_count + k] = -p.b_n[k];
      jump += n[p.a_count + k] * t[d[p.a_count + k]];
    }
    const int count = p.a_count + p.b_count;
    const double factor = p.conductance * p.weight;
    for (int k = 0; k < count; ++k) {
      residual[d[k]] += n[k] * factor * jump;
      if (!tangent)
        continue;
      for (int m = 0; m < count; ++m)
        im.add_entry(*tangent, d[k], d[m], n[k] * n[m] * factor);
    }
  }
  if (tangent) {
    for (std::size_t dof = 0; dof < im.dof_count; ++dof) {
      if (im.is_dirichlet[dof] || !im.used[dof]) {
        const auto i = static_cast<Eigen::Index>(dof);
        tangent->coeffRef(i, i) = 1.0;
      }
    }
  }
}

std::map<std::string, double> Assembler::boundary_heat_rates(const Eigen::VectorXd& t,
                                                             const TimeTerm& time_term) const {
  const auto& im = *impl_;
  const auto& specs = im.problem->boundary_conditions;
  std::map<std::string, double> rates;
  for (const auto& spec : specs)
    rates[spec.boundary] = 0.0;
  for (const auto& p : im.boundary_points) {
    double temperature = 0.0;
    for (int a = 0; a < p.count; ++a) {
      temperature += p.n[a] * t[im.dof_of_node[p.nodes[a]]];
    }
    rates[specs[p.boundary].boundary] -= p.flux_out(temperature) * p.weight;
  }
  Eigen::VectorXd residual;
  assemble(t, time_term, residual, nullptr, Tangent::picard);
  for (std::size_t d = 0; d < im.dof_count; ++d) {
    if (im.dirichlet_boundary[d] >= 0) {
      rates[specs[im.dirichlet_boundary[d]].boundary] += residual[static_cast<Eigen::Index>(d)];
    }
  }
  return rates;
}

std::vector<double> Assembler::contact_heat_rates(const Eigen::VectorXd& t) const {
  const auto& im = *impl_;
  std::vector<double> rates(im.problem->contacts.size(), 0.0);
  for (const auto& p : im.gap_points) {
    double jump = 0.0;
    for (int k = 0; k < p.a_count; ++k)
      jump += p.a_n[k] * t[im.dof_of_node[p.a_nodes[k]]];
    for (int k = 0; k < p.b_count; ++k)
      jump -= p.b_n[k] * t[im.dof_of_node[p.b_nodes[k]]];
    rates[p.contact] += p.conductance * p.weight * jump;
  }
  return rates;
}

Eigen::VectorXd Assembler::to_nodes(const Eigen::VectorXd& dof_temperature) const {
  const auto& im = *impl_;
  Eigen::VectorXd nodes(static_cast<Eigen::Index>(im.dof_of_node.size()));
  for (std::size_t i = 0; i < im.dof_of_node.size(); ++i)
    nodes[static_cast<Eigen::Index>(i)] = dof_temperature[im.dof_of_node[i]];
  return nodes;
}

Eigen::VectorXd Assembler::to_dofs(const Eigen::VectorXd& node_temperature) const {
  const auto& im = *impl_;
  Eigen::VectorXd dofs(static_cast<Eigen::Index>(im.dof_count));
  for (std::size_t i = 0; i < im.dof_of_node.size(); ++i)
    dofs[im.dof_of_node[i]] = node_temperature[static_cast<Eigen::Index>(i)];
  return dofs;
}

void Assembler::check_temperature_range(const Eigen::VectorXd& t) const {
  const auto& im = *impl_;
  const auto& mesh = *im.problem->mesh;
  std::size_t cell = 0;
  for (const auto& block : mesh.blocks) {
    for (std::size_t e = 0; e < block.size(); ++e, ++cell) {
      const auto& material = im.problem->materials[mesh.cell_material[cell]];
      const double low = material_min_temperature(material, im.transient);
      const double high = material_max_temperature(material, im.transient);
      for (auto node : block.element(e)) {
        const double value = t[im.dof_of_node[node]];
        if (!(value >= low && value <= high)) {
          std::ostringstream message;
          message << "temperature " << value << " K at node " << node
                  << " (x = " << mesh.points(node, 0) << " m, y = " << mesh.points(node, 1)
                  << " m) is outside the property table of material '" << material.name << "' ["
                  << low << ", " << high << "] K";
          throw std::invalid_argument(message.str());
        }
      }
    }
  }
}

}  // namespace tfmb::heat
