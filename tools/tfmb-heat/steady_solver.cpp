#include "tfmb-heat/steady_solver.hpp"

#include <Eigen/SparseCholesky>
#include <Eigen/SparseLU>

#include <chrono>
#include <cmath>
#include <stdexcept>

namespace tfmb::heat {

struct NewtonWorkspace::Impl {
  Eigen::SparseMatrix<double> tangent;
  Eigen::SparseLU<Eigen::SparseMatrix<double>, Eigen::COLAMDOrdering<int>> lu;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt;
  bool lu_analysed = false, ldlt_analysed = false;
};

NewtonWorkspace::NewtonWorkspace() : impl_(std::make_unique<Impl>()) {}
NewtonWorkspace::~NewtonWorkspace() = default;

NewtonReport newton_solve(const Assembler& assembler, const TimeTerm& time_term,
                          const NewtonSettings& settings, Eigen::VectorXd& t,
                          NewtonWorkspace& workspace) {
  NewtonReport report;
  auto& ws = workspace.impl();
  const Eigen::VectorXd& dirichlet = assembler.dirichlet_values();
  for (Eigen::Index d = 0; d < t.size(); ++d) {
    if (!std::isnan(dirichlet[d])) t[d] = dirichlet[d];
  }
  Eigen::VectorXd residual, update;
  auto& tangent = ws.tangent;
  auto& lu = ws.lu;
  auto& ldlt = ws.ldlt;
  for (int iteration = 1; iteration <= settings.max_iterations; ++iteration) {
    auto clock = std::chrono::steady_clock::now();
    assembler.assemble(t, time_term, residual, &tangent, settings.tangent);
    report.assembly_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - clock).count();
    clock = std::chrono::steady_clock::now();
    for (Eigen::Index d = 0; d < t.size(); ++d) {
      if (!std::isnan(dirichlet[d])) residual[d] = 0.0;
    }
    report.residual_norm.push_back(residual.lpNorm<Eigen::Infinity>());
    if (settings.tangent == Tangent::consistent) {
      // The pattern is fixed, so the symbolic analysis is done once per workspace.
      if (!ws.lu_analysed) lu.analyzePattern(tangent), ws.lu_analysed = true;
      lu.factorize(tangent);
      if (lu.info() != Eigen::Success) {
        throw std::runtime_error("Newton: sparse LU factorisation failed (" + lu.lastErrorMessage() +
                                 "); is a body without any temperature or convection condition?");
      }
      update = lu.solve(-residual);
    } else {
      if (!ws.ldlt_analysed) ldlt.analyzePattern(tangent), ws.ldlt_analysed = true;
      ldlt.factorize(tangent);
      if (ldlt.info() != Eigen::Success) {
        throw std::runtime_error("Newton: sparse LDLT factorisation failed");
      }
      update = ldlt.solve(-residual);
    }
    report.solve_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - clock).count();
    double largest = update.lpNorm<Eigen::Infinity>();
    if (!std::isfinite(largest)) throw std::runtime_error("Newton: non-finite temperature update");
    if (largest > settings.max_update) update *= settings.max_update / largest;
    t += update;
    report.max_update.push_back(largest);
    report.iterations = iteration;
    if (settings.on_iteration)
      settings.on_iteration(iteration, report.residual_norm.back(), largest);
    if (largest <= settings.temperature_tolerance) {
      report.converged = true;
      break;
    }
  }
  return report;
}

SteadyResult solve_steady(const ThermalProblem& problem, double initial_temperature,
                          const NewtonSettings& settings) {
  const Assembler assembler(problem, false);
  Eigen::VectorXd t = Eigen::VectorXd::Constant(static_cast<Eigen::Index>(assembler.dof_count()),
                                                initial_temperature);
  SteadyResult result;
  NewtonWorkspace workspace;
  result.newton = newton_solve(assembler, TimeTerm{}, settings, t, workspace);
  if (result.newton.converged) assembler.check_temperature_range(t);
  result.temperature = assembler.to_nodes(t);
  return result;
}

}  // namespace tfmb::heat
