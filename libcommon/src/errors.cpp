#include "tfmb/common/errors.hpp"

#include <iostream>

#include "tfmb/common/assert.hpp"

namespace tfmb::detail {

void assertion_failed(const char* file, int line, const char* condition,
                      const std::string& message) {
  const std::string where = std::string(file) + ":" + std::to_string(line) + ": assertion '" +
                            condition + "' failed: " + message;
  std::cerr << "internal error: " << where << std::endl;
  throw InternalError(where);
}

}  // namespace tfmb::detail
