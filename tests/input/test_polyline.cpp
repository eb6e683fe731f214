// Polyline helpers: offsets keep their distance (mitred corners), resampling keeps the ends,
// intersections are found where they are.
#include <gtest/gtest.h>

#include <cmath>

#include "tfmb/common/polyline.hpp"

using namespace tfmb::geometry;

TEST(Polyline, MitredOffsetKeepsTheDistanceToBothSegments) {
  const Polyline corner{{0, 0}, {1, 0}, {1, 1}};  // a left turn of 90 degrees
  const Polyline left = offset(corner, 0.1);
  ASSERT_EQ(left.size(), 3u);
  EXPECT_NEAR((left[1] - Point(0.9, 0.1)).norm(), 0.0, 1e-15);  // inside corner of the turn
  const Polyline right = offset(corner, -0.1);
  EXPECT_NEAR((right[1] - Point(1.1, -0.1)).norm(), 0.0, 1e-15);
  for (const auto& p : {left[0], left[2], right[0], right[2]}) EXPECT_NEAR(distance_to(corner, p), 0.1, 1e-15);
}

TEST(Polyline, ResampleHasEqualArcLengthsAndExactEnds) {
  Polyline arc;
  for (int i = 0; i <= 50; ++i) arc.emplace_back(std::cos(M_PI * i / 100.0), std::sin(M_PI * i / 100.0));
  const Polyline r = resample(arc, 7);
  ASSERT_EQ(r.size(), 8u);
  EXPECT_EQ(r.front(), arc.front());
  EXPECT_EQ(r.back(), arc.back());
  const auto s = tfmb::geometry::cumulative_length(r);
  const double first = s[1];
  // Chords of equal arcs on a polyline of the circle: equal to rounding of the polyline.
  for (std::size_t i = 1; i < s.size(); ++i) EXPECT_NEAR(s[i] - s[i - 1], first, 1e-3 * first);
}

TEST(Polyline, SelfIntersectionIsFoundAtItsPoint) {
  const Polyline loop{{0, 0}, {2, 0}, {2, 1}, {1, -1}};
  const auto c = self_intersection(loop);
  ASSERT_TRUE(c.has_value());
  EXPECT_NEAR(c->point.x(), 1.5, 1e-15);
  EXPECT_NEAR(c->point.y(), 0.0, 1e-15);
  EXPECT_FALSE(self_intersection(Polyline{{0, 0}, {1, 0}, {1, 1}, {0, 1}}).has_value());
  EXPECT_TRUE(self_intersection(Polyline{{0, 0}, {1, 0}, {1, 1}, {0, 1}}, true) == std::nullopt);
}

TEST(Polyline, CrossingIgnoresPointsNearJoints) {
  const Polyline a{{0, 0}, {1, 0}}, b{{1, 0}, {1, 1}};
  EXPECT_TRUE(crossing(a, b).has_value());
  EXPECT_FALSE(crossing(a, b, {Point(1, 0)}, 1e-9).has_value());
}
