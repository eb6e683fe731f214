// Calorically perfect gas: state conversions and the inviscid flux (Blazek 2015, sec. 2.2, 2.8).
// Conservative state U = (rho, rho u, rho v, rho E); primitive state W = (rho, u, v, p).
#pragma once

#include <array>
#include <cmath>

namespace tfmb::flow {

using State = std::array<double, 4>;
using Block = std::array<double, 16>;  // 4x4, row-major

struct PerfectGas {
  double gamma = 1.4;
  double R = 287.05;  // specific gas constant [J/(kg K)]

  double cv() const { return R / (gamma - 1.0); }
  double cp() const { return gamma * R / (gamma - 1.0); }

  // W -> U
  State conservative(const State& w) const {
    return {w[0], w[0] * w[1], w[0] * w[2], w[3] / (gamma - 1.0) + 0.5 * w[0] * (w[1] * w[1] + w[2] * w[2])};
  }
  // U -> W, on any scalar (double, or tfmb::Dual for the exact Roe Jacobian)
  template <class T>
  std::array<T, 4> primitive(const std::array<T, 4>& u) const {
    const T rho = u[0];
    const T vx = u[1] / rho;
    const T vy = u[2] / rho;
    return {rho, vx, vy, (gamma - 1.0) * (u[3] - 0.5 * rho * (vx * vx + vy * vy))};
  }
  double sound_speed(const State& w) const { return std::sqrt(gamma * w[3] / w[0]); }
  double temperature(const State& w) const { return w[3] / (w[0] * R); }
  template <class T>
  T total_enthalpy(const std::array<T, 4>& w) const {
    return gamma / (gamma - 1.0) * w[3] / w[0] + 0.5 * (w[1] * w[1] + w[2] * w[2]);
  }
};

// Inviscid flux through a face with (non-unit) normal n: F(W) . n (Blazek 2015, eq. 2.21).
template <class T>
std::array<T, 4> euler_flux(const PerfectGas& gas, const std::array<T, 4>& w, double nx,
                            double ny) {
  const T vn = w[1] * nx + w[2] * ny;
  const T m = w[0] * vn;
  return {m, m * w[1] + w[3] * nx, m * w[2] + w[3] * ny, m * gas.total_enthalpy(w)};
}

// d(F . n)/dU at W, the convective flux Jacobian (Blazek 2015, eq. A.9 for the 2D case).
inline Block euler_flux_jacobian(const PerfectGas& gas, const State& w, double nx, double ny) {
  const double g1 = gas.gamma - 1.0;
  const double u = w[1], v = w[2];
  const double vn = u * nx + v * ny;
  const double phi = 0.5 * g1 * (u * u + v * v);
  const double h = gas.total_enthalpy(w);
  return {0.0, nx, ny, 0.0,
          nx * phi - u * vn, vn - (gas.gamma - 2.0) * u * nx, u * ny - g1 * v * nx, g1 * nx,
          ny * phi - v * vn, v * nx - g1 * u * ny, vn - (gas.gamma - 2.0) * v * ny, g1 * ny,
          vn * (phi - h), h * nx - g1 * u * vn, h * ny - g1 * v * vn, gas.gamma * vn};
}

}  // namespace tfmb::flow
