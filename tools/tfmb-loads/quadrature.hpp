// Gauss-Legendre rules on [0, 1] (Abramowitz & Stegun 25.4.29, mapped from [-1, 1]).
#pragma once

#include <array>
#include <cmath>
#include <utility>

namespace tfmb::loads {

// Two points, weights sum to 1: exact for polynomials of degree 3.
inline const std::array<std::pair<double, double>, 2> gauss_legendre_2 = {
    std::pair{0.5 - 0.5 / std::sqrt(3.0), 0.5}, std::pair{0.5 + 0.5 / std::sqrt(3.0), 0.5}};

// Five points: exact for degree 9 (used for reference integrals of analytic fields).
inline const std::array<std::pair<double, double>, 5> gauss_legendre_5 = {
    std::pair{0.5 - 0.5 * 0.9061798459386640, 0.5 * 0.2369268850561891},
    std::pair{0.5 - 0.5 * 0.5384693101056831, 0.5 * 0.4786286704993665},
    std::pair{0.5, 0.5 * 0.5688888888888889},
    std::pair{0.5 + 0.5 * 0.5384693101056831, 0.5 * 0.4786286704993665},
    std::pair{0.5 + 0.5 * 0.9061798459386640, 0.5 * 0.2369268850561891}};

}  // namespace tfmb::loads
