#include <gtest/gtest.h>

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
