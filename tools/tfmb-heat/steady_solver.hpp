#pragma once
// Steady nonlinear conduction by Newton's method on the assembled residual.
#include "tfmb-heat/assembly.hpp"

#include <memory>

namespace tfmb::heat {

struct SteadyResult {
  Eigen::VectorXd temperature;  // [K] per node
  NewtonReport newton;
};

/// Newton iterations from `initial_temperature` [K] (uniform; imposed temperatures are set
/// first). Returns the report with converged = false instead of throwing when the iteration
/// limit is reached; throws std::invalid_argument when the converged field leaves a material
/// table.
SteadyResult solve_steady(const ThermalProblem& problem, double initial_temperature,
                          const NewtonSettings& settings = {});

/// Factorisations and the tangent kept between Newton solves on the same assembler, so the
/// symbolic analysis of the (fixed) sparsity pattern is done once per run, not once per step.
class NewtonWorkspace {
 public:
  NewtonWorkspace();
  ~NewtonWorkspace();
  NewtonWorkspace(const NewtonWorkspace&) = delete;
  NewtonWorkspace& operator=(const NewtonWorkspace&) = delete;
  struct Impl;
  Impl& impl() { return *impl_; }

 private:
  std::unique_ptr<Impl> impl_;
};

/// One Newton solve on an existing assembler (the transient driver calls it every step with
/// the same workspace).
NewtonReport newton_solve(const Assembler& assembler, const TimeTerm& time_term,
                          const NewtonSettings& settings, Eigen::VectorXd& dof_temperature,
                          NewtonWorkspace& workspace);

}  // namespace tfmb::heat
