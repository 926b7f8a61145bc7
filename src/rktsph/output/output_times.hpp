#pragma once

namespace rktsph {

// An output time (fields, probes, checkpoints) counts as reached when the clock is within a
// millionth of a step of it: the round-off of t += dt must not push a write one step late.
inline bool output_time_reached(double time, double target, double dt) {
  return time >= target - 1e-6 * dt;
}

}  // namespace rktsph
