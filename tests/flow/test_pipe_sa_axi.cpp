// Turbulent pipe flow, axisymmetric Spalart-Allmaras: checks the nu_tilde equation on r-weighted
// dual volumes and normals, the axis as a symmetry line (the r-weighted axis faces have zero
// measure: no nu_tilde flux, zero normal gradient) and the wall distance in the meridional plane.
// Air at about 1 bar, 300 K, Re_D about 4.1e4, Mach about 0.09; a pipe of 60 diameters from a
// stagnation inflow (nu_tilde = 3 nu entering) to a static-pressure outflow; 61 x 61 nodes, the
// radial ones clustered to the wall (y+ 0.54). At x = 40 and 50 D (developed to 1 %):
// - the momentum balance of fully developed flow, tau_w = -(dp/dx) R / 2 (White 2006, eq. 6-36
//   integrated over the section), to 2 %;
// - the Darcy friction factor f = 8 tau_w / (rho U_b^2) against the fully developed solution of
//   the same SA equations in 1D (solve_developed below: the momentum equation integrated exactly,
//   (nu + nu_t) du/dr = -u_tau^2 r / R, and the nu_tilde equation
//   0 = P - D + 1/sigma [r^-1 d/dr(r (nu + nu_tilde) d nu_tilde/dr) + cb2 (d nu_tilde/dr)^2]
//   in finite differences on 400 radial intervals, converged in the number of intervals to
//   0.1 %), to 4 %: the 2D mesh has 61 radial nodes, first-order nu_tilde convection and
//   second-order mean flow; measured +1.1 % (40 D) and +2.0 % (50 D);
// - f against Prandtl's smooth-pipe law 1/sqrt(f) = 2.0 log10(Re_D sqrt(f)) - 0.8 (White 2006,
//   eq. 6-54), to 6 %: SA in 1D is itself 2.4 % above the law at this Re_D.
// What it does not catch: dropping only the 1/r part of the nu_tilde diffusion (planar edge
// coefficients times the cell's mean r, tried when the test was written) moves f by +1.5 % and
// nu_tilde on the axis by -1 %, inside the tolerances; errors in the r-weighting of volumes,
// normals or sources change mu_t by O(1) and are caught.
// Converged to a density residual drop of 1e-6 (f unchanged to 4 digits against 1e-8): 402
// iterations, 25-50 s on one thread.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "mesh_generate.hpp"
#include "tfmb-flow/turbulence_sa.hpp"
#include "tfmb-flow/solver.hpp"

using namespace tfmb::flow;

namespace sa1d {

struct Developed {
  double u_tau = 0.0, u_bulk = 0.0, friction_factor = 0.0, reynolds = 0.0;  // Re on 2R and U_b
  int iterations = 0;
  double update = 0.0;
  double nu_tilde_axis = 0.0;  // [m^2/s]
};

// For a given friction velocity: momentum integrates exactly, (nu + nu_t) du/dr = -u_tau^2 r/R in
// both geometries; the nu_tilde equation
//   0 = P - D + 1/sigma [ r^-m d/dr(r^m (nu + nu_tilde) d nu_tilde/dr) + cb2 (d nu_tilde/dr)^2 ],
// m = 1 (pipe) or 0 (channel), nu_tilde(R) = 0, d nu_tilde/dr(0) = 0, d = R - r, is solved by
// damped Newton steps on N intervals clustered to the wall (first spacing 1e-4 R).
inline Developed solve_developed(double radius, double nu, double u_tau, bool pipe, int intervals = 400, double cfl_max = 100.0) {
  using namespace tfmb::flow;
  const int n = intervals;
  const double dy1 = 1e-4 * radius, deta = 1.0 / n;
  auto first = [&](double beta) { return 1.0 - std::tanh(beta * (1.0 - deta)) / std::tanh(beta); };
  double lo = 1e-3, hi = 30.0;
  for (int it = 0; it < 200; ++it) {
    const double mid = 0.5 * (lo + hi);
    (first(mid) * radius > dy1 ? lo : hi) = mid;
  }
  const double beta = 0.5 * (lo + hi);
  std::vector<double> r(n + 1), nt(n + 1), u(n + 1), s(n + 1);
  for (int k = 0; k <= n; ++k) {
    r[k] = radius * std::tanh(beta * k * deta) / std::tanh(beta);
    const double y = radius - r[k];
    nt[k] = sa::kappa * u_tau * y * (1.0 - y / radius) + 3.0 * nu;
  }
  nt[n] = 0.0;
  auto w = [&](double rr) { return pipe ? rr : 1.0; };
  Developed out;
  out.u_tau = u_tau;
  std::vector<double> a(n + 1), b(n + 1), c(n + 1), f(n + 1);
  double cfl = 1.0;
  for (int it = 0; it < 5000; ++it) {
    // velocity from the wall inwards
    std::vector<double> g(n + 1);  // -du/dr
    for (int k = 0; k <= n; ++k) {
      const double chi = std::max(nt[k], 0.0) / nu;
      const double nut = std::max(nt[k], 0.0) * sa::fv1(chi);
      g[k] = u_tau * u_tau * r[k] / (radius * (nu + nut));
      s[k] = g[k];
    }
    u[n] = 0.0;
    for (int k = n - 1; k >= 0; --k) u[k] = u[k + 1] + 0.5 * (g[k] + g[k + 1]) * (r[k + 1] - r[k]);
    double biggest = 0.0, scale = 0.0;
    for (int k = 0; k < n; ++k) {
      const double dk = sa::diffusivity(nt[k], nu);
      double diff, dm, dp;  // diffusion and its derivatives wrt nt[k-1], nt[k+1]
      double cb2_term = 0.0;
      if (k == 0) {
        const double dh = 0.5 * (dk + sa::diffusivity(nt[1], nu));
        const double h = r[1];
        const double coef = (pipe ? 4.0 : 2.0) * dh / (h * h);
        diff = coef * (nt[1] - nt[0]);
        dm = 0.0;
        dp = coef;
      } else {
        const double hm = r[k] - r[k - 1], hp = r[k + 1] - r[k];
        const double dmh = 0.5 * (dk + sa::diffusivity(nt[k - 1], nu));
        const double dph = 0.5 * (dk + sa::diffusivity(nt[k + 1], nu));
        const double den = w(r[k]) * 0.5 * (hm + hp);
        dp = w(0.5 * (r[k] + r[k + 1])) * dph / hp / den;
        dm = w(0.5 * (r[k] + r[k - 1])) * dmh / hm / den;
        diff = dp * (nt[k + 1] - nt[k]) - dm * (nt[k] - nt[k - 1]);
        const double grad = (nt[k + 1] - nt[k - 1]) / (hm + hp);
        cb2_term = sa::cb2 * grad * grad;
      }
      const sa::Source src = sa::source(nt[k], nu, s[k], radius - r[k], true);
      f[k] = (diff + cb2_term) / sa::sigma + src.production - src.destruction;
      const double hloc = k == 0 ? r[1] : std::min(r[k] - r[k - 1], r[k + 1] - r[k]);
      const double dt = cfl * hloc * hloc / (nu + std::abs(nt[k]));
      a[k] = -dm / sa::sigma;
      c[k] = -dp / sa::sigma;
      b[k] = 1.0 / dt + (dm + dp) / sa::sigma - src.d_source;
    }
    // Thomas algorithm, nt[n] = 0 fixed
    std::vector<double> cp(n), dpv(n);
    cp[0] = c[0] / b[0];
    dpv[0] = f[0] / b[0];
    for (int k = 1; k < n; ++k) {
      const double m = b[k] - a[k] * cp[k - 1];
      cp[k] = c[k] / m;
      dpv[k] = (f[k] - a[k] * dpv[k - 1]) / m;
    }
    std::vector<double> dx(n);
    dx[n - 1] = dpv[n - 1];
    for (int k = n - 2; k >= 0; --k) dx[k] = dpv[k] - cp[k] * dx[k + 1];
    for (int k = 0; k < n; ++k) {
      nt[k] += dx[k];
      biggest = std::max(biggest, std::abs(dx[k]));
      scale = std::max(scale, std::abs(nt[k]));
    }
    out.iterations = it + 1;
    out.update = biggest / scale;
    if (out.update < 1e-13) break;
    cfl = std::min(cfl * 1.5, cfl_max);
  }
  double q = 0.0, area = 0.0;
  for (int k = 0; k < n; ++k) {
    const double h = r[k + 1] - r[k];
    q += 0.5 * (u[k] * w(r[k]) + u[k + 1] * w(r[k + 1])) * h;
    area += 0.5 * (w(r[k]) + w(r[k + 1])) * h;
  }
  out.u_bulk = q / area;
  out.nu_tilde_axis = nt[0];
  out.friction_factor = 8.0 * u_tau * u_tau / (out.u_bulk * out.u_bulk);
  out.reynolds = out.u_bulk * 2.0 * radius / nu;
  return out;
}

// The same at a given bulk Reynolds number (secant iteration on u_tau).
inline Developed solve_developed_at(double radius, double nu, double reynolds, bool pipe) {
  const double u_b = reynolds * nu / (2.0 * radius);
  double x0 = u_b * std::sqrt(0.02 / 8.0), x1 = 1.05 * x0;
  Developed d0 = solve_developed(radius, nu, x0, pipe), d1 = solve_developed(radius, nu, x1, pipe);
  for (int it = 0; it < 20 && std::abs(d1.reynolds / reynolds - 1.0) > 1e-10; ++it) {
    const double x2 = x1 + (reynolds - d1.reynolds) * (x1 - x0) / (d1.reynolds - d0.reynolds);
    x0 = x1;
    d0 = d1;
    x1 = x2;
    d1 = solve_developed(radius, nu, x1, pipe);
  }
  return d1;
}

}  // namespace sa1d


TEST(PipeSpalartAllmaras, AxisymmetricFullyDevelopedFrictionFactor) {
  const int ni = 61, nj = 61;
  const double radius = 0.01, length = 120.0 * radius, dy1 = 5e-6;
  const double deta = 1.0 / (nj - 1);
  // one-sided tanh clustering to the wall (eta = 1) with the first spacing dy1
  auto first = [&](double beta) { return radius * (1.0 - std::tanh(beta * (1.0 - deta)) / std::tanh(beta)); };
  double lo = 1e-3, hi = 30.0;
  for (int it = 0; it < 200; ++it) {
    const double mid = 0.5 * (lo + hi);
    (first(mid) > dy1 ? lo : hi) = mid;
  }
  const double beta = 0.5 * (lo + hi);
  StructuredMeshSpec spec;
  spec.ni = ni;
  spec.nj = nj;
  spec.map = [&](double xi, double eta) { return Vec2{length * xi, radius * std::tanh(beta * eta) / std::tanh(beta)}; };
  spec.bottom = "axis";
  spec.right = "outlet";
  spec.top = "wall";
  spec.left = "inlet";
  const PerfectGas gas{1.4, 287.05};
  BoundaryCondition axis, out, wall, in;
  axis.kind = BcKind::symmetry;
  out.kind = BcKind::pressure_outflow;
  out.static_pressure = 1.0e5;
  wall.kind = BcKind::wall_adiabatic;
  in.kind = BcKind::stagnation_inflow;
  in.total_pressure = 1.0145e5;
  in.total_temperature = 300.0;
  SolverSettings s;
  s.viscous = true;
  s.turbulent = true;
  s.max_iterations = 2000;
  s.residual_drop = 1e-6;
  s.reference_state = {1.16, 347.0, 347.0, 1.0e5};
  FlowSolver solver(structured_mesh(spec), Geometry::axisymmetric, gas, {axis, out, wall, in}, s);
  solver.set_uniform({1.16, 30.0, 0.0, 1.0e5});
  const SolveReport r = solver.solve();
  std::printf("turbulent pipe (SA, axisymmetric, %d x %d): %d iterations, %ld linear, %.1f s, drop %.1e\n", ni, nj,
              r.iterations, r.linear_iterations, r.wall_time, r.residual_drop);
  ASSERT_TRUE(r.converged);
  const auto w = solver.primitive();
  const auto& x = solver.node_coords();
  auto node = [&](int i, int j) { return j * ni + i; };
  const WallTrace trace = solver.wall_trace(2);
  const auto nu_tilde = solver.nu_tilde();
  for (const double x_over_d : {40.0, 50.0}) {
    const int i0 = static_cast<int>(std::lround(x_over_d * 2.0 * radius / length * (ni - 1)));
    double flux = 0.0, mass = 0.0, area = 0.0;  // integrals of rho u, rho, 1 over r dr
    for (int j = 0; j + 1 < nj; ++j) {
      const double r0 = x[node(i0, j)].y, r1 = x[node(i0, j + 1)].y;
      const auto& a = w[node(i0, j)];
      const auto& b = w[node(i0, j + 1)];
      mass += 0.5 * (a[0] * a[1] * r0 + b[0] * b[1] * r1) * (r1 - r0);
      flux += 0.5 * (a[0] * r0 + b[0] * r1) * (r1 - r0);
      area += 0.5 * (r0 + r1) * (r1 - r0);
    }
    const double rho_b = flux / area, u_b = mass / flux;
    const State& w_wall = w[node(i0, nj - 1)];
    const double mu = s.viscosity.viscosity(gas.temperature(w_wall));
    const double re = rho_b * u_b * 2.0 * radius / mu;
    double tau = 0.0;
    for (std::size_t k = 0; k < trace.node.size(); ++k) {
      if (trace.node[k] == node(i0, nj - 1)) tau = std::abs(trace.shear_stress[k]);
    }
    const double dpdx = (w[node(i0 + 1, 0)][3] - w[node(i0 - 1, 0)][3]) / (x[node(i0 + 1, 0)].x - x[node(i0 - 1, 0)].x);
    const double f = 8.0 * tau / (rho_b * u_b * u_b);
    const sa1d::Developed d = sa1d::solve_developed_at(radius, mu / rho_b, re, true);
    double f_law = 0.02;  // Prandtl's law, by fixed-point iteration
    for (int it = 0; it < 50; ++it) f_law = std::pow(2.0 * std::log10(re * std::sqrt(f_law)) - 0.8, -2.0);
    const double balance = tau / (-dpdx * radius / 2.0);
    // nu_tilde on the axis against the 1D solution scaled to the 2D friction velocity
    const double nt_axis = nu_tilde[node(i0, 0)] / (d.nu_tilde_axis * std::sqrt(tau / rho_b) / d.u_tau);
    std::printf("  x/D %.0f: nu_tilde on the axis / 1D SA %.4f\n", x_over_d, nt_axis);
    const double y_plus = w_wall[0] * std::sqrt(tau / w_wall[0]) * dy1 / mu;
    std::printf("  x/D %.0f: Re_D %.0f, y+ %.2f, tau_w / (-dp/dx R/2) %.4f, f %.5f; 1D SA %.5f (%+.2f %%); "
                "Prandtl's law %.5f (%+.2f %%)\n",
                x_over_d, re, y_plus, balance, f, d.friction_factor, 100.0 * (f / d.friction_factor - 1.0), f_law,
                100.0 * (f / f_law - 1.0));
    EXPECT_NEAR(balance, 1.0, 0.02) << "x/D " << x_over_d;
    EXPECT_NEAR(f / d.friction_factor, 1.0, 0.04) << "x/D " << x_over_d;
    EXPECT_NEAR(f / f_law, 1.0, 0.06) << "x/D " << x_over_d;
    EXPECT_LT(y_plus, 1.0);
  }
}
