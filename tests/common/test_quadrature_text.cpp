// libcommon's Gauss-Legendre rules and number formatter.
#include <gtest/gtest.h>

#include <cmath>

#include "tfmb/common/quadrature.hpp"
#include "tfmb/common/text.hpp"

namespace q = tfmb::quadrature;

// An n-point rule integrates x^k exactly for k <= 2n - 1 and not x^(2n) (so the test can fail).
TEST(Quadrature, UnitRuleIsExactUpToDegreeTwoNMinusOne) {
  for (int n = 1; n <= 8; ++n) {
    const auto rule = q::gauss_legendre_unit(n);
    ASSERT_EQ(rule.size(), static_cast<std::size_t>(n));
    auto integral = [&](int k) {
      double sum = 0.0;
      for (const auto& [x, w] : rule)
        sum += w * std::pow(x, k);
      return sum;
    };
    for (int k = 0; k <= 2 * n - 1; ++k)
      EXPECT_NEAR(integral(k), 1.0 / (k + 1), 1e-14) << "n " << n << " k " << k;
    EXPECT_GT(std::abs(integral(2 * n) - 1.0 / (2 * n + 1)), 1e-12)
        << "n " << n;  // the error is ~1e-10 at n = 8
  }
}

TEST(Quadrature, RefusesPointCountsOutsideItsRange) {
  EXPECT_THROW(q::gauss_legendre(0), std::invalid_argument);
  EXPECT_THROW(q::gauss_legendre(21), std::invalid_argument);
}

TEST(Text, FormatsWithTheGivenSignificantDigits) {
  EXPECT_EQ(tfmb::text::format_number(2.44e5), "244000");
  EXPECT_EQ(tfmb::text::format_number(1.0 / 3.0, 4), "0.3333");
  EXPECT_EQ(tfmb::text::format_number(1.25e-7), "1.25e-07");
}
