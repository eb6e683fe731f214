#pragma once
// Global degrees of freedom, sparsity pattern and assembly of the conduction residual and its
// tangent. Residual (weak form, per unit depth, Galerkin):
//   R_i = int_A [ grad N_i . k(T) grad T + N_i rho c_p(T) dT/dt - N_i q''' ] dA
//       + int_edges N_i [ h (T - T_aw) + eps sigma (T^4 - T_env^4) - q_in ] ds
//       + gap contact terms
// Zienkiewicz, Taylor & Zhu (2013) ch. 3 (weak form of the Poisson equation).
#include "tfmb-heat/problem.hpp"

#include <Eigen/Sparse>

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace tfmb::heat {

/// Time-derivative term at one solve: dT/dt = rate_factor * T + history, with history
/// interpolated from the vector `history` (per dof). rate_factor = 0: steady.
struct TimeTerm {
  double rate_factor = 0.0;        // [1/s]
  const Eigen::VectorXd* history = nullptr;  // [K/s] per dof
};

class Assembler {
 public:
  /// Validates the problem (mesh, materials, boundary names, traces) and precomputes the dof map,
  /// Dirichlet values, boundary and contact integration data and the sparsity pattern.
  /// Throws std::invalid_argument with a message naming what is wrong.
  Assembler(const ThermalProblem& problem, bool transient);
  ~Assembler();
  Assembler(const Assembler&) = delete;
  Assembler& operator=(const Assembler&) = delete;

  std::size_t node_count() const;
  std::size_t dof_count() const;
  const std::vector<std::int64_t>& dof_of_node() const;

  /// Nodes carrying an imposed temperature and their values [K] (per dof; NaN where free).
  const Eigen::VectorXd& dirichlet_values() const;
  bool has_dirichlet() const;

  /// Residual (all dofs, unconstrained: at Dirichlet dofs it equals the heat entering there)
  /// and tangent (Dirichlet rows and columns replaced by the identity) at the dof temperatures.
  void assemble(const Eigen::VectorXd& dof_temperature, const TimeTerm& time_term,
                Eigen::VectorXd& residual, Eigen::SparseMatrix<double>* tangent,
                Tangent kind) const;

  /// Heat entering the body through each tagged boundary [W per metre depth], from the boundary
  /// terms (Robin and flux conditions) and, for imposed-temperature boundaries, from the nodal
  /// reactions. A node shared by two imposed-temperature boundaries counts for the first.
  std::map<std::string, double> boundary_heat_rates(const Eigen::VectorXd& dof_temperature,
                                                    const TimeTerm& time_term) const;

  /// Heat through each gap contact from side a to side b [W/m].
  std::vector<double> contact_heat_rates(const Eigen::VectorXd& dof_temperature) const;

  /// Node temperatures from dof temperatures and back.
  Eigen::VectorXd to_nodes(const Eigen::VectorXd& dof_temperature) const;
  Eigen::VectorXd to_dofs(const Eigen::VectorXd& node_temperature) const;

  /// Throws std::invalid_argument if a node temperature lies outside the property tables of a
  /// material of an element using it.
  void check_temperature_range(const Eigen::VectorXd& dof_temperature) const;

  const ThermalProblem& problem() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace tfmb::heat
