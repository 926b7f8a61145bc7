// Isotropic linear-elastic moduli shared by the analytical references.
#pragma once

namespace rktsph::references {

/// Constrained (oedometric, P-wave) modulus M = E(1-ν)/((1+ν)(1-2ν)): the stiffness of a
/// laterally confined column (docs/theory.md §8.5, §8.8).
inline double oedometric_modulus(double young_modulus, double poisson_ratio) {
  return young_modulus * (1.0 - poisson_ratio) /
         ((1.0 + poisson_ratio) * (1.0 - 2.0 * poisson_ratio));
}

inline double shear_modulus(double young_modulus, double poisson_ratio) {
  return young_modulus / (2.0 * (1.0 + poisson_ratio));
}

inline double bulk_modulus(double young_modulus, double poisson_ratio) {
  return young_modulus / (3.0 * (1.0 - 2.0 * poisson_ratio));
}

/// K0 = ν/(1-ν): lateral to vertical stress ratio of an elastic column that cannot strain sideways.
inline double earth_pressure_at_rest(double poisson_ratio) {
  return poisson_ratio / (1.0 - poisson_ratio);
}

}  // namespace rktsph::references
