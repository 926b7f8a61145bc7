// The phreatic surface of the saturated model (docs/theory.md §6.8): its height y_w(x), the
// hydrostatic pore pressure below it and the weight of the soil on either side of it.
//   p_h = rho_w g (y_w(x) - y) below the table, 0 above it                       (6.6)
// The vertical axis is the last one (y in 2D, x in 1D, where the table is a level).
#pragma once

#include <array>
#include <optional>
#include <vector>

namespace rktsph {

class WaterTable {
 public:
  /// A horizontal table at y_w = `height` [m].
  static WaterTable level(double height, std::optional<double> density_above = {});
  /// The polyline of vertices (x, y_w) [m], two or more with x increasing (the case reader checks).
  static WaterTable polyline(std::vector<std::array<double, 2>> vertices,
                             std::optional<double> density_above = {});

  /// y_w at horizontal coordinate x: the level, or the polyline (constant beyond its ends).
  double height(double x) const;
  /// dy_w/dx at x (0 for a level and beyond the ends; the right-hand slope at a vertex).
  double slope(double x) const;
  /// (y_w(x) - y)^+: the depth of the point (x, y) below the table [m].
  double depth_below(double x, double y) const;
  /// The mass density that soil of mixture density `density` weighs above the table [kg/m^3]:
  /// the case's `density_above`, or rho - n rho_w (its pores drained).
  double density_above(double density, double porosity, double fluid_density) const;

 private:
  WaterTable(std::vector<std::array<double, 2>> vertices, std::optional<double> density_above)
      : vertices_(std::move(vertices)), density_above_(density_above) {}

  std::vector<std::array<double, 2>> vertices_;  // one vertex (x unused) for a level
  std::optional<double> density_above_;
};

/// The mass density that soil of mixture density `density` weighs above a water table [kg/m^3]
/// (docs/theory.md §6.8): `given` (the case's `density_above`) if set, else rho - n rho_w, its
/// pores drained.
double density_above_table(std::optional<double> given, double density, double porosity,
                           double fluid_density);

}  // namespace rktsph
