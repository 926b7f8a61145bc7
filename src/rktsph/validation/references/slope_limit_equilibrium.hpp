// Limit-equilibrium factor of safety of a 2D slope: Bishop's simplified method of slices on
// circular slip surfaces, with pore pressures from a phreatic line, and a search for the least
// factor over circles. It is the independent reference against which the factor of safety found
// by strength reduction (docs/theory.md §10) is checked, dry and with a water table.
//
// Sources:
//  - A. W. Bishop (1955), "The use of the slip circle in the stability analysis of slopes",
//    Géotechnique 5(1), 7-17: moment equilibrium about the centre, interslice shear neglected.
//  - J. M. Duncan and S. G. Wright (2005), "Soil Strength and Slope Stability", Wiley, ch. 6:
//    the slice equations in effective stress and the numerical cautions (small m_α, negative
//    effective normal force).
//  - A. Verruijt, "Soil Mechanics" (Delft University of Technology), slope stability chapter, and
//    Code_Aster validation test ssnp006 (V6.03.006): the slope used as a benchmark here.
//  - D. V. Griffiths and P. A. Lane (1999), "Slope stability analysis by finite elements",
//    Géotechnique 49(3), 387-403, with A. W. Bishop and N. Morgenstern (1960), "Stability
//    coefficients for earth slopes", Géotechnique 10(4), 129-150: the second benchmark.
//
// Conventions: SI units (m, Pa, N/m^3), angles in degrees, x horizontal, y vertical upwards. Plane
// strain, unit thickness. The slope may face +x or -x; the sense of sliding is taken from the sign
// of the moment of the slip mass's weight about the centre.
#pragma once

#include <array>
#include <vector>

namespace rktsph::references {

/// A homogeneous slope on a rigid base, optionally with a phreatic line.
struct SlopeProfile {
  /// Ground surface, x strictly increasing, at least two vertices; level beyond its ends.
  std::vector<std::array<double, 2>> ground;
  /// Rigid base y = base: no slip surface passes below it (touching it is allowed). The ground
  /// must not lie below it.
  double base = 0.0;
  /// γ above the water table [N/m^3] (of the whole soil when there is no table).
  double unit_weight_above = 0.0;
  /// γ_sat below the water table [N/m^3]; only used with a table.
  double unit_weight_below = 0.0;
  double cohesion = 0.0;        ///< c' [Pa]
  double friction_angle = 0.0;  ///< φ' [deg], 0 <= φ' < 90
  /// Phreatic line, x strictly increasing, level beyond its ends; a single vertex is a level
  /// table; empty means dry. It may not stand above the ground anywhere (no ponded water).
  std::vector<std::array<double, 2>> water_table;
  double water_unit_weight = 9810.0;  ///< γ_w [N/m^3]
};

/// A slip circle with its factor of safety; entry_x < exit_x are where the arc meets the ground.
struct SlipCircle {
  double centre_x = 0.0;
  double centre_y = 0.0;
  double radius = 0.0;
  double entry_x = 0.0;
  double exit_x = 0.0;
  double factor = 0.0;
};

/// Slices used by default: F is then converged to about 1e-5 for the benchmark slopes.
inline constexpr int kBishopDefaultSlices = 200;
/// The critical-circle search ignores slip masses whose greatest vertical thickness is below this
/// fraction of the slope height (for c' = 0 the infimum is otherwise a vanishing surface slide).
inline constexpr double kMinimumSlipDepthFraction = 0.02;

/// Bishop's simplified F of one circle. NaN when the lower arc does not cut the ground in one
/// contiguous arc, passes below the base, has no driving moment, or has m_α < 0.2 in a slice.
/// Throws std::invalid_argument for an invalid profile, radius <= 0 or slices < 1.
double bishop_factor(const SlopeProfile& profile, double centre_x, double centre_y, double radius,
                     int slices = kBishopDefaultSlices);

/// The circle of least Bishop F: a grid of centres and depths, then Nelder-Mead refinements (see
/// the .cpp). Throws std::invalid_argument for an invalid profile or level ground.
SlipCircle critical_bishop_circle(const SlopeProfile& profile);

}  // namespace rktsph::references
