#include <gtest/gtest.h>

#include <cmath>

#include "exact_nozzle.hpp"

using namespace tfmb::flow;

TEST(ExactNozzle, AreaMachRelationRoundTrip) {
  for (double m : {0.1, 0.5, 0.99, 1.01, 2.0, 3.5}) {
    const double r = area_ratio_of_mach(m, 1.4);
    EXPECT_NEAR(mach_of_area_ratio(r, 1.4, m > 1.0), m, 1e-10);
  }
  // Anderson (2003) table A.1: M = 2, A/A* = 1.688, p/p0 = 0.1278
  EXPECT_NEAR(area_ratio_of_mach(2.0, 1.4), 1.688, 1e-3);
  EXPECT_NEAR(isentropic_pressure_ratio(2.0, 1.4), 0.1278, 1e-4);
  // table A.2: M1 = 2: M2 = 0.5774, p02/p01 = 0.7209
  EXPECT_NEAR(normal_shock_mach(2.0, 1.4), 0.5774, 1e-4);
  EXPECT_NEAR(normal_shock_total_pressure_ratio(2.0, 1.4), 0.7209, 1e-4);
}

TEST(ExactNozzle, ShockSolutionMatchesExitPressure) {
  auto area = [](double x) {
    const double pi = std::acos(-1.0);
    return x < 5.0 ? 1.75 - 0.75 * std::cos((0.2 * x - 1.0) * pi) : 1.25 - 0.25 * std::cos((0.2 * x - 1.0) * pi);
  };
  const Quasi1dNozzle q(area, 0.0, 5.0, 10.0, 1.4, 0.75);
  ASSERT_TRUE(q.choked());
  ASSERT_TRUE(q.has_shock());
  EXPECT_GT(q.shock_position(), 5.0);
  EXPECT_LT(q.shock_position(), 10.0);
  EXPECT_NEAR(q.pressure_ratio(10.0), 0.75, 1e-9);
  EXPECT_NEAR(q.mach(5.0 - 1e-9), 1.0, 1e-3);
  const Quasi1dNozzle sub(area, 0.0, 5.0, 10.0, 1.4, 0.89);
  EXPECT_FALSE(sub.choked());
  EXPECT_NEAR(sub.pressure_ratio(10.0), 0.89, 1e-9);
  const Quasi1dNozzle sup(area, 0.0, 5.0, 10.0, 1.4, 0.16);
  EXPECT_TRUE(sup.choked());
  EXPECT_FALSE(sup.has_shock());
  EXPECT_NEAR(sup.mach(10.0), mach_of_area_ratio(1.5, 1.4, true), 1e-9);
}
