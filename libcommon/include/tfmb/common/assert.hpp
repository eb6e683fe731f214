// Debug-only checks of internal invariants, beside the always-on user-facing checks of
// errors.hpp (tfmb::require, BadInput).
//
// TFMB_ASSERT(condition, message) states something that holds whatever the input, e.g. an index
// inside the array it was computed for. A failure is a bug in the code: it prints
//   internal error: <file>:<line>: assertion '<condition>' failed: <message>
// on stderr and throws tfmb::InternalError (exit 4 through cli::run_main). `message` is anything
// an std::ostream accepts, also a chain: TFMB_ASSERT(i < n, "node " << i << " of " << n).
//
// Builds with NDEBUG (Release, RelWithDebInfo) drop the check: neither the condition nor the
// message is evaluated, so hot loops pay nothing. They stay compiled, so the expressions cannot
// rot in a release-only build. Debug builds and the sanitizer build (Makefile.cases test-asan)
// keep it. An input can never be the cause: what an input can break is checked with BadInput.
#pragma once

#include <sstream>
#include <string>

namespace tfmb::detail {

// Prints the "internal error: ..." line and throws InternalError. Printing as well as throwing
// keeps the failure visible where a caller catches every exception (a retry loop, a test).
[[noreturn]] void assertion_failed(const char* file, int line, const char* condition,
                                   const std::string& message);

}  // namespace tfmb::detail

#ifdef NDEBUG
#define TFMB_ASSERT(condition, message)  \
  do {                                   \
    if (false) {                         \
      static_cast<void>(condition);      \
      std::ostringstream tfmb_assert_os; \
      tfmb_assert_os << message;         \
    }                                    \
  } while (false)
#else
#define TFMB_ASSERT(condition, message)                                                       \
  do {                                                                                        \
    if (!(condition)) {                                                                       \
      std::ostringstream tfmb_assert_os;                                                      \
      tfmb_assert_os << message;                                                              \
      ::tfmb::detail::assertion_failed(__FILE__, __LINE__, #condition, tfmb_assert_os.str()); \
    }                                                                                         \
  } while (false)
#endif
