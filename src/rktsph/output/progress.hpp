// Progress of the time loop on the console.
//
// On a terminal a single status line is redrawn in place ('\r'); into a file or pipe (CI logs,
// batch jobs) a plain line is written every ~10 s of wall time, since redraws would only fill
// the log with carriage returns. Whether the stream is a terminal is decided by the caller.
#pragma once

#include <chrono>
#include <cstddef>
#include <functional>
#include <ostream>
#include <string>

namespace rktsph {

class Progress {
 public:
  using Clock = std::chrono::steady_clock;
  /// Returns the current time; injectable so tests can drive the rate limiting.
  using ClockFunction = std::function<Clock::time_point()>;

  struct Intervals {
    /// Minimum wall time between redraws of the terminal line (keeps the cost of update()
    /// negligible and the line readable).
    std::chrono::duration<double> terminal{0.25};
    /// Wall time between plain lines when not on a terminal.
    std::chrono::duration<double> plain{10.0};
  };

  /// `end_time` is the simulated time at which the run ends [s].
  Progress(double end_time, std::ostream& out, bool is_terminal, bool quiet);
  Progress(double end_time, std::ostream& out, bool is_terminal, bool quiet, Intervals intervals,
           ClockFunction clock);

  /// Called after every step with the simulated time reached and the step count. It only reads
  /// the clock unless a report is due.
  void update(double time, long step);

  /// Writes the final report (and, on a terminal, ends the status line). Later calls do nothing.
  /// Not called by the destructor: a run that stops on an error should not report completion.
  void finish();

 private:
  void report(Clock::time_point now, bool final_report);
  std::string status_line(Clock::time_point now) const;
  std::string completion_line(Clock::time_point now) const;

  double end_time_;
  std::ostream& out_;
  bool is_terminal_;
  bool quiet_;
  Intervals intervals_;
  ClockFunction clock_;

  Clock::time_point start_wall_time_;
  Clock::time_point last_report_wall_time_;
  bool has_update_ = false;
  bool finished_ = false;
  double start_time_ = 0.0;
  long start_step_ = 0;
  double time_ = 0.0;
  long step_ = 0;
  std::size_t previous_line_length_ = 0;
};

}  // namespace rktsph
