#pragma once

namespace rktsph {

/// Smoothing kernels (docs/theory.md, "Kernels"). Support radius: 2h (cubic), 3h (quintic, Gaussian
/// truncated at 3h).
enum class KernelType { CubicSpline, QuinticSpline, Gaussian };

}  // namespace rktsph
