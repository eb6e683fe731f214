#pragma once
// Steady nonlinear conduction by Newton's method on the assembled residual.
#include "tfmb/heat/assembly.hpp"

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

/// One Newton solve on an existing assembler (used by the transient driver).
NewtonReport newton_solve(const Assembler& assembler, const TimeTerm& time_term,
                          const NewtonSettings& settings, Eigen::VectorXd& dof_temperature);

}  // namespace tfmb::heat
