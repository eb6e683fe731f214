// TFMB_ASSERT as this build compiles it: active without NDEBUG (Debug, the sanitizer build),
// dropped with NDEBUG (Release), where the condition must not even be evaluated.
#include <gtest/gtest.h>

#include "tfmb/common/assert.hpp"
#include "tfmb/common/errors.hpp"

namespace tfmb {
namespace {

TEST(Assert, FollowsTheBuildType) {
  int evaluations = 0;
  auto broken = [&evaluations] {
    ++evaluations;
    return false;
  };
#ifdef NDEBUG
  EXPECT_NO_THROW(TFMB_ASSERT(broken(), "never built"));
  EXPECT_EQ(evaluations, 0);
#else
  EXPECT_THROW(TFMB_ASSERT(broken(), "index " << 3), InternalError);
  EXPECT_EQ(evaluations, 1);
#endif
}

TEST(Assert, AHoldingConditionIsEvaluatedAtMostOnce) {
  int evaluations = 0;
  TFMB_ASSERT(++evaluations > 0, "unreachable");
  EXPECT_LE(evaluations, 1);
}

}  // namespace
}  // namespace tfmb
