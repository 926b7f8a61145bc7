// The phreatic surface of the saturated model (docs/theory.md §6.8): its height y_w(x), the
// hydrostatic pore pressure below it and the weight of the soil on either side of it.
//   p_h = rho_w g (y_w(x) - y) below the table, 0 above it                       (6.6)
// The vertical axis is the last one (y in 2D, x in 1D, where the table is a level).
#pragma once

#include <array>
#include <vector>

#include "rktsph/case/case_description.hpp"

namespace rktsph {

class WaterTable {
 public:
  explicit WaterTable(const WaterTableSpec& spec);

  /// y_w at horizontal coordinate x: the level, or the polyline (constant beyond its ends).
  double height(double x) const;
  /// dy_w/dx at x (0 for a level and beyond the ends; the right-hand slope at a vertex).
  double slope(double x) const;
  /// (y_w(x) - y)^+: the depth of the point (x, y) below the table [m].
  double depth_below(double x, double y) const;

 private:
  std::vector<std::array<double, 2>> vertices_;  // one vertex (x unused) for a level
};

/// The mass density the soil of mixture density `density` weighs above the table: the case's
/// `density_above`, or rho - n rho_w (its pores drained).
double density_above_table(const PoreFluidSpec& fluid, double density);

}  // namespace rktsph
