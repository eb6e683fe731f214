#include "tfmb-beam/linear_solver.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <sstream>
#include <vector>

#include "tfmb-beam/errors.hpp"

namespace tfmb::beam {

Eigen::VectorXd NewtonLinearSolver::solve(int n, const Triplets& k, const Eigen::VectorXd& r, double step_limit) {
  matrix_.resize(n, n);
  matrix_.setFromTriplets(k.begin(), k.end());
  matrix_.makeCompressed();
  // The sparsity pattern is fixed by the model (joints insert their full blocks), so the symbolic
  // analysis is done once.
  if (!analysed_ || matrix_.nonZeros() != pattern_nnz_) {
    lu_.analyzePattern(matrix_);
    analysed_ = true;
    pattern_nnz_ = matrix_.nonZeros();
  }
  lu_.factorize(matrix_);
  bool singular = lu_.info() != Eigen::Success;
  Eigen::VectorXd dx;
  if (!singular) {
    dx = lu_.solve(-r);
    singular = lu_.info() != Eigen::Success || !dx.allFinite();
    // A pivot that vanished only up to round-off shows up as an absurd step.
    if (!singular) {
      const double resid = (matrix_ * dx + r).norm();
      singular = (resid > 1e-6 * (r.norm() + 1e-300) && resid > 1e-8 * matrix_.norm() * dx.norm()) ||
                 dx.cwiseAbs().maxCoeff() > step_limit;
    }
  }
  if (singular) throw ModelError(describe_singularity(matrix_));
  return dx;
}

std::string NewtonLinearSolver::describe_singularity(const Eigen::SparseMatrix<double>& k) const {
  std::ostringstream msg;
  msg << "the system matrix is singular: the model is a mechanism (free rigid-body motion) or has redundant "
         "constraints.";
  const Eigen::Index n = k.rows();
  if (n > 3000) {
    msg << " (" << n << " unknowns: too many for the null-space analysis; check supports and joints)";
    return msg.str();
  }
  const Eigen::MatrixXd dense(k);
  Eigen::FullPivLU<Eigen::MatrixXd> lu(dense);
  lu.setThreshold(1e-10);
  const Eigen::MatrixXd ker = lu.kernel();
  if (ker.cols() == 0 || (ker.cols() == 1 && ker.norm() == 0.0)) {
    msg << " Nearly singular; check supports and joint axes.";
    return msg.str();
  }
  msg << " Free directions (" << ker.cols() << "):";
  for (Eigen::Index c = 0; c < std::min<Eigen::Index>(ker.cols(), 6); ++c) {
    Eigen::VectorXd v = ker.col(c).normalized();
    std::vector<int> idx(static_cast<size_t>(n));
    for (int i = 0; i < n; ++i) idx[i] = i;
    std::sort(idx.begin(), idx.end(), [&](int a, int b) { return std::abs(v(a)) > std::abs(v(b)); });
    msg << (c ? ";" : "") << " mode " << c + 1 << ": ";
    for (int t = 0; t < 3 && t < n; ++t) {
      if (std::abs(v(idx[t])) < 0.3 * std::abs(v(idx[0]))) break;
      msg << (t ? ", " : "") << name_of_(idx[t]);
    }
  }
  msg << ". Add a support or joint that removes this motion.";
  return msg.str();
}

}  // namespace tfmb::beam
