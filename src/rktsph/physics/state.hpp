// The persistent state of a run: the fields on the SPH nodes (docs/theory.md §2.2), and in 2D
// the generalised hourglass force of each stress-point cell (eq. 3.9), the only state a stress
// point carries between steps.
#pragma once

#include <array>

#include "rktsph/core/field_array.hpp"

namespace rktsph {

struct State {
  double time = 0.0;  ///< [s]
  long step = 0;
  FieldArray fields;        ///< the model's unknowns (velocity, stress, ...) on SPH nodes
  FieldArray internal;      ///< internal variables on SPH nodes
  FieldArray displacement;  ///< u, integrated from the velocity (trapezoidal), one field per axis
  /// e: the time integral of the symmetric nodal velocity gradient the nodal stress was updated
  /// with (xx, yy, xy), kept only when the strain hourglass stiffness is on (docs/theory.md eq.
  /// 3.5); empty otherwise.
  FieldArray strain;
  /// The generalised hourglass force k q of every stress-point cell (x, y), advanced with the
  /// velocity (docs/theory.md eq. 3.9); empty when the hourglass stiffness is off.
  FieldArray hourglass_force;

  /// Every array of the state, in checkpoint order (empty ones included).
  std::array<FieldArray*, 5> arrays() {
    return {&fields, &internal, &displacement, &strain, &hourglass_force};
  }
  std::array<const FieldArray*, 5> arrays() const {
    return {&fields, &internal, &displacement, &strain, &hourglass_force};
  }
};

}  // namespace rktsph
