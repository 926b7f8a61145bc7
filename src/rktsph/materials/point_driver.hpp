// Drives one material point along a prescribed path: each of the six components has either its
// total strain rate or its stress rate prescribed, and the other one follows from
//
//   stress_rate = D^e : (strain_rate - eps_vp_rate(stress, internal)),  internal_rate = rates,
//
// integrated with classical RK4 over sub-steps chosen by the rule of docs/theory.md eq. 2.7,
// m = max(1, ceil(dt * source_stiffness / substep_factor)), capped at max_substeps: the rule and
// the RK4 sub-steps of the SPH step's stress update (materials/overstress_integrator.hpp), on rates
// of its own (point_driver.cpp says why it does not call that integrator).
// Used by the material tests and by validation of constitutive behaviour without SPH.
#pragma once

#include <array>
#include <functional>
#include <vector>

#include "rktsph/materials/material.hpp"

namespace rktsph {

enum class PathControl {
  Strain,  // the total strain rate of the component is prescribed
  Stress,  // the stress rate of the component is prescribed
};

struct StrainPath {
  /// Per component (xx, yy, zz, xy, yz, zx).
  std::array<PathControl, 6> control{};  // all Strain
  /// Prescribed rates at time t: strain rate for Strain components, stress rate [Pa/s] for
  /// Stress components (the other entries are ignored).
  std::function<SymmetricTensor(double time)> rate;
  double duration = 0.0;  // [s]

  /// Every strain component prescribed at a constant rate.
  static StrainPath constant_strain_rate(const SymmetricTensor& strain_rate, double duration);
  /// Axial (xx) strain at a constant rate, yy and zz stresses held at their starting values,
  /// shear strains held: a 1D bar (from zero stress) or a triaxial test (from a confining stress).
  static StrainPath uniaxial_stress(double axial_strain_rate, double duration);
};

struct PointState {
  double time = 0.0;             // [s]
  SymmetricTensor stress{};      // [Pa]
  SymmetricTensor strain{};      // total strain accumulated since the start
  std::vector<double> internal;  // material internal variables
  int substeps = 0;              // RK4 sub-steps of the step that ended here (0 at the start)
};

struct DriveOptions {
  double time_step = 0.0;       // [s], > 0; the last step is shortened to end at the duration
  double substep_factor = 2.5;  // eq. 2.7 (§2.8); smaller values give more accurate integration
  int max_substeps = 1000;
  int record_every = 1;  // keep every n-th step (the first and last are always kept)
};

/// Zero strain, the given stress, and the material's initial internal variables.
PointState initial_point_state(const Material& material, const SymmetricTensor& stress);

/// The states at the start, every `record_every` steps and at the end. Throws
/// std::invalid_argument for bad options or a missing rate, RunError if the state stops being
/// finite.
std::vector<PointState> drive(const Material& material, const StrainPath& path,
                              const PointState& start, const DriveOptions& options);

}  // namespace rktsph
