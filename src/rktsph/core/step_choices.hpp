// The step's numerical choices that a case may make (docs/theory.md §2.2, §3.3), as plain enums
// below every layer: the case reader fills them, the step and its controls read them, and neither
// needs the other's headers.
#pragma once

namespace rktsph {

/// How the nodal stress is updated in step 2 (docs/theory.md §2.2).
enum class StressUpdate {
  HalfStep,      ///< thesis: the gradient of the stress points' half-step velocities (eq. 2.3)
  MeanVelocity,  ///< the lumped average of G((v^n + v^{n+1})/2), the velocity of u (eq. 2.5)
};

/// The fields the hourglass filter acts on (docs/theory.md §3.3).
/// Unset in the case: Velocity where each stress point's stencil is its cell's corners, All
/// with wider stencils (where the velocity-only filter is unstable).
enum class HourglassFields {
  Velocity,  ///< the velocity only: equilibrium stress states stay fixed points
  All,       ///< every field (docs/theory.md §3.3); the total normal stress in the saturated model
};

}  // namespace rktsph
