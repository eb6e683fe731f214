// Roe flux-difference splitting (Roe 1981, J. Comput. Phys. 43:357) with Harten's entropy fix
// (Harten 1983, J. Comput. Phys. 49:357), in the form of Blazek (2015), eqs. 4.89-4.93.
#pragma once

#include "gas.hpp"

namespace tfmb::flow {

struct RoeFluxJacobians {
  Block d_left;   // d F / d U_left
  Block d_right;  // d F / d U_right
};

// Numerical flux through a face with normal n (length = face measure), from the left state
// (inside the dual cell the normal points out of) to the right state. entropy_fix is the
// fraction of the Roe-averaged sound speed below which |eigenvalues| are smoothed.
// When jacobians is non-null, fills the exact derivative of the first-order flux with the
// dissipation matrix |A_Roe| held fixed (the usual first-order implicit operator).
State roe_flux(const PerfectGas& gas, const State& w_left, const State& w_right, double nx, double ny,
               double entropy_fix, RoeFluxJacobians* jacobians = nullptr);

// The same flux and its exact derivatives with respect to both sides' conservative variables,
// the dissipation matrix's own dependence and the entropy fix's included (forward automatic
// differentiation, tfmb/common/dual.hpp). Frozen |A_Roe| misses that dependence, which matters
// where an eigenvalue changes sign: at sonic points and stagnation lines.
State roe_flux_exact(const PerfectGas& gas, const State& w_left, const State& w_right, double nx,
                     double ny, double entropy_fix, RoeFluxJacobians& jacobians);

}  // namespace tfmb::flow
