// Scalar ILU(0) on the node-edge pattern of the dual mesh (diagonal + one entry per edge end),
// for the segregated turbulence equation. Anisotropic boundary-layer cells couple wall-normal
// neighbours thousands of times more strongly than streamwise ones; point Gauss-Seidel then
// leaves the wall-normal "move together" mode unconverged, ILU(0) in the banded (RCM) order
// does not (Saad 2003, Iterative Methods for Sparse Linear Systems, alg. 10.4).
#pragma once

#include <vector>

#include "mesh_dual.hpp"

namespace tfmb::flow {

class ScalarIlu0 {
 public:
  // The matrix: diag[i] and offdiag[k] for the neighbour slots k of NodeEdges.
  void factorize(const NodeEdges& pattern, const std::vector<double>& diag, const std::vector<double>& offdiag);
  void apply(const std::vector<double>& rhs, std::vector<double>& x) const;  // x = (LU)^-1 rhs

 private:
  const NodeEdges* pattern_ = nullptr;
  std::vector<double> diag_, offdiag_;
  std::vector<int> sorted_slots_;  // per row, slots in increasing neighbour order
  std::vector<int> position_;      // scratch: slot of column j in the current row
};

// Solves A x = b (A = diag/offdiag on the pattern) by ILU(0)-preconditioned Richardson
// iterations (defect correction), starting from x = 0.
void solve_scalar(const NodeEdges& pattern, const std::vector<double>& diag, const std::vector<double>& offdiag,
                  const std::vector<double>& b, std::vector<double>& x, int iterations, ScalarIlu0& ilu);

}  // namespace tfmb::flow
