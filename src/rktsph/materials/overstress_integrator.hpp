// The stress update of one material point over an interval: the material integrates its own
// stress. The point ODE of the carried stresses sigma and the internal variables kappa,
//
//   sigma' = R_sigma - D : eps_dot^vp(sigma, kappa),   kappa' = kappa_dot(sigma, kappa),
//
// with the flux rate R_sigma frozen over the interval (docs/theory.md §2.1, §2.8), by classical RK4
// on sub-steps sized by the source stiffness (the sub-step rule, eq. 2.7), then the tension
// cut-off (docs/theory.md §1.7). D is the elastic stiffness condensed onto the carried components
// (docs/theory.md §1.6, eq. 1.6): the strains of the stress-free components are absorbed by it, so
// only the carried components of eps_dot^vp enter.
//
// The kinematic setting comes in as plain tables (which components are carried, their slots and
// shear factors, the condensed D), so that this file needs nothing above materials/.
#pragma once

#include <array>
#include <cmath>
#include <functional>
#include <span>

#include "rktsph/materials/material.hpp"

namespace rktsph {

/// The options of the source integration of a step (the velocity's damping source uses the same
/// rule and the same frozen-flux choice, docs/theory.md §2.1).
struct SourceIntegration {
  // m = ceil(interval * stiffness / factor). 0.5 rather than the 2.5 of eq. 2.7: with larger steps
  // the RK4 stages jump across the yield surface (the Macaulay switch) and the overstress
  // undershoots (15 % per sub-step at lambda delta = 2.3, docs/theory.md §2.1).
  double substep_factor = 0.5;
  int max_substeps = 1000;
  /// true: y' = R + S(y) with R frozen (docs/theory.md §2.8); false: the additive split,
  /// y = y0 + interval R + [integral of y' = S(y) from y0] (biased by xi dt/2 with damping,
  /// eq. 2.6).
  bool frozen_flux = true;
};

/// The sub-step rule of docs/theory.md eq. 2.7: m = max(1, ceil(interval * stiffness / factor)),
/// capped at max_substeps. The cap is tested on the double, before any conversion to int, so that
/// an infinite or NaN stiffness (a diverging source) gives the cap.
inline int substep_count(double interval, double stiffness, double factor, int max_substeps) {
  const double wanted = std::ceil(interval * stiffness / factor);
  if (!(wanted < max_substeps)) return max_substeps;
  return wanted > 1.0 ? static_cast<int>(wanted) : 1;
}

/// Classical RK4 over `substeps` equal sub-steps of [time, time + interval] for y' = f(t, y) on the
/// n values y[0, n): slope(t, state, slope_out). `stage` and `k[0..3]` are caller scratch of n
/// values each, so that a step allocates nothing.
template <class Slope>
void rk4_substeps(Slope&& slope, double time, double interval, int substeps, int n, double* y,
                  double* stage, double* const k[4]) {
  const double delta = interval / substeps;
  for (int s = 0; s < substeps; ++s) {
    const double start = time + s * delta;
    slope(start, static_cast<const double*>(y), k[0]);
    for (int c = 0; c < n; ++c)
      stage[c] = y[c] + 0.5 * delta * k[0][c];
    slope(start + 0.5 * delta, static_cast<const double*>(stage), k[1]);
    for (int c = 0; c < n; ++c)
      stage[c] = y[c] + 0.5 * delta * k[1][c];
    slope(start + 0.5 * delta, static_cast<const double*>(stage), k[2]);
    for (int c = 0; c < n; ++c)
      stage[c] = y[c] + delta * k[2][c];
    slope(start + delta, static_cast<const double*>(stage), k[3]);
    for (int c = 0; c < n; ++c)
      y[c] += delta / 6.0 * (k[0][c] + 2.0 * k[1][c] + 2.0 * k[2][c] + k[3][c]);
  }
}

/// The stress components a kinematic setting carries, in its order (docs/theory.md §1.6).
struct CarriedStress {
  static constexpr int kMax = 6;
  int count = 0;
  std::array<int, kMax> slot{};             ///< SymmetricTensor slot of each carried component
  std::array<double, kMax> shear_factor{};  ///< 2 off the diagonal (gamma = 2 eps), 1 on it
};

/// D on the carried components, row r of column c at r * kMax + c, acting on engineering shear
/// strains (sigma = D gamma).
using CondensedStiffness = std::array<double, CarriedStress::kMax * CarriedStress::kMax>;

/// The condensation of elastic constants onto the carried components (the kinematic setting's D),
/// for a material whose elasticity depends on the stress (Material::stress_dependent_elasticity):
/// supplied by the model, which knows the setting.
using StiffnessCondenser = std::function<CondensedStiffness(const ElasticConstants&)>;

/// The stress update of one material in one kinematic setting (see the top of this file).
class OverstressIntegrator {
 public:
  /// The most internal variables a material may have.
  static constexpr int kMaxInternal = 8;

  /// `material` must outlive the integrator. `stiffness` is D of material.elastic(); `condense`
  /// is needed (and used) only if the material's elasticity depends on the stress.
  OverstressIntegrator(const Material& material, const CarriedStress& carried,
                       const CondensedStiffness& stiffness, SourceIntegration integration,
                       StiffnessCondenser condense = {});

  /// sigma (the carried components) and kappa advanced over `interval` under the frozen flux rate
  /// `rate_sigma`, then returned onto the tension cut-off.
  void advance(const double* rate_sigma, double interval, double* sigma, double* kappa) const {
    integrate(rate_sigma, interval, sigma, kappa);
    cut_tension(sigma);
  }
  /// The sub-stepped update of advance, before the tension cut-off. A material with
  /// stress-dependent elasticity is always integrated in the frozen-flux form.
  void integrate(const double* rate_sigma, double interval, double* sigma, double* kappa) const;
  /// Returns a mean stress above the material's tension cut-off onto it (docs/theory.md eq. 1.7).
  void cut_tension(double* sigma) const;
  /// The source -D : eps_dot^vp on the carried components and the rates of the internal variables.
  void source(const double* sigma, const double* kappa, double* sigma_rate,
              double* kappa_rate) const;

  const Material& material() const { return material_; }

 private:
  /// integrate() for stress-dependent elasticity: the flux rate is D : eps_dot with D of
  /// elastic(), so eps_dot = D^-1 R_sigma is recovered and
  ///   sigma' = D(sigma) : (eps_dot - eps_dot^vp),  kappa' = kappa_dot
  /// integrated by RK4 (docs/theory.md §1.5, eq. 1.10c), with the tangent D at each stage.
  void integrate_stress_dependent(const double* rate_sigma, double interval, double* sigma,
                                  double* kappa) const;
  /// The stress of the carried components as a full tensor (stress-free components zero).
  SymmetricTensor full_stress(const double* sigma) const;

  const Material& material_;
  CarriedStress carried_;
  CondensedStiffness stiffness_;
  SourceIntegration integration_;
  StiffnessCondenser condense_;
  CondensedStiffness compliance_{};  // the inverse of stiffness_ (stress-dependent elasticity)
};

}  // namespace rktsph
