// Static bounds on the deposit of a collapsed cohesive (Tresca / Von Mises) block (thesis §5.3.4;
// docs/theory.md §9.14).
//
// A thin deposit of unit weight γ resting on a rough base is statically admissible only if its
// basal shear γ h |dh/dx| does not exceed the cohesion c (the lubrication, thin-layer balance).
// Integrated from the front, this bounds the height at a distance x′ behind the front by Nye's
// plastic profile
//
//   h(x′) ≤ √(2 c x′ / γ).
//
// A block of area A spreading from a vertical back wall fills the steepest admissible profile
// when A = (2/3) L √(2 c L / γ); any deposit at rest therefore runs out at least
//
//   L_min = (3A/2)^(2/3) (γ / 2c)^(1/3),   with a height at the wall of at most √(2 c L_min / γ).
//
// Before it stops, the front of a collapsing column of height H cannot outrun the inviscid dam
// break (Ritter): x_f(t) ≤ x_0 + 2 t √(g H).
#pragma once

namespace rktsph::references {

/// √(2 c x′ / γ): the highest admissible surface at a distance x′ ≥ 0 behind the front [m].
/// Throws std::invalid_argument for a negative distance or a non-positive c or γ.
double nye_height(double distance_behind_front, double cohesion, double unit_weight);
/// L_min = (3A/2)^(2/3) (γ/2c)^(1/3): the shortest run-out from the back wall of a deposit of
/// area A [m²] at rest on a rough base [m]. Throws std::invalid_argument for non-positive inputs.
double nye_minimum_runout(double area, double cohesion, double unit_weight);
/// x_0 + 2 t √(g H): Ritter's front of the inviscid dam break of a column of height H released
/// at x_0 at t = 0, an upper bound on a cohesive column's front [m].
double ritter_front(double time, double initial_front, double height, double gravity);

}  // namespace rktsph::references
