// Spalart-Allmaras source terms and the wall distance (tools/tfmb-flow/turbulence_sa.cpp,
// wall_distance.cpp).
#include <gtest/gtest.h>

#include <cmath>

#include "tfmb-flow/turbulence_sa.hpp"
#include "tfmb-flow/wall_distance.hpp"

using namespace tfmb::flow;

// In the log layer nu_tilde = kappa u_tau y, Omega = u_tau / (kappa y), d = y; with fv2, ft2 -> 0
// (chi large) r = 1, fw = 1, and production - destruction must balance the diffusion
// (1 + cb2)/sigma (kappa u_tau)^2: that is how cw1 is defined (Spalart and Allmaras 1994).
TEST(SpalartAllmaras, LogLayerBalancesDiffusion) {
  const double u_tau = 2.0, nu = 1e-9;
  for (double y : {1e-3, 1e-2, 0.1}) {
    const double nu_tilde = sa::kappa * u_tau * y;
    const sa::Source s = sa::source(nu_tilde, nu, u_tau / (sa::kappa * y), y);
    const double diffusion = (1.0 + sa::cb2) / sa::sigma * std::pow(sa::kappa * u_tau, 2);
    EXPECT_NEAR((s.production - s.destruction + diffusion) / diffusion, 0.0, 1e-3) << "y = " << y;
  }
}

TEST(SpalartAllmaras, EddyViscosityAndNegativeBranch) {
  const double nu = 1.5e-5, rho = 1.2;
  // chi = cv1: fv1 = 1/2
  EXPECT_NEAR(sa::eddy_viscosity(rho, sa::cv1 * nu, nu), rho * sa::cv1 * nu * 0.5, 1e-15);
  EXPECT_EQ(sa::eddy_viscosity(rho, -1e-5, nu), 0.0);
  // SA-neg: production cb1 (1 - ct3) Omega nu_tilde, destruction -cw1 (nu_tilde/d)^2
  const double nt = -2e-5, omega = 300.0, d = 0.01;
  const sa::Source s = sa::source(nt, nu, omega, d);
  EXPECT_NEAR(s.production, sa::cb1 * (1.0 - sa::ct3) * omega * nt, 1e-15);
  EXPECT_NEAR(s.destruction, -sa::cw1 * nt * nt / (d * d), 1e-12);
  // diffusion coefficient with fn = (cn1 + chi^3)/(cn1 - chi^3)
  const double chi = nt / nu;
  EXPECT_NEAR(sa::diffusivity(nt, nu), nu + nt * (16.0 + chi * chi * chi) / (16.0 - chi * chi * chi), 1e-18);
  EXPECT_GT(sa::diffusivity(nt, nu), 0.0);
}

// The implicit coefficient is the source's derivative where that is negative, never positive.
TEST(SpalartAllmaras, SourceDerivativeIsNonPositiveAndConsistent) {
  const double nu = 1.5e-5;
  for (double chi : {0.5, 3.0, 30.0, 300.0}) {
    for (double d : {1e-5, 1e-3, 0.1}) {
      const double nt = chi * nu, omega = 1e3;
      const sa::Source s = sa::source(nt, nu, omega, d);
      EXPECT_LE(s.d_source, 0.0);
      const double h = 1e-6 * nt;
      const sa::Source a = sa::source(nt + h, nu, omega, d), b = sa::source(nt - h, nu, omega, d);
      const double fd = ((a.production - a.destruction) - (b.production - b.destruction)) / (2.0 * h);
      if (fd < 0.0) {
        EXPECT_NEAR(s.d_source, fd, 1e-4 * std::abs(fd) + 1e-12) << "chi " << chi << " d " << d;
      }
    }
  }
}

TEST(WallDistance, ExactToSegmentsAndEnds) {
  const std::vector<std::array<Vec2, 2>> walls = {{Vec2{0.0, 0.0}, Vec2{1.0, 0.0}}, {Vec2{1.0, 0.0}, Vec2{1.0, 1.0}}};
  const std::vector<Vec2> points = {{0.5, 0.3}, {-0.3, 0.4}, {0.9, 0.5}, {2.0, 0.5}, {0.2, 0.0}};
  const auto d = wall_distance(points, walls);
  EXPECT_DOUBLE_EQ(d[0], 0.3);
  EXPECT_DOUBLE_EQ(d[1], 0.5);   // to the end point (0, 0)
  EXPECT_NEAR(d[2], 0.1, 1e-15);  // nearer to the vertical wall
  EXPECT_DOUBLE_EQ(d[3], 1.0);
  EXPECT_DOUBLE_EQ(d[4], 0.0);
  EXPECT_TRUE(std::isinf(wall_distance(points, {})[0]));
}

// The exact derivative (forward AD) of production - destruction against central differences,
// over both S-tilde branches (the clipping of TMR note 1(c) where S-bar < -cv2 Omega), the
// r = 10 cap, with and without ft2, and the SA-neg branch.
TEST(SpalartAllmaras, SourceDerivativeByAutomaticDifferentiationMatchesDifferences) {
  const double nu = 1.5e-5;
  int clipped = 0, capped = 0;
  for (bool ft2 : {true, false}) {
    for (double chi : {-2.0, 0.5, 3.0, 30.0, 300.0}) {
      for (double d : {1e-5, 1e-3, 0.1}) {
        for (double omega : {1.0, 1e3, 1e5}) {
          const double nt = chi * nu;
          const double kd2 = sa::kappa * sa::kappa * d * d;
          const double c3 = chi * chi * chi;
          const double fv2 = 1.0 - chi / (1.0 + chi * c3 / (c3 + sa::cv1 * sa::cv1 * sa::cv1));
          const double s_bar = nt * fv2 / kd2;
          const double h = 1e-6 * std::abs(nt);
          auto source = [&](double x) {
            const sa::Source s = sa::source(x, nu, omega, d, ft2);
            return s.production - s.destruction;
          };
          if (chi > 0.0) {
            // stay on one branch for the difference
            const bool near_switch = std::abs(s_bar + sa::cv2 * omega) < 1e-3 * std::abs(s_bar);
            if (near_switch)
              continue;
            clipped += s_bar < -sa::cv2 * omega;
            capped += nt / ((omega + s_bar) * kd2) >= 10.0;
          }
          const double fd = (source(nt + h) - source(nt - h)) / (2.0 * h);
          const double ad = sa::source_derivative(nt, nu, omega, d, ft2);
          EXPECT_NEAR(ad, fd, 1e-6 * std::abs(fd) + 1e-9 * std::abs(source(nt)) / std::abs(nt))
              << "chi " << chi << " d " << d << " omega " << omega << " ft2 " << ft2;
          EXPECT_EQ(sa::source(nt, nu, omega, d, ft2).d_source, std::min(ad, 0.0));
        }
      }
    }
  }
  EXPECT_GT(clipped, 0);  // both branches were exercised
  EXPECT_GT(capped, 0);
}
