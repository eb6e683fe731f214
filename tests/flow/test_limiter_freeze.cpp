// The limiter rise rule's count (SolverSettings::limiter_rise_iterations): rises in a row at the
// CFL ceiling, reset by a fall, by a CFL number below half the ceiling, and counting nothing on
// the first iteration (no previous residual).
#include <gtest/gtest.h>

#include <limits>

#include "tfmb-flow/solver.hpp"

using tfmb::flow::rises_at_ceiling;

TEST(LimiterRiseRule, CountsRisesInARowAtTheCeiling) {
  const double ceiling = 1e7;
  int count = rises_at_ceiling(0, 1.0, std::numeric_limits<double>::infinity(), ceiling, ceiling);
  EXPECT_EQ(count, 0);
  double previous = 1.0;
  for (const double r : {1.06, 1.12, 1.19, 1.26, 1.33}) {
    count = rises_at_ceiling(count, r, previous, ceiling, ceiling);
    previous = r;
  }
  EXPECT_EQ(count, 5);
  EXPECT_EQ(rises_at_ceiling(count, 1.30, 1.33, ceiling, ceiling), 0);        // a fall
  EXPECT_EQ(rises_at_ceiling(count, 1.40, 1.33, 0.6 * ceiling, ceiling), 6);  // near it
  EXPECT_EQ(rises_at_ceiling(count, 1.40, 1.33, 0.4 * ceiling, ceiling), 0);  // below half
  EXPECT_EQ(rises_at_ceiling(count, 1.33, 1.33, ceiling, ceiling), 0);        // no rise
}
