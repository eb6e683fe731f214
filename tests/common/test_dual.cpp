// Forward-mode automatic differentiation (libcommon dual.hpp): each operation and elementary
// function against its derivative by hand, and a composite against central differences.
#include <gtest/gtest.h>

#include <cmath>

#include "tfmb/common/dual.hpp"

using tfmb::Dual;

namespace {

// f(x, y) = sqrt(x) exp(-x y) / (1 + y^2) + pow(x, 1/6) cbrt(y) - log(x) max(x, y) + |x - y|
template <typename T>
T composite(const T& x, const T& y) {
  using std::abs;
  using std::cbrt;
  using std::exp;
  using std::log;
  using std::max;
  using std::pow;
  using std::sqrt;
  return sqrt(x) * exp(-x * y) / (1.0 + y * y) + pow(x, 1.0 / 6.0) * cbrt(y) - log(x) * max(x, y) +
         abs(x - y) - 3.0 / x;
}

}  // namespace

TEST(Dual, ArithmeticAndElementaryFunctions) {
  const auto x = Dual<2>::variable(0, 1.3);
  const auto y = Dual<2>::variable(1, -0.4);
  const auto p = x * y;
  EXPECT_DOUBLE_EQ(p.v, 1.3 * -0.4);
  EXPECT_DOUBLE_EQ(p.d[0], -0.4);
  EXPECT_DOUBLE_EQ(p.d[1], 1.3);
  const auto q = x / y;
  EXPECT_DOUBLE_EQ(q.d[0], 1.0 / -0.4);
  EXPECT_DOUBLE_EQ(q.d[1], -1.3 / (0.4 * 0.4));
  EXPECT_DOUBLE_EQ(sqrt(x).d[0], 0.5 / std::sqrt(1.3));
  EXPECT_DOUBLE_EQ(exp(y).d[1], std::exp(-0.4));
  EXPECT_DOUBLE_EQ(pow(x, 2.5).d[0], 2.5 * std::pow(1.3, 1.5));
  EXPECT_DOUBLE_EQ(cbrt(y).d[1], 1.0 / (3.0 * std::cbrt(0.16)));
  EXPECT_DOUBLE_EQ(abs(y).d[1], -1.0);
  EXPECT_EQ(min(x, y).v, -0.4);
  EXPECT_EQ(max(x, y).d[0], 1.0);
  EXPECT_TRUE(y < x && x > 1.0 && 0.0 > y);
}

TEST(Dual, CompositeAgreesWithCentralDifferences) {
  for (const auto& [x0, y0] : {std::pair{1.3, 0.7}, std::pair{0.4, 2.1}, std::pair{2.5, 0.2}}) {
    const auto f = composite(Dual<2>::variable(0, x0), Dual<2>::variable(1, y0));
    EXPECT_NEAR(f.v, composite(x0, y0), 1e-14 * std::abs(f.v));
    const double h = 1e-6;
    const double dfdx = (composite(x0 + h, y0) - composite(x0 - h, y0)) / (2.0 * h);
    const double dfdy = (composite(x0, y0 + h) - composite(x0, y0 - h)) / (2.0 * h);
    EXPECT_NEAR(f.d[0], dfdx, 1e-7 * (1.0 + std::abs(dfdx))) << x0 << " " << y0;
    EXPECT_NEAR(f.d[1], dfdy, 1e-7 * (1.0 + std::abs(dfdy))) << x0 << " " << y0;
  }
}
