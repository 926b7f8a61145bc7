// Scalar functions of time used by imposed velocities, tractions, gravity factors and loads.
#pragma once

#include <utility>
#include <vector>

namespace rktsph {

struct TimeFunction {
  enum class Kind {
    Constant,    ///< value
    Step,        ///< 0 before `start`, `value` from `start` on
    LinearRamp,  ///< 0 before `start`, linear to `value` over `duration`, then `value`
    Table,       ///< piecewise linear through `table` (t, value), constant beyond its ends
    Harmonic,    ///< offset + amplitude * sin(2*pi*(t - start)/period + phase) for t >= start,
                 ///< `offset` before
  };
  Kind kind = Kind::Constant;
  double value = 0.0;
  double start = 0.0;                            // [s]
  double duration = 0.0;                         // [s], LinearRamp only (> 0)
  std::vector<std::pair<double, double>> table;  // strictly increasing times
  double amplitude = 0.0;
  double period = 1.0;  // [s]
  double phase = 0.0;   // [rad]
  double offset = 0.0;

  static TimeFunction constant(double v) {
    TimeFunction f;
    f.value = v;
    return f;
  }

  double operator()(double t) const;
  /// The integral of the function from 0 to t >= 0 (exact for every kind).
  double integral(double t) const;
};

}  // namespace rktsph
