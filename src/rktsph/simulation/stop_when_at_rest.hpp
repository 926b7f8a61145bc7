// The observer behind `time.stop_when_at_rest` (docs/input-reference.md): ends a run once the body
// has come to rest, so that a damped static case does not run out its whole time span. "At rest"
// is the largest speed over the SPH nodes staying at or below `fraction` times its peak so far for
// as many consecutive steps as a P-wave needs to cross the body (its largest extent) once: a wave
// still travelling through the body cannot pass for rest (docs/theory.md §2.6).
#pragma once

#include <string>

#include "rktsph/simulation/simulation.hpp"

namespace rktsph {

class StopWhenAtRest final : public Observer {
 public:
  /// `fraction` in (0, 1).
  explicit StopWhenAtRest(double fraction);

  void on_start(const Simulation& simulation) override;
  void on_resume(const Simulation& simulation) override { on_start(simulation); }
  void after_step(const Simulation& simulation) override;
  std::string stop_reason() const override { return reason_; }

  /// The steps the speed must stay low: one P-wave transit of the body, at least 1.
  long window_steps() const { return window_steps_; }

 private:
  double fraction_;
  long window_steps_ = 1;
  double peak_speed_ = 0.0;
  long quiet_steps_ = 0;
  std::string reason_;
};

}  // namespace rktsph
