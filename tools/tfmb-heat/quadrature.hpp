#pragma once
// Gauss quadrature rules on the reference elements of shape_functions.hpp.
#include "tfmb/common/quadrature.hpp"
#include "tfmb-heat/mesh.hpp"

#include <array>
#include <vector>

namespace tfmb::heat {

using QuadratureRule1D = quadrature::Rule1D;  // points on [-1, 1], weights sum to 2
using quadrature::gauss_legendre;             // n points, exact for degree 2n - 1 (libcommon)

struct QuadratureRule2D {
  std::vector<std::array<double, 2>> points;
  std::vector<double> weights;  // sum to the reference area: 1/2 (triangle) or 4 (quad)
};

/// Tensor-product n x n Gauss rule on [-1, 1]^2.
QuadratureRule2D quad_gauss(int n);

/// Symmetric triangle rule exact for total degree `degree` (1, 2, 4 or 5; others round up).
/// Dunavant (1985) Int. J. Numer. Meth. Eng. 21, 1129-1148, table of rules 1, 2, 4 and 5.
QuadratureRule2D triangle_rule(int degree);

/// Rule used for the element matrices: exact for the mass matrix on affine elements and enough
/// for a temperature-dependent conductivity (tri3: 3 points, quad4: 2x2, tri6: 6, quad8/9: 3x3).
QuadratureRule2D stiffness_rule(ElementType type);

/// Higher rule for error norms and post-processing (tri: 7 points, quad: 5x5).
QuadratureRule2D accurate_rule(ElementType type);

}  // namespace tfmb::heat
