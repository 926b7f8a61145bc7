// Steady-state u–p saturated column under a harmonic surface load (Zienkiewicz, Chang & Bettess
// 1980; docs/theory.md §8.9).
//
// z points down from the loaded, drained surface (z = 0) to the fixed, impermeable base (z = L).
// Every field is a complex amplitude: f(z, t) = Re(F(z) e^{iωt}). The total vertical stress at
// the top is −q0 e^{iωt} (compression), so a pore pressure (compression positive) in phase with
// the load has arg P = 0. Equations (σ' tension positive, σ = D u_z − α p):
//   −ρω² U = D U″ − α P′                                  (mixture momentum)
//   (iω/Q) P + iω α U′ − k̄ P″ + k̄ ρ_f ω² U′ = 0            (storage + Darcy with fluid inertia)
// BCs: D U′ − α P = −q0 and P = 0 at z = 0; U = 0 and P′ = 0 (no flux) at z = L.
// The fluid-acceleration term k̄ρ_fω²U′ is what harmonic_column.py's u-p form keeps; it can be
// switched off. Modes e^{μz} give a quadratic in s = μ²; the two roots give four bounded
// exponentials e^{−λz}, e^{λ(z−L)} and a 4×4 complex system for their weights.
#pragma once

#include <array>
#include <complex>

namespace rktsph::references {

struct HarmonicColumn {
  double depth = 0.0;                ///< L [m]
  double constrained_modulus = 0.0;  ///< D, the drained oedometric modulus [Pa]
  double biot_modulus = 0.0;         ///< Q, finite [Pa] (1/Q = n/K_w for incompressible grains)
  double biot_coefficient = 1.0;     ///< α
  double mixture_density = 0.0;      ///< ρ [kg/m³]
  double fluid_density = 0.0;        ///< ρ_f [kg/m³]
  double permeability = 0.0;         ///< k̄ = k/(ρ_f g) [m³·s/kg]
  double angular_frequency = 0.0;    ///< ω [rad/s]
  double load_amplitude = 1.0;       ///< q0 [Pa]
  bool fluid_acceleration_in_darcy = true;

  /// The dimensionless column (docs/theory.md §8.9): L = ρ = V_c = α = 1, D/Q given,
  /// Π1 = k̄ρV_c²/(ωL²), Π2 = ω²L²/V_c², β = ρ_f/ρ.
  static HarmonicColumn dimensionless(double permeability_group, double frequency_group,
                                      double fluid_density_ratio = 1.0 / 3.0,
                                      double modulus_ratio = 0.1);
  /// Physical parameters, α = 1 and incompressible grains; k is the hydraulic conductivity [m/s].
  static HarmonicColumn physical(double depth, double young_modulus, double poisson_ratio,
                                 double porosity, double solid_density, double fluid_density,
                                 double fluid_bulk_modulus, double hydraulic_conductivity,
                                 double period, double gravity = 9.81, double load = 1.0);
};

/// V_c = √((D + α²Q)/ρ), the undrained compression wave speed.
double undrained_wave_speed(const HarmonicColumn& column);
/// p_u = αQ q0/(D + α²Q), the static undrained pore pressure.
double undrained_static_pressure(const HarmonicColumn& column);
/// Π1 = k̄ρV_c²/(ωL²) (permeability group).
double permeability_group(const HarmonicColumn& column);
/// Π2 = ω²L²/V_c² (frequency group; the undrained column resonates at π²/4).
double frequency_group(const HarmonicColumn& column);

class HarmonicColumnSolution {
 public:
  /// Solves the boundary-value problem once. Throws std::invalid_argument for non-positive or
  /// infinite parameters and RunError if the 4×4 system is singular.
  explicit HarmonicColumnSolution(const HarmonicColumn& column);

  std::complex<double> pressure(double z) const;      ///< P(z) [Pa]
  std::complex<double> displacement(double z) const;  ///< U(z) [m]
  /// |P(z)|/q0: the steady-state pore-pressure envelope.
  double pressure_ratio(double z) const;
  /// arg P(z) in (−π, π] against the compressive load q0 e^{iωt}.
  double pressure_phase(double z) const;

 private:
  struct Mode {
    std::complex<double> exponent;      ///< μ
    double origin = 0.0;                ///< e^{μ(z − origin)} stays ≤ 1 on [0, L]
    std::complex<double> displacement;  ///< U weight of the mode
    std::complex<double> pressure;      ///< P weight of the mode
  };
  HarmonicColumn column_;
  std::array<Mode, 4> modes_;
};

/// k̄ → 0 limit: P = p_u cos(ω(L−z)/V_c)/cos(ωL/V_c). Valid outside the drained boundary layer.
std::complex<double> undrained_harmonic_pressure(const HarmonicColumn& column, double z);
/// ω → 0 (no inertia) limit: P = p_u [1 − cosh κ(L−z)/cosh κL], κ² = iω(α²/D + 1/Q)/k̄.
std::complex<double> quasi_static_harmonic_pressure(const HarmonicColumn& column, double z);

}  // namespace rktsph::references
