// Errors and exit codes shared by every tfmb tool (DESIGN.md §5).
//
// Libraries throw; only main() turns an exception into an exit code (see cli.hpp run_main).
// User-facing errors carry one line that says what is wrong and where (file, path inside it,
// key, value) and, where it helps, how to fix it.
#pragma once

#include <stdexcept>
#include <string>

namespace tfmb {

enum class ExitCode : int {
  ok = 0,
  not_converged = 1,  // result written but flagged unconverged
  usage = 2,          // bad command line
  bad_input = 3,      // an input file or case file is invalid
  internal = 4,       // a bug or an environment failure (disk full, ...)
};

class Error : public std::runtime_error {
 public:
  Error(ExitCode code, const std::string& message) : std::runtime_error(message), code_(code) {}
  ExitCode code() const noexcept { return code_; }

 private:
  ExitCode code_;
};

// An input (file, case key, option value) is invalid. Exit code 3.
class BadInput : public Error {
 public:
  explicit BadInput(const std::string& message) : Error(ExitCode::bad_input, message) {}
};

// The command line is invalid. Exit code 2.
class UsageError : public Error {
 public:
  explicit UsageError(const std::string& message) : Error(ExitCode::usage, message) {}
};

// A solver stopped without converging; the caller decides whether a flagged result was written.
class NotConverged : public Error {
 public:
  explicit NotConverged(const std::string& message) : Error(ExitCode::not_converged, message) {}
};

// An invariant broke or the environment failed (I/O error while writing). Exit code 4.
class InternalError : public Error {
 public:
  explicit InternalError(const std::string& message) : Error(ExitCode::internal, message) {}
};

// Always-on user-facing check: throws BadInput(message) when the condition is false.
inline void require(bool condition, const std::string& message) {
  if (!condition) throw BadInput(message);
}

}  // namespace tfmb
