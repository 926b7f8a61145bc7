// When a periodic output is due (fields, probe records, checkpoints): one schedule for every
// observer that writes every `interval` of simulated time.
#pragma once

#include <limits>

namespace rktsph {

/// When an output every `interval` of simulated time is due: at the first step whose time reaches
/// the next multiple k * interval (within 1e-6 of a step, so that the round-off of t += dt does
/// not push a write one step late), after which the next due time is the first multiple beyond
/// that step's time (so one output per step at most). Interval 0: never, also after a restored
/// next time.
class OutputSchedule {
 public:
  explicit OutputSchedule(double interval)
      : interval_(interval),
        next_time_(interval > 0.0 ? interval : std::numeric_limits<double>::infinity()) {}

  /// True if an output is due at `time` (and moves on to the next one).
  bool due(double time, double time_step) {
    if (interval_ <= 0.0 || !reached(time, time_step)) return false;
    while (reached(time, time_step))
      next_time_ += interval_;
    return true;
  }

  /// The next due time, saved and restored by checkpoints.
  double next_time() const { return next_time_; }
  void set_next_time(double next_time) { next_time_ = next_time; }

 private:
  bool reached(double time, double time_step) const {
    return time >= next_time_ - 1e-6 * time_step;
  }

  double interval_;
  double next_time_;
};

}  // namespace rktsph
