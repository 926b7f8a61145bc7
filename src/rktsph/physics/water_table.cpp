#include "rktsph/physics/water_table.hpp"

#include <algorithm>

namespace rktsph {

WaterTable::WaterTable(const WaterTableSpec& spec) {
  if (spec.level)
    vertices_ = {{0.0, *spec.level}};
  else
    vertices_ = spec.polyline;  // the reader checked: 2 or more vertices, x increasing
}

double WaterTable::height(double x) const {
  if (vertices_.size() == 1 || x <= vertices_.front()[0]) return vertices_.front()[1];
  if (x >= vertices_.back()[0]) return vertices_.back()[1];
  const auto after = std::upper_bound(
      vertices_.begin(), vertices_.end(), x,
      [](double value, const std::array<double, 2>& vertex) { return value < vertex[0]; });
  const auto& b = *after;
  const auto& a = *(after - 1);
  return a[1] + (b[1] - a[1]) * (x - a[0]) / (b[0] - a[0]);
}

double WaterTable::slope(double x) const {
  if (vertices_.size() == 1 || x < vertices_.front()[0] || x >= vertices_.back()[0]) return 0.0;
  const auto after = std::upper_bound(
      vertices_.begin(), vertices_.end(), x,
      [](double value, const std::array<double, 2>& vertex) { return value < vertex[0]; });
  const auto& b = *after;
  const auto& a = *(after - 1);
  return (b[1] - a[1]) / (b[0] - a[0]);
}

double WaterTable::depth_below(double x, double y) const {
  return std::max(0.0, height(x) - y);
}

double density_above_table(const PoreFluidSpec& fluid, double density) {
  if (fluid.water_table && fluid.water_table->density_above)
    return *fluid.water_table->density_above;
  return density - fluid.porosity * fluid.density;
}

}  // namespace rktsph
