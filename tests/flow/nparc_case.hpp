// NPARC converging-diverging verification nozzle (refdata/flow/nparc_cdv_nozzle_definition.csv):
// planar channel 0 <= y <= A(x) [in], 0 <= x <= 10 [in], inlet total conditions, exit static
// pressure. Used by the verification test and the benchmark.
#pragma once

#include <cmath>
#include <vector>

#include "mesh_generate.hpp"
#include "tfmb-flow/quasi_one_dimensional.hpp"
#include "tfmb-flow/solver.hpp"

namespace tfmb::flow::nparc {

constexpr double kInch = 0.0254;
constexpr double kP0 = 1.0e5;   // inlet total pressure [Pa]
constexpr double kT0 = 300.0;   // inlet total temperature [K]

// Area law of the refdata file, x and A in inches.
inline double area_in(double x) {
  const double pi = std::acos(-1.0);
  return x < 5.0 ? 1.75 - 0.75 * std::cos((0.2 * x - 1.0) * pi) : 1.25 - 0.25 * std::cos((0.2 * x - 1.0) * pi);
}

// ni x nj nodes, about a third of the cells split into triangles. Boundaries: bottom = symmetry
// plane (y = 0), right = exit, top = wall, left = inlet.
inline Mesh make_mesh(int ni, int nj) {
  StructuredMeshSpec spec;
  spec.ni = ni;
  spec.nj = nj;
  spec.map = [](double xi, double eta) {
    const double x = 10.0 * xi;
    return Vec2{x * kInch, eta * area_in(x) * kInch};
  };
  spec.split = [](int i, int j) { return (i + j) % 3 == 0; };
  spec.bottom = "symmetry";
  spec.right = "outlet";
  spec.top = "wall";
  spec.left = "inlet";
  return structured_mesh(spec);
}

inline std::vector<BoundaryCondition> boundary_conditions(double p_exit_ratio) {
  BoundaryCondition sym, out, wall, in;
  sym.kind = BcKind::symmetry;
  out.kind = BcKind::pressure_outflow;
  out.static_pressure = p_exit_ratio * kP0;
  wall.kind = BcKind::slip_wall;
  in.kind = BcKind::stagnation_inflow;
  in.total_pressure = kP0;
  in.total_temperature = kT0;
  return {sym, out, wall, in};
}

// Column averages of p/p0 and Mach along x for a structured ni x nj mesh (trapezoidal rule in y).
struct Column {
  double x_in;
  double p_ratio;
  double mach;
};
inline std::vector<Column> column_averages(const std::vector<State>& w, const std::vector<Vec2>& x,
                                           const PerfectGas& gas, int ni, int nj) {
  std::vector<Column> out(ni);
  for (int i = 0; i < ni; ++i) {
    double h = 0.0, p = 0.0, m = 0.0;
    for (int j = 0; j + 1 < nj; ++j) {
      const int a = j * ni + i, b = (j + 1) * ni + i;
      const double dy = x[b].y - x[a].y;
      auto mach = [&](int k) { return std::hypot(w[k][1], w[k][2]) / gas.sound_speed(w[k]); };
      h += dy;
      p += 0.5 * dy * (w[a][3] + w[b][3]) / kP0;
      m += 0.5 * dy * (mach(a) + mach(b));
    }
    out[i] = {x[i].x / kInch, p / h, m / h};
  }
  return out;
}

}  // namespace tfmb::flow::nparc
