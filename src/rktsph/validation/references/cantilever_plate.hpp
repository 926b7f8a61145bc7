// Thin-plate (Euler-Bernoulli) reference of the oscillating cantilever plate of Gray, Monaghan &
// Swift (2001) (docs/theory.md §9.11).
//
// A plate of free length L and thickness H, clamped at its root, swings in its first bending mode.
// Its clamped-free modes have k_n L the roots of 1 + cos(kL) cosh(kL) = 0 (the first is 1.875104);
// in plane strain the bending stiffness per unit width is E' H³/12 with E' = E/(1 − ν²), so
//
//   ω² = E' H² k⁴ / (12 ρ),   T = 2π/ω.
//
// The benchmark sets the tip velocity as V_f c0 with c0 = √(K/ρ), K = E/(3(1 − 2ν)).
#pragma once

namespace rktsph::references {

struct CantileverPlate {
  double length = 0.0;         ///< free length L [m]
  double thickness = 0.0;      ///< H [m]
  double young_modulus = 0.0;  ///< E [Pa]
  double poisson_ratio = 0.0;  ///< ν
  double density = 0.0;        ///< ρ [kg/m³]
};

/// k_n L: the n-th root (n ≥ 1) of 1 + cos x cosh x = 0, by bisection to round-off.
/// Throws std::invalid_argument for n < 1.
double cantilever_mode_root(int n);

/// ω of the first bending mode in plane strain [rad/s]; throws std::invalid_argument for a
/// non-positive length, thickness, modulus or density, or ν outside (−1, 0.5).
double cantilever_plate_angular_frequency(const CantileverPlate& plate);
/// T = 2π/ω [s].
double cantilever_plate_period(const CantileverPlate& plate);
/// c0 = √(K/ρ), the velocity scale of the benchmark's tip velocity V_f c0 [m/s].
double cantilever_plate_velocity_scale(const CantileverPlate& plate);

}  // namespace rktsph::references
