#include "tfmb/common/log.hpp"

#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>

namespace tfmb {

Logger::Logger(std::string tool_name, Verbosity verbosity)
    : tool_name_(std::move(tool_name)),
      verbosity_(verbosity),
      stream_(&std::cerr),
      is_terminal_(isatty(fileno(stderr)) != 0) {}

Logger::Logger(std::string tool_name, Verbosity verbosity, std::ostream& stream)
    : tool_name_(std::move(tool_name)), verbosity_(verbosity), stream_(&stream), is_terminal_(false) {}

void Logger::emit(const std::string& prefix, const std::string& message) const {
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

Progress::Progress(const Logger& logger, std::string label, std::size_t total)
    : logger_(logger), label_(std::move(label)), total_(total),
      start_(std::chrono::steady_clock::now()) {}

Progress::~Progress() { finish(); }

void Progress::update(std::size_t done) {
  if (finished_ || logger_.verbosity() < Verbosity::normal || total_ == 0) return;
  const double fraction = std::min(1.0, static_cast<double>(done) / static_cast<double>(total_));
  if (logger_.is_terminal()) {
    const int width = static_cast<int>(fraction * 40.0);
    if (width == last_width_) return;
    last_width_ = width;
    logger_.stream() << '\r' << logger_.tool_name() << ": " << label_ << " ["
                     << std::string(static_cast<std::size_t>(width), '#')
                     << std::string(static_cast<std::size_t>(40 - width), ' ') << "] "
                     << std::setw(3) << static_cast<int>(fraction * 100) << "%" << std::flush;
  } else {
    const int decile = static_cast<int>(fraction * 10.0);
    if (decile == last_decile_) return;
    last_decile_ = decile;
    logger_.stream() << logger_.tool_name() << ": " << label_ << " " << decile * 10 << "%\n"
                     << std::flush;
  }
}

void Progress::finish() {
  if (finished_) return;
  finished_ = true;
  if (logger_.is_terminal() && last_width_ >= 0) logger_.stream() << '\n' << std::flush;
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
