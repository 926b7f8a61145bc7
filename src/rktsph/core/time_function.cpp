#include "rktsph/core/time_function.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace rktsph {

namespace {

/// Piecewise-linear interpolation through `table`, held constant beyond its first and last
/// points so that a load history simply stays at its end value.
double interpolate_table(const std::vector<std::pair<double, double>>& table, double time) {
  if (table.empty()) return 0.0;
  if (time <= table.front().first) return table.front().second;
  if (time >= table.back().first) return table.back().second;
  // First point with a time strictly greater than `time`; the one before it starts the interval.
  const auto upper = std::upper_bound(
      table.begin(), table.end(), time,
      [](double t, const std::pair<double, double>& point) { return t < point.first; });
  const auto lower = upper - 1;
  const double fraction = (time - lower->first) / (upper->first - lower->first);
  return lower->second + fraction * (upper->second - lower->second);
}

/// The integral of the piecewise-linear `table` (constant beyond its ends) from 0 to `time`.
double integrate_table(const std::vector<std::pair<double, double>>& table, double time) {
  if (table.empty()) return 0.0;
  // Integrate over [a, b] within one piece: the trapezoid of the function's values at its ends.
  auto piece = [&](double a, double b) {
    return b > a ? 0.5 * (b - a) * (interpolate_table(table, a) + interpolate_table(table, b))
                 : 0.0;
  };
  double sum = 0.0, from = 0.0;
  for (const auto& [t, v] : table) {
    (void)v;
    if (t >= time) break;
    if (t > from) {
      sum += piece(from, t);
      from = t;
    }
  }
  return sum + piece(from, time);
}

}  // namespace

double TimeFunction::integral(double t) const {
  switch (kind) {
    case Kind::Constant:
      return value * t;
    case Kind::Step:
      return value * std::max(0.0, t - start);
    case Kind::LinearRamp: {
      if (t <= start) return 0.0;
      const double ramp = std::min(t - start, duration);
      return value * ramp * ramp / (2.0 * duration) + value * std::max(0.0, t - start - duration);
    }
    case Kind::Table:
      return integrate_table(table, t);
    case Kind::Harmonic: {
      const double before = offset * std::min(t, std::max(start, 0.0));
      const double from = std::max(start, 0.0);
      if (t <= from) return offset * t;
      const double w = 2.0 * std::numbers::pi / period;
      return before + offset * (t - from) +
             amplitude / w *
                 (std::cos(w * (from - start) + phase) - std::cos(w * (t - start) + phase));
    }
  }
  return value * t;
}

double TimeFunction::operator()(double t) const {
  switch (kind) {
    case Kind::Constant:
      return value;
    case Kind::Step:
      return t < start ? 0.0 : value;
    case Kind::LinearRamp:
      if (t < start) return 0.0;
      if (t >= start + duration) return value;
      return value * (t - start) / duration;
    case Kind::Table:
      return interpolate_table(table, t);
    case Kind::Harmonic:
      if (t < start) return offset;
      return offset + amplitude * std::sin(2.0 * std::numbers::pi * (t - start) / period + phase);
  }
  return value;
}

}  // namespace rktsph
