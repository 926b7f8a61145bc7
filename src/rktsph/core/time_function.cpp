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

}  // namespace

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
