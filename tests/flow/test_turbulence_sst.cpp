// k-omega SST model terms (tools/tfmb-flow/turbulence_sst.cpp) against the relations that define
// its constants (Menter 1994; NASA TMR, https://turbmodels.larc.nasa.gov/sst.html).
#include <gtest/gtest.h>

#include <cmath>

#include "tfmb-flow/turbulence_sst.hpp"

using namespace tfmb::flow;

TEST(Sst, ConstantsOfBothVariants) {
  const sst::Constants v = sst::constants(sst::Variant::sst_v);
  EXPECT_NEAR(v.gamma1, 0.5532, 1e-4);
  EXPECT_NEAR(v.gamma2, 0.4404, 1e-4);
  EXPECT_TRUE(v.vorticity);
  EXPECT_FALSE(v.limit_omega_production);
  const sst::Constants c = sst::constants(sst::Variant::sst2003);
  // TMR: gamma1 = 5/9 is about 0.43 % above Menter 1994's, gamma2 = 0.44 about 0.08 % below
  EXPECT_NEAR(c.gamma1 / v.gamma1 - 1.0, 0.0043, 2e-4);
  EXPECT_NEAR(c.gamma2 / v.gamma2 - 1.0, -8e-4, 1e-4);
  EXPECT_FALSE(c.vorticity);
  EXPECT_TRUE(c.limit_omega_production);
}

// The log layer of the inner (k-omega) model: k = u_tau^2 / sqrt(beta*), omega = u_tau /
// (sqrt(beta*) kappa y), dU/dy = u_tau / (kappa y). Production balances dissipation exactly in
// the k equation, and in the omega equation the sources balance the diffusion
// d/dy(sigma_w nu_t d omega/dy) = sigma_w u_tau^2 / (sqrt(beta*) y^2): that is how gamma1 is
// defined (Menter 1994, eq. 2 with gamma = beta/beta* - sigma_w kappa^2 / sqrt(beta*)).
TEST(Sst, LogLayerBalances) {
  const sst::Constants c = sst::constants(sst::Variant::sst_v);
  const double u_tau = 1.5, root = std::sqrt(sst::beta_star);
  for (double y : {1e-4, 1e-3, 1e-2}) {
    const double k = u_tau * u_tau / root;
    const double omega = u_tau / (root * sst::kappa * y);
    const double shear_rate = u_tau / (sst::kappa * y);
    const sst::Shear s = sst::shear(0.0, shear_rate, 0.0, 0.0);
    const sst::Source src = sst::source(c, k, omega, s, 1.0, 1.0, 0.0);
    EXPECT_FALSE(src.limited);
    EXPECT_NEAR(src.k / (sst::beta_star * omega * k), 0.0, 1e-12) << "y = " << y;
    const double diffusion = sst::sigma_w1 * u_tau * u_tau / (root * y * y);
    EXPECT_NEAR((src.omega + diffusion) / diffusion, 0.0, 1e-12) << "y = " << y;
    // a1 omega > Omega F2 there: mu_t = rho k / omega, nu_t = kappa u_tau y
    EXPECT_NEAR(sst::eddy_viscosity(1.0, k, omega, shear_rate, 1.0), sst::kappa * u_tau * y,
                1e-12 * u_tau * y);
  }
}

TEST(Sst, ShearStressLimiterAndProductionLimiter) {
  const sst::Constants c = sst::constants(sst::Variant::sst2003);
  const double rho = 1.2, k = 2.0, omega = 100.0;
  // a strain rate far above a1 omega / F2: mu_t = rho a1 k / (S F2)
  const double strain = 1e4;
  EXPECT_NEAR(sst::eddy_viscosity(rho, k, omega, strain, 1.0), rho * sst::a1 * k / strain, 1e-15);
  EXPECT_NEAR(sst::eddy_viscosity(rho, k, omega, strain, 0.0), rho * k / omega, 1e-15);
  EXPECT_EQ(sst::eddy_viscosity(rho, 0.0, omega, strain, 1.0), 0.0);
  // pure shear S = 1e4 1/s with F2 = 0: P / (rho k) = S^2 / omega = 1e6 > 10 beta* omega
  const sst::Shear s = sst::shear(0.0, strain, 0.0, 0.0);
  const sst::Source src = sst::source(c, k, omega, s, 1.0, 0.0, 0.0);
  EXPECT_TRUE(src.limited);
  EXPECT_NEAR(src.k, k * (10.0 - 1.0) * sst::beta_star * omega, 1e-9);
  // SST-2003 limits the omega production as well: gamma1 (10 beta* omega) omega - beta1 omega^2
  EXPECT_NEAR(src.omega, (c.gamma1 * 10.0 * sst::beta_star - sst::beta1) * omega * omega, 1e-6);
  // SST-V (Menter 1994) limits the k equation's only, at 20 beta* rho omega k
  const sst::Constants v = sst::constants(sst::Variant::sst_v);
  const sst::Source sv = sst::source(v, k, omega, s, 1.0, 0.0, 0.0);
  EXPECT_NEAR(sv.k, k * (20.0 - 1.0) * sst::beta_star * omega, 1e-9);
  EXPECT_NEAR(sv.omega, v.gamma1 * strain * strain - sst::beta1 * omega * omega, 1e-6);
  // the implicit parts are stabilising
  EXPECT_LT(src.k_slope, 0.0);
  EXPECT_LT(src.omega_slope, 0.0);
}

TEST(Sst, BlendingNearAndFarFromTheWall) {
  const sst::Constants c = sst::constants(sst::Variant::sst2003);
  const double nu = 1.5e-5;
  // close to the wall the viscous argument 500 nu / (d^2 omega) is large: F1 = F2 = 1
  const sst::Blending wall = sst::blending(c, 1e-3, 1e6, nu, 1e-5, 0.0);
  EXPECT_NEAR(wall.f1, 1.0, 1e-12);
  EXPECT_NEAR(wall.f2, 1.0, 1e-12);
  // far from it in a free stream of TMR's values (a = 347 m/s): both vanish
  const double a = 347.0, rho = 1.2, mu = 1.8e-5;
  const sst::Blending far =
      sst::blending(c, sst::freestream_k(a), sst::freestream_omega(rho, a, mu), nu, 1.0, 0.0);
  EXPECT_LT(far.f1, 1e-6);
  EXPECT_LT(far.f2, 1e-6);
}

TEST(Sst, BoundaryValues) {
  // TMR's far-field k and omega give mu_t / mu = 9e-9 / 1e-6 = 0.009 at any velocity
  const double a = 340.0, rho = 1.2, mu = 1.8e-5;
  const double k = sst::freestream_k(a), omega = sst::freestream_omega(rho, a, mu);
  EXPECT_NEAR(sst::eddy_viscosity(rho, k, omega, 0.0, 0.0) / mu, 0.009, 1e-12);
  // omega_wall = 10 * 6 nu / (beta1 d1^2)
  EXPECT_NEAR(sst::wall_omega(1.5e-5, 1e-6), 60.0 * 1.5e-5 / (0.075 * 1e-12), 1e-3);
}

TEST(Sst, ShearInvariants) {
  // pure shear: S = Omega = |du/dy|
  sst::Shear s = sst::shear(0.0, 3.0, 0.0, 0.0);
  EXPECT_NEAR(s.strain, 3.0, 1e-14);
  EXPECT_NEAR(s.vorticity, 3.0, 1e-14);
  EXPECT_EQ(s.divergence, 0.0);
  // solid-body rotation: no strain
  s = sst::shear(0.0, -2.0, 2.0, 0.0);
  EXPECT_NEAR(s.strain, 0.0, 1e-14);
  EXPECT_NEAR(s.vorticity, 4.0, 1e-14);
  // axisymmetric radial expansion u_r = r: du_r/dr = v/r = 1, S^2 = 2 (1 + 1)
  s = sst::shear(0.0, 0.0, 0.0, 1.0, 1.0);
  EXPECT_NEAR(s.strain, 2.0, 1e-14);
  EXPECT_NEAR(s.divergence, 2.0, 1e-14);
}
