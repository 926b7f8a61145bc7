#include "rktsph/simulation/stop_when_at_rest.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "rktsph/simulation/quantities.hpp"

namespace rktsph {

namespace {

// The largest extent of the reference configuration along any axis [m].
double body_extent(const NodeSets& nodes) {
  double extent = 0.0;
  for (int a = 0; a < nodes.dimension; ++a) {
    const auto& x = nodes.sph_nodes.position[static_cast<std::size_t>(a)];
    if (x.empty()) continue;
    const auto [low, high] = std::minmax_element(x.begin(), x.end());
    extent = std::max(extent, *high - *low);
  }
  return extent;
}

}  // namespace

StopWhenAtRest::StopWhenAtRest(double fraction) : fraction_(fraction) {}

void StopWhenAtRest::on_start(const Simulation& simulation) {
  const double transit = body_extent(simulation.nodes()) / simulation.model().max_wave_speed();
  window_steps_ = std::max(1L, static_cast<long>(std::ceil(transit / simulation.time_step())));
  peak_speed_ = largest_speed(simulation);
  quiet_steps_ = 0;
  reason_.clear();
}

void StopWhenAtRest::after_step(const Simulation& simulation) {
  const double speed = largest_speed(simulation);
  peak_speed_ = std::max(peak_speed_, speed);
  if (peak_speed_ > 0.0 && speed <= fraction_ * peak_speed_)
    ++quiet_steps_;
  else
    quiet_steps_ = 0;
  if (quiet_steps_ >= window_steps_)
    reason_ = fmt::format(
        "at rest (time.stop_when_at_rest = {}): the largest speed stayed at or below {:.3g} m/s, "
        "{} of its peak {:.4g} m/s, for {} steps (one P-wave transit of the body)",
        fraction_, fraction_ * peak_speed_, fraction_, peak_speed_, window_steps_);
}

}  // namespace rktsph
