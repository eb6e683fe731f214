// Error types of the beam library. They mirror libcommon's (BadInput -> exit 3, NotConverged -> 1)
// so main.cpp can map them once libcommon exists.
#pragma once

#include <stdexcept>
#include <string>

namespace tfmb::beam {

/// The model cannot be solved as given (bad data, or a mechanism: free rigid-body motion).
struct ModelError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// Newton failed even after cutting the step back.
struct NotConvergedError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace tfmb::beam
