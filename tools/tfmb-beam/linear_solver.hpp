// Sparse direct solve of the Newton system (Eigen SparseLU, general: the tangent of spatial
// rotations is unsymmetric away from equilibrium, FORMULATION.md sec. 2), with mechanism detection.
#pragma once

#include <Eigen/Sparse>
#include <Eigen/SparseLU>
#include <functional>
#include <string>

#include "tfmb-beam/assembly.hpp"

namespace tfmb::beam {

class NewtonLinearSolver {
 public:
  /// `name_of` names a global unknown for error messages.
  explicit NewtonLinearSolver(std::function<std::string(int)> name_of) : name_of_(std::move(name_of)) {}
  /// Solves K dx = -r. Throws ModelError naming the free unknowns if K is singular (mechanism or
  /// redundant constraint).
  /// `step_limit`: a correction larger than this (infinity norm) comes from a pivot that vanished
  /// up to round-off, i.e. a singular matrix.
  Eigen::VectorXd solve(int n, const Triplets& k, const Eigen::VectorXd& r, double step_limit = 1e300);
  /// Solves with the matrix factorised by the last solve() (another right-hand side).
  Eigen::VectorXd solve_again(const Eigen::VectorXd& rhs) const { return lu_.solve(rhs); }
  /// Sign of det K of the matrix factorised by the last solve() (row and column permutations
  /// included): a change along a path means an odd number of eigenvalues crossed zero.
  int determinant_sign() const { return lu_.signDeterminant() < 0.0 ? -1 : 1; }
  /// Message describing the null space of a singular matrix (dense analysis; small systems only).
  std::string describe_singularity(const Eigen::SparseMatrix<double>& k) const;

 private:
  std::function<std::string(int)> name_of_;
  Eigen::SparseMatrix<double> matrix_;
  mutable Eigen::SparseLU<Eigen::SparseMatrix<double>, Eigen::COLAMDOrdering<int>> lu_;
  bool analysed_ = false;
  Eigen::Index pattern_nnz_ = -1;
};

}  // namespace tfmb::beam
