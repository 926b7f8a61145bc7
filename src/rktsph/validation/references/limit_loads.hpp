// Closed-form limit loads, band angles and undrained strip pore pressure used by the validation
// cases (docs/theory.md §8.1, §8.4, §8.6, §8.7, §8.10).
//
// Plane-strain Von Mises with developed flow equals Tresca with c = Y/√3, so every limit load is
// written in terms of the cohesion c. Angles are in degrees.
#pragma once

namespace rktsph::references {

/// c = Y/√3: Tresca cohesion of a plane-strain Von Mises material (docs/theory.md §8.1).
double von_mises_plane_strain_cohesion(double yield_stress);

// --- Vertical cut, φ = 0 (docs/theory.md §8.6) ---------------------------------------------------

/// γH/c at failure for the critical toe circle (Taylor 1937; chart value c/(γH) = 0.261).
/// vertical_cut.py minimises over toe circles and finds 3.8313.
inline constexpr double kTaylorVerticalCutStabilityNumber = 3.83;
/// γH/c of the Culmann plane at 45°, an upper bound above the toe circle.
inline constexpr double kCulmannVerticalCutStabilityNumber = 4.0;

/// H_c = 3.83 c/γ.
double taylor_critical_height(double cohesion, double unit_weight);
/// H_c = 4 c/γ.
double culmann_critical_height(double cohesion, double unit_weight);

// --- Strip footing of width B flush with the crest of a vertical cut (docs/theory.md §8.7) ---

/// Weightless soil: the uniaxial column under the footing (lower bound) and the 45° wedge (upper
/// bound) meet at q = 2c.
double footing_on_cut_limit_pressure(double cohesion);
/// Upper bound of a rigid wedge sliding on a plane through the inner footing edge, inclined at
/// `wedge_angle_deg` to the horizontal: q = 2c/sin 2θ − γB tan θ/2 (the work of the wedge's weight
/// subtracted).
double footing_on_cut_wedge_pressure(double cohesion, double unit_weight, double footing_width,
                                     double wedge_angle_deg);
/// The 45° wedge with self weight: q = 2c − γB/2 (eq. 8.3 at θ = 45°).
double footing_on_cut_45_degree_wedge(double cohesion, double unit_weight, double footing_width);

struct WedgeBound {
  double pressure = 0.0;   ///< least upper bound [Pa]
  double angle_deg = 0.0;  ///< angle of the sliding plane to the horizontal
};
/// The wedge bound minimised over the angles whose plane exits the face above the toe, tan θ ≤ H/B
/// (docs/theory.md eq. 8.3: 93.8 kPa at 50.9° for c = 57.7 kPa, γ = 19.62 kN/m³, B = 2 m).
WedgeBound footing_on_cut_optimal_wedge(double cohesion, double unit_weight, double footing_width,
                                        double cut_height);

// --- Bearing capacity of a strip on Tresca soil (docs/theory.md §8.7)
// ------------------------------

/// Prandtl (1920)/Hill: q_u = (2+π)c + q_s; self weight does not enter when φ = 0.
double prandtl_bearing_capacity(double cohesion, double surcharge = 0.0);
/// Kinematic upper bound of N_c for a rough footing on a thin rough-based layer (docs/theory.md
/// eq. 8.4): N_c ≤ 2 + 2√2 + B/(2H) + H/B.
double thin_layer_bearing_factor_upper_bound(double footing_width, double layer_depth);

// --- Shear-band angles, measured from the major (most compressive) principal stress axis ------

/// Associated J2 in plane strain with developed flow (s_zz = 0): 45° (docs/theory.md §8.4).
double j2_plane_strain_band_angle_deg();
/// Associated J2 at first yield of an elastic plane-strain sample (s_zz ≠ 0): Rudnicki–Rice with
/// β = μ = 0, θ = 45° + ½ asin(N(1−2ν)/√(4−3N²)), N = s_zz/√J2 of the state σ_x = 0,
/// σ_y = −S, σ_z = −νS (docs/theory.md eq. 8.2).
double j2_first_yield_band_angle_deg(double poisson_ratio);
/// Axial stress magnitude at first yield of an unconfined plane-strain sample: Y/√(1−ν+ν²).
double plane_strain_first_yield_stress(double yield_stress, double poisson_ratio);
/// Coulomb 45° − φ/2, Roscoe 45° − ψ/2, Arthur 45° − (φ+ψ)/4. Measured from the minor
/// principal stress axis instead each is 90° minus these.
double coulomb_band_angle_deg(double friction_angle_deg);
double roscoe_band_angle_deg(double dilatancy_angle_deg);
double arthur_band_angle_deg(double friction_angle_deg, double dilatancy_angle_deg);

// --- Undrained pore pressure under a flexible strip load (docs/theory.md §8.10) ---------------
// Geometry: strip of half-width b on the surface of a half-plane, uniform pressure q, x across
// the strip from its centre line, z depth below the surface (> 0). The elastic total stresses
// give σ_x + σ_z = 2qα/π (compression positive), α the angle the strip subtends at (x, z).

/// α = atan((x+b)/z) − atan((x−b)/z) [rad]; at z = 0: π under the strip, π/2 at an edge, 0 beyond.
double strip_subtended_angle(double half_width, double x, double z);
/// Undrained p0 with incompressible water and grains: q α/π (circles through the strip edges).
double strip_undrained_pore_pressure(double load, double half_width, double x, double z);
/// The same on the centre line: (2q/π) atan(b/z).
double strip_centre_line_pore_pressure(double load, double half_width, double z);
/// Factor B(1+ν_u)·2/3 that multiplies qα/π for a compressible fluid (B = Q/(Q+K),
/// K_u = K + Q, ν_u = (3K_u − 2G)/(2(3K_u + G)), 1/Q = n/K_w); 1 in the incompressible limit.
double strip_undrained_compressibility_factor(double young_modulus, double poisson_ratio,
                                              double porosity, double fluid_bulk_modulus);

// --- Factor of safety by strength reduction (docs/theory.md §10; issue 31) ----------------------

/// Verruijt's homogeneous slope (H = 4.5 m at 1:2, gamma = 16 kN/m^3, c' = 5 kPa, phi' = 20 deg),
/// Code_Aster validation test ssnp006 (V6.03.006, "Benchmark solution"): Bishop's simplified
/// method as given by Verruijt, and the Plaxis 2D finite-element strength reduction.
inline constexpr double kVerruijtSlopeBishopFactor = 1.534;
inline constexpr double kVerruijtSlopeStrengthReductionFactor = 1.54;
/// Griffiths and Lane (1999), Geotechnique 49(3), example 1 (H = 10 m, 2:1, c'/(gamma H) = 0.05,
/// phi' = 20 deg, psi = 0): finite-element strength reduction 1.4 (Bishop and Morgenstern's
/// charts 1.38).
inline constexpr double kGriffithsLaneExample1Factor = 1.4;

/// Upper bound of limit analysis for a vertical cut in c-phi soil with associated flow (Chen
/// 1975, log-spiral toe mechanism, closely approximated as): gamma H / c = 3.83 tan(45 deg +
/// phi/2).
double frictional_vertical_cut_stability_number(double friction_angle_deg);
/// The strength factor F at which a vertical cut of height H reaches that bound:
/// gamma H F / c = 3.83 tan(45 deg + phi_F/2), phi_F = atan(tan phi / F) (bisection).
double vertical_cut_upper_bound_factor(double height, double unit_weight, double cohesion,
                                       double friction_angle_deg);

}  // namespace rktsph::references
