// Progress and messages on stderr (stdout stays clean for piping), DESIGN.md §5.
//
// A Logger is an object owned by the caller (no global logger): tools create one in main() and
// pass it to the stage's run(). Tests pass a quiet one.
#pragma once

#include <chrono>
#include <cstddef>
#include <functional>
#include <ostream>
#include <string>

namespace tfmb {

enum class Verbosity : int { quiet = 0, normal = 1, verbose = 2, debug = 3 };

class Logger {
 public:
  explicit Logger(std::string tool_name, Verbosity verbosity = Verbosity::normal);
  // For tests: write to any stream instead of std::cerr, taken for a terminal or not.
  Logger(std::string tool_name, Verbosity verbosity, std::ostream& stream,
         bool is_terminal = false);

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

// How a Progress reports.
struct ProgressSettings {
  std::string unit = "iterations";  // what is counted, plural
  // The loop may stop before the total (an iteration limit of a solve that stops once
  // converged): the time left is then an upper bound, written "ETA <= ...".
  bool total_is_limit = false;
  // Seconds between plain lines when stderr is not a terminal; negative: $TFMB_PROGRESS_INTERVAL
  // if set (0: a line at every update), else 10 s.
  double interval = -1.0;
  // false: the time so far instead of a rate and the time left, for counts whose items differ
  // much in cost (a mesher's phases), where a rate would promise a wrong time left.
  bool time_left = true;
};

// Progress of a loop with a known total or budget (iterations, load steps): done/total, rate
// and the time left at that rate. On a terminal one line is redrawn in place (at most five times
// a second) and erased by finish(); the cursor is left at its start, so that a line another part
// of the program prints overwrites it. Otherwise (a log, a pipe) a plain line every `interval`:
//   <tool>: progress: <label> <done>/<total> <unit>, <rate>, ETA [<=] <time left>
// (rate "4.2/s", or "41 s each" below one per second; "<time> so far" instead of rate and time
// left when settings.time_left is false), and ", in <activity> for <time>" while update_while()
// runs a long call. Nothing when the logger is quiet or the total is 0.
class Progress {
 public:
  Progress(const Logger& logger, std::string label, std::size_t total,
           ProgressSettings settings = {});
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  void update(std::size_t done);
  // The same as update() at `seconds` after construction (tests; update() reads the clock).
  void update_at(std::size_t done, double seconds);
  // Runs `work`, one long call that reports no count of its own (gmsh's meshing), in this thread
  // while a helper thread keeps the line going: update(done) with ", in <activity> for <time
  // spent in work>" at the usual pace (the terminal redraw or the interval). Nothing else may use
  // this Progress meanwhile. What work throws is passed on once the helper has stopped.
  void update_while(std::size_t done, const std::string& activity,
                    const std::function<void()>& work);
  void finish();

  // The line's text after "<tool>: " (without "progress: ") for `done` after `seconds`.
  std::string text(std::size_t done, double seconds) const;
  double interval() const { return interval_; }

 private:
  const Logger& logger_;
  std::string label_;
  std::size_t total_;
  ProgressSettings settings_;
  double interval_;         // [s] between plain lines
  double last_line_ = 0.0;  // [s] when the last plain line or terminal redraw was written
  bool drawn_ = false;      // a terminal line is showing
  bool finished_ = false;
  std::chrono::steady_clock::time_point start_;
  std::string activity_;         // what update_while() runs, empty outside it
  double activity_start_ = 0.0;  // [s] after construction, when it began
};

// "42 s", "7 min 26 s", "2 h 05 min": a duration [s] for people.
std::string format_duration(double seconds);

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
