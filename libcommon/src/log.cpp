#include "tfmb/common/log.hpp"

#include <sys/ioctl.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <mutex>
#include <sstream>
#include <thread>

namespace tfmb {

Logger::Logger(std::string tool_name, Verbosity verbosity)
    : tool_name_(std::move(tool_name)),
      verbosity_(verbosity),
      stream_(&std::cerr),
      is_terminal_(isatty(fileno(stderr)) != 0) {}

Logger::Logger(std::string tool_name, Verbosity verbosity, std::ostream& stream, bool is_terminal)
    : tool_name_(std::move(tool_name)),
      verbosity_(verbosity),
      stream_(&stream),
      is_terminal_(is_terminal) {}

void Logger::emit(const std::string& prefix, const std::string& message) const {
  // On a terminal a progress line may be showing: erase it, then the message takes its place.
  if (is_terminal_)
    *stream_ << "\r\033[K";
  *stream_ << tool_name_ << ": " << prefix << message << '\n';
  stream_->flush();
}

void Logger::info(const std::string& message) const {
  if (verbosity_ >= Verbosity::normal) emit("", message);
}
void Logger::verbose(const std::string& message) const {
  if (verbosity_ >= Verbosity::verbose) emit("", message);
}
void Logger::debug(const std::string& message) const {
  if (verbosity_ >= Verbosity::debug) emit("debug: ", message);
}
void Logger::warn(const std::string& message) const { emit("warning: ", message); }
void Logger::summary(const std::string& message) const { emit("", message); }

namespace {

// Seconds between plain progress lines: $TFMB_PROGRESS_INTERVAL (workflows/stage asks for lines
// often when it draws them on a terminal itself), else 10 s, few enough for a log.
double default_interval() {
  if (const char* value = std::getenv("TFMB_PROGRESS_INTERVAL"); value && *value) {
    char* end = nullptr;
    const double seconds = std::strtod(value, &end);
    if (end != value && *end == '\0' && seconds >= 0.0 && std::isfinite(seconds))
      return seconds;
  }
  return 10.0;
}

// Columns of the terminal on stderr (80 if unknown): a redrawn line must not wrap, or the next
// redraw leaves the wrapped part behind.
std::size_t terminal_columns() {
  winsize size{};
  if (ioctl(fileno(stderr), TIOCGWINSZ, &size) == 0 && size.ws_col > 0)
    return size.ws_col;
  return 80;
}

}  // namespace

std::string format_duration(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0.0)
    return "?";
  const long total = std::lround(seconds);
  char buffer[64];
  if (total < 60) {
    std::snprintf(buffer, sizeof buffer, "%ld s", total);
  } else if (total < 3600) {
    std::snprintf(buffer, sizeof buffer, "%ld min %02ld s", total / 60, total % 60);
  } else {
    const long minutes = (total + 30) / 60;
    std::snprintf(buffer, sizeof buffer, "%ld h %02ld min", minutes / 60, minutes % 60);
  }
  return buffer;
}

Progress::Progress(const Logger& logger, std::string label, std::size_t total,
                   ProgressSettings settings)
    : logger_(logger),
      label_(std::move(label)),
      total_(total),
      settings_(std::move(settings)),
      interval_(settings_.interval >= 0.0 ? settings_.interval : default_interval()),
      start_(std::chrono::steady_clock::now()) {}

Progress::~Progress() { finish(); }

std::string Progress::text(std::size_t done, double seconds) const {
  std::ostringstream line;
  line << label_ << ' ' << done << '/' << total_ << ' ' << settings_.unit;
  const std::string activity = activity_.empty() ? std::string()
                                                 : ", in " + activity_ + " for " +
                                                       format_duration(seconds - activity_start_);
  if (!settings_.time_left) {
    line << ", " << format_duration(seconds) << " so far" << activity;
    return line.str();
  }
  const double rate = seconds > 0.0 ? static_cast<double>(done) / seconds : 0.0;
  if (done == 0 || rate <= 0.0) {
    line << ", ETA ?" << activity;
    return line.str();
  }
  // a rate below one per second reads better as the time each takes
  char buffer[32];
  if (rate >= 1.0) {
    std::snprintf(buffer, sizeof buffer, rate >= 10.0 ? "%.0f/s" : "%.1f/s", rate);
  } else if (1.0 / rate < 9.95) {
    std::snprintf(buffer, sizeof buffer, "%.1f s each", 1.0 / rate);
  } else {
    std::snprintf(buffer, sizeof buffer, "%s each", format_duration(1.0 / rate).c_str());
  }
  const double left = done >= total_ ? 0.0 : static_cast<double>(total_ - done) / rate;
  line << ", " << buffer << ", ETA " << (settings_.total_is_limit ? "<= " : "")
       << format_duration(left) << activity;
  return line.str();
}

void Progress::update_while(std::size_t done, const std::string& activity,
                            const std::function<void()>& work) {
  activity_ = activity;
  activity_start_ =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  update(done);
  // The helper wakes at the terminal's redraw pace, or often enough for the interval of plain
  // lines (update() itself keeps to the interval).
  const double pace = logger_.is_terminal() ? 0.2 : std::clamp(interval_, 0.2, 1.0);
  std::mutex mutex;
  std::condition_variable wake;
  bool stop = false;
  std::thread helper([&] {
    std::unique_lock lock(mutex);
    while (!wake.wait_for(lock, std::chrono::duration<double>(pace), [&] { return stop; }))
      update(done);
  });
  // Stops and joins the helper however work() ends.
  struct Join {
    std::mutex& mutex;
    std::condition_variable& wake;
    bool& stop;
    std::thread& helper;
    ~Join() {
      {
        const std::lock_guard lock(mutex);
        stop = true;
      }
      wake.notify_one();
      helper.join();
    }
  };
  {
    const Join join{mutex, wake, stop, helper};
    work();
  }
  activity_.clear();
}

void Progress::update(std::size_t done) {
  update_at(done, std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count());
}

void Progress::update_at(std::size_t done, double seconds) {
  if (finished_ || logger_.verbosity() < Verbosity::normal || total_ == 0) return;
  std::ostream& out = logger_.stream();
  if (logger_.is_terminal()) {
    if (drawn_ && seconds - last_line_ < 0.2 && done < total_)
      return;
    last_line_ = seconds;
    std::string line = logger_.tool_name() + ": " + text(done, seconds);
    const std::size_t columns = terminal_columns();
    if (line.size() >= columns)
      line.resize(columns - 1);
    out << '\r' << line << "\033[K\r" << std::flush;
    drawn_ = true;
  } else {
    if (seconds - last_line_ < interval_)
      return;
    last_line_ = seconds;
    out << logger_.tool_name() << ": progress: " << text(done, seconds) << '\n' << std::flush;
  }
}

void Progress::finish() {
  if (finished_) return;
  finished_ = true;
  if (drawn_)
    logger_.stream() << "\r\033[K" << std::flush;
}

std::size_t peak_memory_bytes() {
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line)) {
    if (line.rfind("VmHWM:", 0) == 0) {
      std::istringstream fields(line.substr(6));
      std::size_t kib = 0;
      fields >> kib;
      return kib * 1024;
    }
  }
  return 0;
}

}  // namespace tfmb
