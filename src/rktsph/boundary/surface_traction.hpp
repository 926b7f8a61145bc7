// The traction condition sigma·n = t on a surface node of any outward unit normal n
// (docs/theory.md eq. 5.1a): sigma·n is overwritten, the tangential–tangential stress is kept.
#pragma once

#include <array>
#include <cstdint>
#include <optional>

#include "rktsph/boundary/surface_set.hpp"

namespace rktsph {

/// A symmetric stress tensor, full 3 x 3 (components a missing field does not carry are zero).
using StressTensor = std::array<std::array<double, 3>, 3>;

struct TractionCondition {
  Vec3 normal{};    ///< outward unit normal n
  Vec3 traction{};  ///< target t, components in the global frame [Pa, tension positive]
  /// Bit c: (sigma·n)_c = t_c is imposed; the other components keep their current sigma·n (a
  /// reaction to an imposed velocity, or a component this condition does not give).
  std::uint8_t components = 0;
  /// Saturated model: sigma is the effective stress and t acts on the total stress
  /// sigma' - alpha p_w I, so sigma'·n = t + alpha p_w n (docs/theory.md §5.1).
  std::optional<double> biot_pore_pressure;
};

/// +-1 and the axis if `n` is a coordinate axis, else nullopt.
struct AxisNormal {
  int axis = 0;
  double sign = 1.0;
};
std::optional<AxisNormal> as_axis_normal(const Vec3& n);

/// Imposes `condition` on `sigma` in `dimension` (1 to 3) dimensions. On a coordinate axis
/// n = sign e_a this assigns sigma_ac = sign t_c (+ alpha p_w for c = a) exactly; on any other
/// normal it uses the rotated form, eq. 5.1a.
void impose_traction(const TractionCondition& condition, int dimension, StressTensor& sigma);

}  // namespace rktsph
