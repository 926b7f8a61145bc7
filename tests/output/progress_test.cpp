#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <sstream>
#include <string>
#include <vector>

#include "rktsph/output/progress.hpp"

namespace rktsph::progress_test {
namespace {

using std::chrono::milliseconds;
using std::chrono::seconds;

// A clock the test moves by hand, so the rate limiting is deterministic.
struct FakeClock {
  Progress::Clock::time_point now{};
  Progress::ClockFunction function() {
    return [this] { return now; };
  }
};

std::vector<std::string> split_lines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream stream(text);
  std::string line;
  while (std::getline(stream, line))
    lines.push_back(line);
  return lines;
}

TEST(Progress, PlainModeWritesALineEveryIntervalWithTheSimulatedTime) {
  FakeClock clock;
  std::ostringstream out;
  Progress progress(2.0, out, /*is_terminal=*/false, /*quiet=*/false, Progress::Intervals{},
                    clock.function());
  // 100 steps of 0.01 s simulated time, 1 s of wall time each: a line is due at 10 s, 20 s, ...
  for (long step = 1; step <= 100; ++step) {
    clock.now += seconds(1);
    progress.update(0.01 * static_cast<double>(step), step);
  }
  progress.finish();
  const std::vector<std::string> lines = split_lines(out.str());
  // First update at wall 1 s sets the reference; lines at 10, 20, ..., 100 s; then the final.
  ASSERT_EQ(lines.size(), 11u) << out.str();
  EXPECT_EQ(out.str().find('\r'), std::string::npos);
  // At the first line (step 10, wall 10 s): t = 0.1 s of 2 s, 5 %, 9 steps in 9 s.
  EXPECT_NE(lines[0].find("t = 0.1 s"), std::string::npos) << lines[0];
  EXPECT_NE(lines[0].find("5.0%"), std::string::npos) << lines[0];
  EXPECT_NE(lines[0].find("step 10"), std::string::npos) << lines[0];
  EXPECT_NE(lines[0].find("1 steps/s"), std::string::npos) << lines[0];
  // Remaining 1.9 s of simulated time at 0.01 s per wall second: 190 s = 0:03:10.
  EXPECT_NE(lines[0].find("ETA 0:03:10"), std::string::npos) << lines[0];
  EXPECT_NE(lines[9].find("t = 1 s"), std::string::npos) << lines[9];
  EXPECT_NE(lines[10].find("done"), std::string::npos) << lines[10];
  EXPECT_NE(lines[10].find("t = 1 s"), std::string::npos) << lines[10];
}

TEST(Progress, UpdatesBetweenIntervalsWriteNothing) {
  FakeClock clock;
  std::ostringstream out;
  Progress progress(1.0, out, false, false, Progress::Intervals{}, clock.function());
  for (long step = 1; step <= 1000; ++step) {
    clock.now += milliseconds(9);  // 9 s in total: below the 10 s interval
    progress.update(1e-3 * static_cast<double>(step), step);
  }
  EXPECT_EQ(out.str(), "");
}

TEST(Progress, QuietWritesNothingInEitherMode) {
  for (const bool is_terminal : {false, true}) {
    FakeClock clock;
    std::ostringstream out;
    Progress progress(1.0, out, is_terminal, /*quiet=*/true, Progress::Intervals{},
                      clock.function());
    for (long step = 1; step <= 50; ++step) {
      clock.now += seconds(5);
      progress.update(0.02 * static_cast<double>(step), step);
    }
    progress.finish();
    EXPECT_EQ(out.str(), "") << "is_terminal = " << is_terminal;
  }
}

TEST(Progress, TerminalModeRedrawsOneLineAndEndsIt) {
  FakeClock clock;
  std::ostringstream out;
  Progress progress(1.0, out, /*is_terminal=*/true, false, Progress::Intervals{}, clock.function());
  for (long step = 1; step <= 4; ++step) {
    clock.now += seconds(1);
    progress.update(0.25 * static_cast<double>(step), step);
  }
  progress.finish();
  progress.finish();  // a second finish must not write again
  const std::string text = out.str();
  // Every update comes 1 s after the previous report, more than the 0.25 s redraw interval, so
  // steps 1 to 4 each redraw, and finish() draws once more.
  EXPECT_EQ(std::count(text.begin(), text.end(), '\r'), 5) << text;
  // A redraw shorter than the line it overwrites must blank the leftover characters.
  std::size_t previous_length = 0;
  std::size_t position = text.find('\r');
  while (position != std::string::npos) {
    const std::size_t next = text.find_first_of("\r\n", position + 1);
    const std::size_t length = next - position - 1;
    EXPECT_GE(length, previous_length) << text;
    previous_length = length;
    position = text.find('\r', position + 1);
  }
  const std::vector<std::string> lines = split_lines(text);
  ASSERT_EQ(lines.size(), 2u) << text;
  EXPECT_NE(lines[0].rfind("100.0%"), std::string::npos) << lines[0];
  EXPECT_NE(lines[0].rfind("[########################]"), std::string::npos) << lines[0];
  EXPECT_NE(lines[1].find("done: t = 1 s"), std::string::npos) << lines[1];
}

}  // namespace
}  // namespace rktsph::progress_test
