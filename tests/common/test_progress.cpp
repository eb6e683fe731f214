// Progress (libcommon log.hpp): plain lines at the interval in a log, one redrawn line on a
// terminal, the rate and the time left, nothing when quiet.
#include <gtest/gtest.h>

#include <chrono>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>

#include "tfmb/common/log.hpp"

namespace {

int count(const std::string& text, const std::string& what) {
  int n = 0;
  for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1))
    ++n;
  return n;
}

}  // namespace

TEST(Progress, TextGivesCountRateAndTimeLeft) {
  std::ostringstream out;
  const tfmb::Logger log("tfmb-x", tfmb::Verbosity::normal, out);
  const tfmb::Progress progress(log, "solve", 2000, {.total_is_limit = true, .interval = 10.0});
  // 120 iterations in 30 s: 4 per second, 1880 left take 470 s
  EXPECT_EQ(progress.text(120, 30.0), "solve 120/2000 iterations, 4.0/s, ETA <= 7 min 50 s");
  EXPECT_EQ(progress.text(0, 0.0), "solve 0/2000 iterations, ETA ?");
  // below one per second: the time each takes
  EXPECT_EQ(progress.text(3, 123.0), "solve 3/2000 iterations, 41 s each, ETA <= 22 h 45 min");
  EXPECT_EQ(progress.text(10, 25.0), "solve 10/2000 iterations, 2.5 s each, ETA <= 1 h 23 min");
  const tfmb::Progress steps(log, "load steps", 10, {.unit = "steps", .interval = 10.0});
  EXPECT_EQ(steps.text(5, 2.5), "load steps 5/10 steps, 2.0/s, ETA 3 s");  // 2.5 s, rounded
  EXPECT_EQ(steps.text(10, 2.5), "load steps 10/10 steps, 4.0/s, ETA 0 s");
}

TEST(Progress, FormatDuration) {
  EXPECT_EQ(tfmb::format_duration(0.4), "0 s");
  EXPECT_EQ(tfmb::format_duration(59.4), "59 s");
  EXPECT_EQ(tfmb::format_duration(446.0), "7 min 26 s");
  EXPECT_EQ(tfmb::format_duration(7530.0), "2 h 06 min");
  EXPECT_EQ(tfmb::format_duration(-1.0), "?");
}

TEST(Progress, PlainLinesAtTheInterval) {
  std::ostringstream out;
  const tfmb::Logger log("tfmb-x", tfmb::Verbosity::normal, out);
  {
    tfmb::Progress progress(log, "solve", 100, {.interval = 10.0});
    for (int i = 1; i <= 100; ++i)
      progress.update_at(i, 0.5 * i);  // 50 s in all
  }
  // one line at 10, 20, 30, 40 and 50 s, each whole, none drawn in place
  EXPECT_EQ(count(out.str(), "tfmb-x: progress: solve "), 5) << out.str();
  EXPECT_EQ(count(out.str(), "\n"), 5);
  EXPECT_EQ(out.str().find('\r'), std::string::npos);
  EXPECT_NE(out.str().find("tfmb-x: progress: solve 20/100 iterations, 2.0/s, ETA 40 s\n"),
            std::string::npos)
      << out.str();
}

TEST(Progress, IntervalZeroWritesEveryUpdate) {
  std::ostringstream out;
  const tfmb::Logger log("tfmb-x", tfmb::Verbosity::normal, out);
  tfmb::Progress progress(log, "solve", 3, {.interval = 0.0});
  for (int i = 1; i <= 3; ++i)
    progress.update_at(i, 0.01 * i);
  EXPECT_EQ(count(out.str(), "progress:"), 3);
}

TEST(Progress, TerminalRedrawsOneLineAndErasesIt) {
  std::ostringstream out;
  const tfmb::Logger log("tfmb-x", tfmb::Verbosity::normal, out, true);
  {
    tfmb::Progress progress(log, "solve", 16, {.interval = 10.0});
    for (int i = 1; i <= 16; ++i)
      progress.update_at(i, 0.125 * i);  // 2 s in all
  }
  const std::string text = out.str();
  EXPECT_EQ(text.find('\n'), std::string::npos);  // never a new line
  // redrawn at most five times a second (every other update here), and at the end
  EXPECT_EQ(count(text, "tfmb-x: solve "), 9) << text;
  EXPECT_NE(text.find("\rtfmb-x: solve 3/16 iterations, 8.0/s, ETA 2 s\033[K\r"),
            std::string::npos);
  EXPECT_NE(text.find("tfmb-x: solve 16/16 iterations"), std::string::npos);
  EXPECT_EQ(text.substr(text.size() - 4), "\r\033[K");  // erased by finish()
}

TEST(Progress, TerminalLoggerLinesEraseTheProgressLine) {
  std::ostringstream out;
  const tfmb::Logger log("tfmb-x", tfmb::Verbosity::normal, out, true);
  log.info("done");
  EXPECT_EQ(out.str(), "\r\033[Ktfmb-x: done\n");
}

TEST(Progress, QuietOrEmptyWritesNothing) {
  std::ostringstream out;
  const tfmb::Logger quiet("tfmb-x", tfmb::Verbosity::quiet, out);
  tfmb::Progress progress(quiet, "solve", 10, {.interval = 0.0});
  progress.update_at(5, 1.0);
  const tfmb::Logger log("tfmb-x", tfmb::Verbosity::normal, out, true);
  tfmb::Progress empty(log, "solve", 0, {.interval = 0.0});
  empty.update_at(0, 1.0);
  empty.finish();
  EXPECT_EQ(out.str(), "");
}

TEST(Progress, TimeSoFarInsteadOfATimeLeft) {
  std::ostringstream out;
  const tfmb::Logger log("tfmb-x", tfmb::Verbosity::normal, out);
  const tfmb::Progress phases(log, "flow mesh", 4,
                              {.unit = "phases", .interval = 10.0, .time_left = false});
  EXPECT_EQ(phases.text(1, 26.0), "flow mesh 1/4 phases, 26 s so far");
  EXPECT_EQ(phases.text(0, 0.0), "flow mesh 0/4 phases, 0 s so far");
}

// A long call without a count of its own: the helper thread writes lines while it runs, naming
// it and the time spent in it; afterwards the line is as before; what the call throws comes out.
TEST(Progress, UpdateWhileKeepsTheLineGoing) {
  std::ostringstream out;
  const tfmb::Logger log("tfmb-x", tfmb::Verbosity::normal, out);
  tfmb::Progress progress(log, "flow mesh", 4,
                          {.unit = "phases", .interval = 0.0, .time_left = false});
  progress.update_while(1, "meshing",
                        [] { std::this_thread::sleep_for(std::chrono::milliseconds(900)); });
  const std::string text = out.str();
  // one line as it starts, then one every 0.2 s at interval 0 (at least two in 0.9 s on a busy
  // machine)
  EXPECT_GE(count(text, "tfmb-x: progress: flow mesh 1/4 phases, "), 3) << text;
  EXPECT_EQ(count(text, ", in meshing for "), count(text, "\n")) << text;
  EXPECT_EQ(progress.text(2, 1.0), "flow mesh 2/4 phases, 1 s so far");
  EXPECT_THROW(progress.update_while(2, "meshing", [] { throw std::runtime_error("gmsh"); }),
               std::runtime_error);
}
