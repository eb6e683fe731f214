// TFMB_ASSERT's failure path, checked in every build: this file compiles it as a Debug build
// does, whatever the build type. (It includes no more than the macro needs, so no inline
// function of a library header gets a second, differently asserted definition.)
#undef NDEBUG
#include <gtest/gtest.h>

#include <string>

#include "tfmb/common/assert.hpp"
#include "tfmb/common/errors.hpp"

namespace tfmb {
namespace {

void check_index(int index, int size) {
  TFMB_ASSERT(index >= 0 && index < size, "index " << index << " of " << size);
}

TEST(AssertActive, FailureThrowsInternalErrorAndPrintsWhere) {
  EXPECT_NO_THROW(check_index(2, 3));
  testing::internal::CaptureStderr();
  try {
    check_index(3, 3);
    ADD_FAILURE() << "no exception";
  } catch (const InternalError& error) {
    EXPECT_EQ(error.code(), ExitCode::internal);  // run_main's exit code 4
    EXPECT_NE(std::string(error.what())
                  .find("assertion 'index >= 0 && index < size' failed: index 3 of 3"),
              std::string::npos)
        << error.what();
  }
  const std::string printed = testing::internal::GetCapturedStderr();
  EXPECT_EQ(printed.rfind("internal error: ", 0), 0u) << printed;
  EXPECT_NE(printed.find("test_assert_active.cpp:"), std::string::npos) << printed;
  EXPECT_NE(printed.find(": assertion 'index >= 0 && index < size' failed: index 3 of 3\n"),
            std::string::npos)
      << printed;
}

}  // namespace
}  // namespace tfmb
