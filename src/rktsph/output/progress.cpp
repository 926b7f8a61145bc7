#include "rktsph/output/progress.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include <fmt/format.h>

namespace rktsph {

namespace {

constexpr int kBarWidth = 24;

double seconds_between(Progress::Clock::time_point from, Progress::Clock::time_point to) {
  return std::chrono::duration<double>(to - from).count();
}

std::string format_duration(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0.0) return "--:--:--";
  const long total = std::lround(seconds);
  return fmt::format("{}:{:02}:{:02}", total / 3600, (total / 60) % 60, total % 60);
}

}  // namespace

Progress::Progress(double end_time, std::ostream& out, bool is_terminal, bool quiet)
    : Progress(end_time, out, is_terminal, quiet, Intervals{}, [] { return Clock::now(); }) {}

Progress::Progress(double end_time, std::ostream& out, bool is_terminal, bool quiet,
                   Intervals intervals, ClockFunction clock)
    : end_time_(end_time),
      out_(out),
      is_terminal_(is_terminal),
      quiet_(quiet),
      intervals_(intervals),
      clock_(std::move(clock)) {
  start_wall_time_ = clock_();
  last_report_wall_time_ = start_wall_time_;
}

void Progress::update(double time, long step) {
  if (quiet_ || finished_) return;
  const Clock::time_point now = clock_();
  if (!has_update_) {
    // Rates are measured from the first reported step so that set-up time before the loop (and
    // the start time of a restarted run) does not distort steps/s and the ETA.
    has_update_ = true;
    start_time_ = time;
    start_step_ = step;
    start_wall_time_ = now;
  }
  time_ = time;
  step_ = step;
  const auto interval = is_terminal_ ? intervals_.terminal : intervals_.plain;
  if (now - last_report_wall_time_ >= interval) report(now, false);
}

void Progress::finish() {
  if (quiet_ || finished_) return;
  finished_ = true;
  report(clock_(), true);
}

void Progress::report(Clock::time_point now, bool final_report) {
  last_report_wall_time_ = now;
  if (is_terminal_) {
    if (has_update_) {
      std::string line = status_line(now);
      // A shorter line must blank out the tail of the longer one it overwrites; the padded
      // length is what the terminal now shows, so it is what the next redraw has to cover.
      if (line.size() < previous_line_length_) line.resize(previous_line_length_, ' ');
      previous_line_length_ = line.size();
      out_ << '\r' << line;
      if (final_report) out_ << '\n';
    }
    if (final_report) out_ << completion_line(now) << '\n';
  } else {
    out_ << (final_report ? completion_line(now) : status_line(now)) << '\n';
  }
  out_.flush();
}

std::string Progress::status_line(Clock::time_point now) const {
  const double fraction = end_time_ > 0.0 ? std::clamp(time_ / end_time_, 0.0, 1.0) : 1.0;
  const double elapsed = seconds_between(start_wall_time_, now);
  const double steps_per_second =
      elapsed > 0.0 ? static_cast<double>(step_ - start_step_) / elapsed : 0.0;
  const double simulated_per_wall_second = elapsed > 0.0 ? (time_ - start_time_) / elapsed : 0.0;
  const double remaining = simulated_per_wall_second > 0.0
                               ? std::max(end_time_ - time_, 0.0) / simulated_per_wall_second
                               : std::nan("");
  std::string line;
  if (is_terminal_) {
    const int filled = static_cast<int>(fraction * kBarWidth);
    line = fmt::format("[{}{}] ", std::string(static_cast<std::size_t>(filled), '#'),
                       std::string(static_cast<std::size_t>(kBarWidth - filled), '.'));
  } else {
    line = "progress ";
  }
  line += fmt::format("{:5.1f}%  t = {:.6g} s of {:.6g} s  step {}  {:.4g} steps/s  ETA {}",
                      100.0 * fraction, time_, end_time_, step_, steps_per_second,
                      format_duration(remaining));
  return line;
}

std::string Progress::completion_line(Clock::time_point now) const {
  if (!has_update_) return "done: no steps were taken";
  const double elapsed = seconds_between(start_wall_time_, now);
  const long steps = step_ - start_step_;
  const double steps_per_second = elapsed > 0.0 ? static_cast<double>(steps) / elapsed : 0.0;
  return fmt::format("done: t = {:.6g} s, step {}, wall time {} ({:.4g} steps/s)", time_, step_,
                     format_duration(elapsed), steps_per_second);
}

}  // namespace rktsph
