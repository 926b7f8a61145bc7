#include "rktsph/physics/water_table.hpp"

#include <algorithm>
#include <utility>

namespace rktsph {

WaterTable WaterTable::level(double height, std::optional<double> density_above) {
  return WaterTable({{0.0, height}}, density_above);
}

WaterTable WaterTable::polyline(std::vector<std::array<double, 2>> vertices,
                                std::optional<double> density_above) {
  return WaterTable(std::move(vertices), density_above);
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

double WaterTable::density_above(double density, double porosity, double fluid_density) const {
  return density_above_table(density_above_, density, porosity, fluid_density);
}

double density_above_table(std::optional<double> given, double density, double porosity,
                           double fluid_density) {
  return given ? *given : density - porosity * fluid_density;
}

}  // namespace rktsph
