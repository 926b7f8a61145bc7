// Terzaghi 1D consolidation with Biot-consistent coefficients (docs/theory.md §8.8,
// eq. 8.5).
//
// Column of drainage length H_d, drained (p = 0) at z = 0, impermeable at z = H_d, total load q0
// applied suddenly at t = 0, no gravity (excess quantities), Biot α = 1, incompressible grains.
// Pore pressure is compression positive. With a fluid of finite bulk modulus the 1D coupled
// problem still gives the Terzaghi series; only the initial pressure p0 and c_v change.
#pragma once

#include <limits>

namespace rktsph::references {

/// Biot modulus for incompressible grains, Q = K_w/n (1/Q = n/K_w); +∞ for incompressible water.
double biot_modulus(double porosity, double fluid_bulk_modulus);

/// Undrained loading efficiency p0/q0 = Q/(M + Q) of a confined column (the 1D Skempton-type B):
/// the share of a sudden vertical load first carried by the water. 1 when Q = ∞.
double loading_efficiency(double oedometric_modulus,
                          double biot_modulus = std::numeric_limits<double>::infinity());

/// c_v = (k/γ_w) / (1/M + 1/Q) [m²/s], k the hydraulic conductivity [m/s]. With Q = ∞ this is the
/// classical k·E_oed/γ_w.
double consolidation_coefficient(double hydraulic_conductivity, double fluid_unit_weight,
                                 double oedometric_modulus,
                                 double biot_modulus = std::numeric_limits<double>::infinity());

/// T_v = c_v t / H_d².
double time_factor(double consolidation_coefficient, double time, double drainage_length);

/// p/p0 at depth ratio ζ = z/H_d ∈ [0, 1] (z from the drained face) and time factor T_v, to about
/// 1e-13 absolute for every T_v > 0. 1 inside the column at T_v ≤ 0 (the undrained state).
double terzaghi_pressure_ratio(double depth_ratio, double time_factor);

/// p(z, t) [Pa] for a column with initial excess pressure p0.
double terzaghi_pore_pressure(double depth, double time, double drainage_length,
                              double consolidation_coefficient, double initial_pressure);

/// Degree of consolidation U(T_v) = 1 − (mean p)/p0, to about 1e-13 absolute.
double degree_of_consolidation(double time_factor);

/// Top settlement s = s_u + (s_∞ − s_u) U, s_∞ = q0 H/M, s_u = q0 H/(M + Q) [m], positive down.
double terzaghi_settlement(double load, double drainage_length, double oedometric_modulus,
                           double biot_modulus, double time_factor);

}  // namespace rktsph::references
