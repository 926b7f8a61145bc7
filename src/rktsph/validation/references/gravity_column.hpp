// Laterally confined elastic column under gravity: the far field of the vertical slope
// (docs/theory.md §8.5).
//
// Column of height H, free top (z = 0), fixed base (z = H), z measured down, tension positive.
// Vertical displacement: ρ u_tt = M u_zz + ρ g f(t) − ρ μ u_t, with M the oedometric modulus,
// f(t) = min(t/t_r, 1) the gravity "time factor" (t_r = 0: sudden) and μ a mass damping [1/s].
// Modes cos(k_n z), k_n = (2n−1)π/(2H), ω_n = c k_n, c = √(M/ρ); each modal coordinate is a
// damped oscillator driven by g f(t) Γ_n, Γ_n = 2(−1)^{n+1}/(k_n H), solved in closed form.
#pragma once

namespace rktsph::references {

/// σ_v = −ρ g depth: the geostatic vertical stress (tension positive, so negative).
double geostatic_vertical_stress(double density, double gravity, double depth);
/// σ_h = K0 σ_v with K0 = ν/(1−ν): the lateral (and out-of-plane) stress of a confined column.
double geostatic_horizontal_stress(double density, double gravity, double depth,
                                   double poisson_ratio);

struct GravityColumn {
  double height = 0.0;         ///< H [m]
  double young_modulus = 0.0;  ///< E [Pa]
  double poisson_ratio = 0.0;  ///< ν
  double density = 0.0;        ///< ρ [kg/m³]
  double gravity = 9.81;       ///< g [m/s²]
  double ramp_duration = 0.0;  ///< t_r [s]; 0 applies gravity at once
  double mass_damping = 0.0;   ///< μ [1/s]
};

/// c_p = √(M/ρ).
double gravity_column_wave_speed(const GravityColumn& column);
/// T1 = 4H/c_p, the period of the first mode.
double gravity_column_fundamental_period(const GravityColumn& column);
/// Relative amplitude of the undamped oscillation left by a linear ramp of a mode of angular
/// frequency ω: A = |sin(ω t_r/2)|/(ω t_r/2) (1 for a sudden load).
double ramp_oscillation_amplitude(double angular_frequency, double ramp_duration);

/// σ_v(depth, t) [Pa] summed over `modes` modes.
/// static_correction = false: the plain modal sum (as gravity_column.py), whose static part
/// converges only like 1/modes. true: the exact quasi-static part −ρ g depth f(t) plus the modal
/// sum of the dynamic remainder only, which converges faster for ramped loads and is exact in
/// the static limit for any number of modes.
double gravity_column_vertical_stress(const GravityColumn& column, double depth, double time,
                                      int modes, bool static_correction = true);

}  // namespace rktsph::references
