// Perzyna viscoplasticity with the Mohr–Coulomb hexagon as six planes in principal stresses, each
// with its own overstress (a multi-surface Koiter rule), non-associated flow, hardening or
// softening of c and phi, and a Rankine tension cut-off on each principal stress (docs/theory.md
// §1.8, eqs. 1.16–1.18):
//
//   F_ij = (sigma_i - sigma_j)/2 + (sigma_i + sigma_j)/2 sin(phi) - c cos(phi),  i != j,
//   g_ij: the same with psi,  F_i = sigma_i - sigma_t  (sigma_t <= c cot phi, the apex),
//   eps_vp_rate = gamma sum_ij <F_ij/F0>^N dg_ij/dstress + gamma sum_i <F_i/F0>^N P_i,
//
// P_i = n_i (x) n_i the principal projectors. The elastic domain (every F <= 0) is the exact
// hexagon; each plane's flow vanishes with its own overstress, so the flow is continuous at the
// corners and at the apex without rounding the surface (eq. 1.17).
#pragma once

#include <array>

#include "rktsph/materials/frictional_strength.hpp"
#include "rktsph/materials/material.hpp"
#include "rktsph/materials/parameter_reader.hpp"

namespace rktsph {

class PerzynaMohrCoulomb final : public Material {
 public:
  using Internal = FrictionalInternal;
  /// Six Mohr–Coulomb planes (ordered pairs i != j) and three tension planes.
  static constexpr int kPlaneCount = 9;

  PerzynaMohrCoulomb(double density, ElasticConstants elastic, FrictionalParameters parameters);
  /// Keys: density, young_modulus, poisson_ratio, cohesion, friction_angle, dilatancy_angle (0),
  /// cohesion_hardening_modulus (0), friction_hardening_modulus (0), minimum_cohesion (0),
  /// minimum_friction_angle (0), fluidity, exponent (1), reference_stress (c0 cos phi0;
  /// required if cohesion is 0), tension_cutoff (the apex).
  static std::unique_ptr<Material> from_parameters(ParameterReader& reader);

  std::string model_name() const override { return "perzyna_mohr_coulomb"; }
  int internal_count() const override { return Internal::kCount; }
  std::vector<std::string> internal_names() const override;
  void initial_internal(std::span<double> internal) const override;
  bool is_elastic() const override { return false; }
  void viscoplastic_rate(const SymmetricTensor& stress, std::span<const double> internal,
                         SymmetricTensor& strain_rate,
                         std::span<double> internal_rate) const override;
  bool flows(const SymmetricTensor& stress, std::span<const double> internal) const override;
  /// eps_vp > 0: the zero-energy controls that follow flow keep a cell that has flowed at its
  /// near-flow strength (docs/theory.md eqs. 3.10, 3.14) instead of restoring it whenever the
  /// point drops below yield.
  bool has_flowed(std::span<const double> internal) const override {
    return internal[Internal::kEquivalentStrain] > 0.0;
  }
  /// gamma/F0 times the largest row sum of |dF_a/dstress : D : dg_b/dstress| N x_b^(N-1) over
  /// the planes that flow (docs/theory.md eq. 1.18): exact on a face, a bound at corners.
  double source_stiffness(const SymmetricTensor& stress,
                          std::span<const double> internal) const override;

  const FrictionalParameters& parameters() const { return parameters_; }
  /// max over the six planes: the Mohr–Coulomb function (sigma1 - sigma3)/2 + (sigma1 + sigma3)/2
  /// sin(phi) - c cos(phi) with sigma1 >= sigma2 >= sigma3 [Pa].
  double yield_function(const SymmetricTensor& stress, std::span<const double> internal) const;

  static constexpr double kOverstressFloor = 1e-6;

 private:
  /// One plane in principal stresses: F = normal . sigma_principal - offset, its flow direction
  /// (coefficients of P_1, P_2, P_3) and its value at the stress.
  struct Plane {
    std::array<double, 3> normal;
    std::array<double, 3> flow;
    double value;
  };
  struct Planes {
    std::array<Plane, kPlaneCount> plane;
    std::array<double, 3> principal;           // eigenvalues
    std::array<SymmetricTensor, 3> projector;  // n_i (x) n_i
  };
  Planes planes(const SymmetricTensor& stress, std::span<const double> internal) const;

  FrictionalParameters parameters_;
};

}  // namespace rktsph
