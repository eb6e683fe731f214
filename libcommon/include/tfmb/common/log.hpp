// Progress and messages on stderr (stdout stays clean for piping), DESIGN.md §5.
//
// A Logger is an object owned by the caller (no global logger): tools create one in main() and
// pass it to the stage's run(). Tests pass a quiet one.
#pragma once

#include <chrono>
#include <cstddef>
#include <ostream>
#include <string>

namespace tfmb {

enum class Verbosity : int { quiet = 0, normal = 1, verbose = 2, debug = 3 };

class Logger {
 public:
  explicit Logger(std::string tool_name, Verbosity verbosity = Verbosity::normal);
  // For tests: write to any stream instead of std::cerr.
  Logger(std::string tool_name, Verbosity verbosity, std::ostream& stream);

  void info(const std::string& message) const;     // normal and above
  void verbose(const std::string& message) const;  // verbose and above
  void debug(const std::string& message) const;    // debug only
  void warn(const std::string& message) const;     // always, prefixed "warning:"
  // The one final summary line of a run; always printed.
  void summary(const std::string& message) const;

  Verbosity verbosity() const { return verbosity_; }
  const std::string& tool_name() const { return tool_name_; }
  std::ostream& stream() const { return *stream_; }
  bool is_terminal() const { return is_terminal_; }

 private:
  void emit(const std::string& prefix, const std::string& message) const;
  std::string tool_name_;
  Verbosity verbosity_;
  std::ostream* stream_;
  bool is_terminal_;
};

// A progress bar on a terminal, or a line every 10 % when stderr is a file or pipe.
class Progress {
 public:
  Progress(const Logger& logger, std::string label, std::size_t total);
  ~Progress();
  void update(std::size_t done);
  void finish();

 private:
  const Logger& logger_;
  std::string label_;
  std::size_t total_;
  int last_decile_ = -1;
  int last_width_ = -1;
  bool finished_ = false;
  std::chrono::steady_clock::time_point start_;
};

// Wall-clock seconds since construction.
class Stopwatch {
 public:
  Stopwatch() : start_(std::chrono::steady_clock::now()) {}
  double seconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }

 private:
  std::chrono::steady_clock::time_point start_;
};

// Peak resident memory of this process [bytes] (VmHWM from /proc/self/status; 0 if unknown).
std::size_t peak_memory_bytes();

}  // namespace tfmb
