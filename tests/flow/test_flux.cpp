#include <gtest/gtest.h>

#include <cstdio>

#include "tfmb-flow/flux_roe.hpp"

using namespace tfmb::flow;

namespace {
const PerfectGas kAir{1.4, 287.05};
}

TEST(RoeFlux, ConsistentWithPhysicalFlux) {
  const State w{1.2, 150.0, -40.0, 9.0e4};
  const State f = roe_flux(kAir, w, w, 0.3, -0.7, 0.1);
  const State fe = euler_flux(kAir, w, 0.3, -0.7);
  for (int k = 0; k < 4; ++k) EXPECT_NEAR(f[k], fe[k], 1e-12 * (std::abs(fe[k]) + 1.0));
}

TEST(RoeFlux, SupersonicFluxIsUpwind) {
  // all eigenvalues positive and above the entropy-fix band: the flux is the left flux
  const State wl{1.0, 800.0, 10.0, 1.0e5};
  const State wr{1.1, 780.0, 0.0, 1.1e5};
  const State f = roe_flux(kAir, wl, wr, 1.0, 0.0, 0.1);
  const State fl = euler_flux(kAir, wl, 1.0, 0.0);
  for (int k = 0; k < 4; ++k) EXPECT_NEAR(f[k], fl[k], 1e-9 * std::abs(fl[k]) + 1e-9);
}

TEST(EulerFlux, JacobianMatchesFiniteDifferences) {
  const State w{0.9, 120.0, 60.0, 8.0e4};
  const Block a = euler_flux_jacobian(kAir, w, 0.6, 0.8);
  const State u = kAir.conservative(w);
  for (int c = 0; c < 4; ++c) {
    State up = u, um = u;
    const double h = 1e-6 * std::abs(u[c]);
    up[c] += h;
    um[c] -= h;
    const State fp = euler_flux(kAir, kAir.primitive(up), 0.6, 0.8);
    const State fm = euler_flux(kAir, kAir.primitive(um), 0.6, 0.8);
    for (int r = 0; r < 4; ++r) {
      const double fd = (fp[r] - fm[r]) / (2 * h);
      EXPECT_NEAR(a[4 * r + c], fd, 1e-6 * (std::abs(fd) + 1.0)) << "row " << r << " col " << c;
    }
  }
}

TEST(RoeFlux, FrozenJacobianIsExactForLinearJumps) {
  // With the dissipation matrix frozen, dF/dUL + dF/dUR at equal states is the flux Jacobian,
  // and a small jump in U_R changes F by dF/dUR times the jump (to first order).
  const State w{1.1, 90.0, -30.0, 1.0e5};
  RoeFluxJacobians j;
  roe_flux(kAir, w, w, 0.5, 0.2, 0.1, &j);
  const Block a = euler_flux_jacobian(kAir, w, 0.5, 0.2);
  for (int k = 0; k < 16; ++k) EXPECT_NEAR(j.d_left[k] + j.d_right[k], a[k], 1e-9 * (std::abs(a[k]) + 1.0));
  const State u = kAir.conservative(w);
  for (int c = 0; c < 4; ++c) {
    State up = u;
    const double h = 1e-7 * (std::abs(u[c]) + 1.0);
    up[c] += h;
    const State f0 = roe_flux(kAir, w, w, 0.5, 0.2, 0.1);
    const State f1 = roe_flux(kAir, w, kAir.primitive(up), 0.5, 0.2, 0.1);
    for (int r = 0; r < 4; ++r) {
      const double fd = (f1[r] - f0[r]) / h;
      EXPECT_NEAR(j.d_right[4 * r + c], fd, 1e-4 * (std::abs(fd) + 1.0)) << r << "," << c;
    }
  }
}

namespace {
// Central differences of the Roe flux in the conservative variables of one side.
Block roe_flux_central_difference(const State& wl, const State& wr, double nx, double ny,
                                  double entropy_fix, bool right) {
  Block d{};
  const State u = kAir.conservative(right ? wr : wl);
  for (int c = 0; c < 4; ++c) {
    const double h = 1e-6 * (std::abs(u[c]) + std::sqrt(u[0] * u[3]));
    State up = u, um = u;
    up[c] += h;
    um[c] -= h;
    const State fp = right ? roe_flux(kAir, wl, kAir.primitive(up), nx, ny, entropy_fix)
                           : roe_flux(kAir, kAir.primitive(up), wr, nx, ny, entropy_fix);
    const State fm = right ? roe_flux(kAir, wl, kAir.primitive(um), nx, ny, entropy_fix)
                           : roe_flux(kAir, kAir.primitive(um), wr, nx, ny, entropy_fix);
    for (int r = 0; r < 4; ++r)
      d[4 * r + c] = (fp[r] - fm[r]) / (2.0 * h);
  }
  return d;
}

double largest_difference(const Block& a, const Block& b, double* scale) {
  double diff = 0.0;
  *scale = 0.0;
  for (int k = 0; k < 16; ++k) {
    diff = std::max(diff, std::abs(a[k] - b[k]));
    *scale = std::max(*scale, std::abs(b[k]));
  }
  return diff;
}
}  // namespace

TEST(RoeFlux, ExactJacobianMatchesCentralDifferencesWhereFrozenDissipationDoesNot) {
  // Pairs of states with a jump across the face: subsonic, a sonic point inside the entropy-fix
  // band (V.n - c near 0 at the Roe state), a stagnation line (V.n near 0) and a supersonic one.
  struct Case {
    const char* name;
    State wl, wr;
    double nx, ny;
  };
  const double c0 = std::sqrt(1.4 * 1.0e5 / 1.2);
  const Case cases[] = {
      {"subsonic", {1.2, 120.0, 30.0, 1.0e5}, {1.1, 140.0, 20.0, 0.95e5}, 0.8, 0.6},
      {"sonic", {1.2, 0.98 * c0, 5.0, 1.0e5}, {1.15, 1.03 * c0, -5.0, 0.97e5}, 1.0, 0.0},
      {"stagnation", {1.2, 3.0, 50.0, 1.0e5}, {1.21, -2.0, 45.0, 1.01e5}, 0.3, 0.0},
      {"supersonic", {0.8, 700.0, 40.0, 5.0e4}, {0.7, 720.0, 35.0, 4.5e4}, 0.5, 0.1},
  };
  for (const Case& k : cases) {
    RoeFluxJacobians exact, frozen;
    const State f = roe_flux_exact(kAir, k.wl, k.wr, k.nx, k.ny, 0.1, exact);
    roe_flux(kAir, k.wl, k.wr, k.nx, k.ny, 0.1, &frozen);
    const State f_plain = roe_flux(kAir, k.wl, k.wr, k.nx, k.ny, 0.1);
    for (int r = 0; r < 4; ++r)
      EXPECT_NEAR(f[r], f_plain[r], 1e-12 * (std::abs(f_plain[r]) + 1.0)) << k.name;
    // one scale for both sides: the supersonic flux does not depend on the right state at all
    double scale = 0.0;
    for (bool right : {false, true}) {
      double side_scale = 0.0;
      const Block fd = roe_flux_central_difference(k.wl, k.wr, k.nx, k.ny, 0.1, right);
      largest_difference(fd, fd, &side_scale);
      scale = std::max(scale, side_scale);
    }
    for (bool right : {false, true}) {
      const Block fd = roe_flux_central_difference(k.wl, k.wr, k.nx, k.ny, 0.1, right);
      double unused = 0.0;
      const double exact_error =
          largest_difference(right ? exact.d_right : exact.d_left, fd, &unused);
      const double frozen_error =
          largest_difference(right ? frozen.d_right : frozen.d_left, fd, &unused);
      std::printf(
          "%-10s %-5s: largest difference from central differences, exact %.1e, frozen "
          "%.1e (of the largest entry)\n",
          k.name, right ? "right" : "left", exact_error / scale, frozen_error / scale);
      EXPECT_LT(exact_error, 1e-6 * scale) << k.name << (right ? " right" : " left");
      // the frozen dissipation matrix is only the derivative of the flux for a vanishing jump
      EXPECT_GT(frozen_error, 1e3 * exact_error) << k.name << (right ? " right" : " left");
    }
  }
}
