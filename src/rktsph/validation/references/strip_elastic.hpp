// Stresses under a uniform flexible strip load on a dry linear-elastic half-plane (plane strain):
// the Flamant strip solution (Poulos & Davis 1974, section 3.4; Timoshenko & Goodier,
// section 36).
//
// A pressure q (compression) acts on |x| <= b of the surface z = 0, z measured down (> 0). With
//   α = atan((x+b)/z) − atan((x−b)/z)   (the angle the strip subtends at the point)
//   δ = atan((x−b)/z)
// the stresses, COMPRESSION POSITIVE (the code's stress is tension positive: negate them), do not
// depend on E or ν:
//   σ_z = (q/π)[α + sin α cos(α + 2δ)],  σ_x = (q/π)[α − sin α cos(α + 2δ)],
//   τ_xz = (q/π) sin α sin(α + 2δ).
// On the centre line x = 0: α = 2 atan(b/z), σ_z = (q/π)(α + sin α), σ_x = (q/π)(α − sin α).
#pragma once

#include <vector>

namespace rktsph::references {

struct StripStress {
  double sigma_x = 0.0;  ///< horizontal normal stress [Pa], compression positive
  double sigma_z = 0.0;  ///< vertical normal stress [Pa], compression positive
  double tau_xz = 0.0;   ///< shear stress [Pa], sign as in the formula above
};

/// The Flamant strip stresses at (x, z), z > 0 (std::invalid_argument otherwise).
StripStress flamant_strip_stress(double load, double half_width, double x, double z);
/// σ_z on the centre line x = 0 at depth z > 0, compression positive.
double flamant_centre_line_vertical_stress(double load, double half_width, double z);
/// σ_x on the centre line x = 0 at depth z > 0, compression positive.
double flamant_centre_line_horizontal_stress(double load, double half_width, double z);

// --- The same strip on a finite box: a layer between smooth walls on a smooth rigid base -------
// The half model of a bundled case is the box 0 <= x <= W, 0 <= z <= H (z down from the loaded
// surface) with rollers on x = 0 (symmetry), x = W and the base z = H. Smooth walls make the
// problem periodic in x with period 2W, so the load is the cosine series
//   p(x) = q b/W + Σ_{n>=1} (2q/(nπ)) sin(k_n b) cos(k_n x),  k_n = nπ/W.
// The mean term is the laterally confined (oedometric) state σ_z = q b/W, σ_x = K0 q b/W with
// K0 = ν/(1−ν). Each other term has the Airy function φ = cos(k x) f(z) (σ_x = φ_zz, σ_z = φ_xx,
// τ = −φ_xz), f = (A + B kz) e^{−kz} + (C + D k(H−z)) e^{−k(H−z)}, with σ_z = p_n cos(kx) and
// τ = 0 at z = 0, and τ = 0, u_z = 0 at z = H, i.e. f'(H) = f'''(H) = 0 (from the compatibility of
// u_z: u_z ∝ f'''/k² − (2 + ν')f'), so those terms do not depend on ν. As W, H → ∞ the sum tends to
// the Flamant strip, but only like b/W: the far walls take the load, which the Flamant field
// spreads as 1/r, so σ_x differs by about 0.6 q b/W on the centre line (4.6 % of q at z = b in a
// 12b x 12b box), while σ_z is changed by less than 0.1 % of q there.

struct SmoothLayer {
  double width = 0.0;          ///< W [m], the far wall x = W
  double depth = 0.0;          ///< H [m], the base z = H
  double poisson_ratio = 0.0;  ///< ν (the mean term only)
};

/// σ_x and σ_z (τ_xz is not computed) under the strip of half width b on the smooth layer, at
/// (x, z) with 0 <= x <= W and 0 < z <= H, compression positive, summed over the cosine modes
/// until e^{−k z} < 1e-16 (std::invalid_argument outside the box or for b > W).
StripStress strip_on_smooth_layer_stress(double load, double half_width, const SmoothLayer& layer,
                                         double x, double z);

/// The settlement u_z (downwards) of the loaded surface z = 0 at the points `x` (0 <= x <= W),
/// plane strain, for Young's modulus E: the oedometric q b H/(W M) of the mean load,
/// M = E(1−ν)/((1+ν)(1−2ν)), plus Σ cos(k_n x) f_n‴(0)/(E′ k_n²) with E′ = E/(1−ν²) (from
/// u_z = cos(kx)(f‴/k² − (2+ν′)f′)/E′, ν′ = ν/(1−ν), and f′(0) = 0), over `modes` cosine modes
/// (the terms fall like 1/n²). In the half-plane limit s(0) − s(b) = 4 ln2 (1−ν²) q b/(π E).
std::vector<double> strip_on_smooth_layer_surface_settlement(double load, double half_width,
                                                             const SmoothLayer& layer,
                                                             double young_modulus,
                                                             const std::vector<double>& x,
                                                             long modes = 20000);

}  // namespace rktsph::references
