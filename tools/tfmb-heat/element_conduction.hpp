#pragma once
// Element residual and tangent of the volume terms: conduction with k(T), heat capacity
// rho(T) c_p(T) dT/dt and a volumetric source.
//   R_a = sum_q w_q |J| [ B_a . k(T) grad T + N_a rho c_p Tdot - N_a q''' ]
//   consistent tangent K_ab = sum_q w_q |J| [ B_a . k B_b + (B_a . grad T) k'(T) N_b
//                                          + N_a N_b ( rho c_p r + (rho c_p)'(T) Tdot ) ]
// with Tdot = r T + history (r: rate factor of the time scheme). The Picard tangent drops the
// k' and (rho c_p)' terms. Reddy & Gartling (2010) The Finite Element Method in Heat Transfer
// and Fluid Dynamics, 3rd ed., sec. 3.4 (non-linear conduction and its Newton tangent).
#include "tfmb-heat/problem.hpp"
#include "tfmb-heat/reference_element.hpp"

#include <Eigen/Dense>

#include <functional>

namespace tfmb::heat {

using ElementVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, 9, 1>;
using ElementMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 9, 9>;
using ElementCoordinates = Eigen::Matrix<double, Eigen::Dynamic, 2, 0, 9, 2>;

struct ElementTimeTerm {
  double rate_factor = 0.0;               // r [1/s]; 0: steady (no capacity term)
  const ElementVector* history = nullptr; // nodal history [K/s]
};

/// Adds the element's residual [W/m] and (when tangent != nullptr) tangent [W/(m K)].
/// residual and tangent must be sized to the element's node count.
void add_conduction_element(const ReferenceElement& ref, const ElementCoordinates& xy,
                            const ElementVector& temperature, const Material& material,
                            const ElementTimeTerm& time_term,
                            const std::function<double(double, double)>& source, Tangent kind,
                            ElementVector& residual, ElementMatrix* tangent);

/// Area [m^2] and the integrals of a nodal field f over the element: int f dA.
double element_integral(const ReferenceElement& ref, const ElementCoordinates& xy,
                        const ElementVector& nodal_field);

}  // namespace tfmb::heat
