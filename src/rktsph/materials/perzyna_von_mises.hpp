// Perzyna viscoplasticity with a Von Mises function and linear hardening or softening of the yield
// stress (docs/theory.md §1.3–1.4, §2.8):
//
//   eps_vp_rate = fluidity <Psi> m,  Psi = <(q - Y) / Y>^N,  m = (3/2) s / q,
//   Y_rate = H eps_eq_rate,  eps_eq_rate = sqrt(2/3 e_vp_rate : e_vp_rate) = fluidity Psi.
//
// Softening stops at `minimum_yield_stress`, so that F0 = Y never reaches 0.
#pragma once

#include <limits>

#include "rktsph/materials/invariants.hpp"
#include "rktsph/materials/material.hpp"
#include "rktsph/materials/parameter_reader.hpp"

namespace rktsph {

struct PerzynaVonMisesParameters {
  double yield_stress = 0.0;          // Y0 [Pa], > 0
  double hardening_modulus = 0.0;     // H [Pa], < 0 for softening
  double fluidity = 0.0;              // gamma [1/s], > 0
  double exponent = 1.0;              // N [-], > 0
  double minimum_yield_stress = 0.0;  // floor of Y under softening [Pa], in (0, Y0]
  /// Largest mean stress [Pa], >= 0; +infinity (the default) leaves tension unlimited.
  double tension_cutoff = std::numeric_limits<double>::infinity();
};

class PerzynaVonMises final : public Material {
 public:
  // Indices of the internal variables.
  static constexpr int kEquivalentStrain = 0;  // "eps_vp" [-]
  static constexpr int kYieldStress = 1;       // "yield_stress" [Pa]

  PerzynaVonMises(double density, ElasticConstants elastic, PerzynaVonMisesParameters parameters);
  /// Keys: density, young_modulus, poisson_ratio, yield_stress, hardening_modulus (0),
  /// fluidity, exponent (1), minimum_yield_stress (0.01 yield_stress), tension_cutoff (none).
  static std::unique_ptr<Material> from_parameters(ParameterReader& reader);

  std::string model_name() const override { return "perzyna_von_mises"; }
  int internal_count() const override { return 2; }
  std::vector<std::string> internal_names() const override;
  void initial_internal(std::span<double> internal) const override;
  bool is_elastic() const override { return false; }
  double tension_cutoff() const override { return parameters_.tension_cutoff; }
  void viscoplastic_rate(const SymmetricTensor& stress, std::span<const double> internal,
                         SymmetricTensor& strain_rate,
                         std::span<double> internal_rate) const override;
  /// (3 G + max(H, 0)) gamma N Psi^((N-1)/N) / Y (docs/theory.md eq. 2.7), with Psi^(1/N) = (q -
  /// Y)/Y floored at kOverstressFloor so that N < 1 gives a finite rate as Psi -> 0.
  double source_stiffness(const SymmetricTensor& stress,
                          std::span<const double> internal) const override;

  const PerzynaVonMisesParameters& parameters() const { return parameters_; }
  /// F0 = max(Y, minimum_yield_stress).
  double effective_yield_stress(std::span<const double> internal) const;
  /// Psi = <(q - F0)/F0>^N.
  double overstress(const SymmetricTensor& stress, std::span<const double> internal) const;
  bool flows(const SymmetricTensor& stress, std::span<const double> internal) const override {
    return overstress(stress, internal) > 0.0;
  }
  bool has_flowed(std::span<const double> internal) const override {
    return internal[kEquivalentStrain] > 0.0;
  }
  /// g = F = q: C1 = 0, C2 = sqrt3, C3 = 0 (docs/theory.md §1.4).
  static FlowCoefficients flow_coefficients();
  /// m = dq/dstress = (3/2) s / q; zero at q = 0.
  static SymmetricTensor flow_direction(const SymmetricTensor& stress);

  /// Relative overstress (q - Y)/Y below which the stiffness of an N < 1 source is no longer
  /// resolved: the stress left to relax there is below 1e-6 Y.
  static constexpr double kOverstressFloor = 1e-6;

 private:
  PerzynaVonMisesParameters parameters_;
};

}  // namespace rktsph
