// Closed forms of Modified Cam-Clay with the pressure-dependent elasticity K = (1 + e0) p / kappa
// (docs/theory.md §1.5, eqs. 1.10a–1.10b; Wood, "Soil behaviour and critical state soil mechanics",
// 1990, ch. 6–7; Roscoe & Burland 1968). Mean effective pressure p is compression positive,
// volumetric strain tension positive (as everywhere in the code); the void ratio is held at e0,
// as the material holds it.
#pragma once

namespace rktsph::references {

/// M in triaxial compression from the friction angle phi [deg]: 6 sin(phi) / (3 - sin(phi)).
double critical_state_ratio_compression(double friction_angle_deg);

/// p on the isotropic unloading (swelling) line after a volumetric strain change
/// `volumetric_strain` (tension positive) from p0: ln(p / p0) = -(1 + e0) eps_v / kappa.
double isotropic_unloading_pressure(double initial_pressure, double volumetric_strain,
                                    double initial_void_ratio, double swelling_index);

/// Undrained (isochoric) failure pressure at the critical state from an isotropic p0 with
/// overconsolidation ratio OCR = pc0 / p0: p_f = p0 (OCR / 2)^Lambda, Lambda = (lambda - kappa) /
/// lambda. It needs K proportional to p (the elastic and plastic volumetric strains cancel:
/// kappa ln(p_f / p0) + (lambda - kappa) ln(pc_f / pc0) = 0 with pc_f = 2 p_f) and holds for any
/// Lode angle, so in plane strain as in triaxial compression.
double undrained_failure_pressure(double initial_pressure, double overconsolidation_ratio,
                                  double compression_index, double swelling_index);

/// Drained triaxial compression at constant cell pressure p0 (dq/dp = 3) ends on the critical
/// state line q = M p at p_f = 3 p0 / (3 - M) (M < 3), for a sample on the wet side of
/// critical (OCR < 2), which hardens towards it.
double drained_triaxial_failure_pressure(double initial_pressure, double critical_state_ratio);

}  // namespace rktsph::references
