// Perzyna viscoplasticity with a Drucker–Prager cone matched to Mohr–Coulomb, non-associated flow,
// hardening or softening of c and phi, and a tension cut-off on the mean stress that also treats
// the apex (docs/theory.md §1.8, eqs. 1.11–1.15):
//
//   F = q - M p - k,  g = q - M_g p,  F_t = -p - sigma_t  (sigma_t <= c cot phi, the apex),
//   eps_vp_rate = gamma <F/F0>^N m + gamma <F_t/F0>^N I/3,
//   m = (3/2) s / max(q, F) + (M_g/3) I,
//
// with M, k, M_g from c, phi, psi by the chosen matching (plane strain, compression or extension
// corners of Mohr–Coulomb, eq. 1.12). max(q, F) differs from q only beyond the apex, where it
// makes the deviator relax in proportion instead of at a fixed rate (eq. 1.14).
#pragma once

#include <string>

#include "rktsph/materials/frictional_strength.hpp"
#include "rktsph/materials/invariants.hpp"
#include "rktsph/materials/material.hpp"
#include "rktsph/materials/parameter_reader.hpp"

namespace rktsph {

/// Where the cone meets Mohr–Coulomb (docs/theory.md eq. 1.12).
enum class ConeMatching {
  PlaneStrain,  // same plane-strain strength and dilatancy as Mohr–Coulomb with phi, psi
  Compression,  // through the triaxial-compression corners (outer cone)
  Extension,    // through the triaxial-extension corners (inner cone)
};

/// The case-file words of ConeMatching, in enum order.
const std::vector<std::string>& cone_matching_words();

struct PerzynaDruckerPragerParameters {
  FrictionalParameters strength;
  ConeMatching matching = ConeMatching::PlaneStrain;
};

/// q = M p + k on the yield cone, g = q - M_g p the flow potential.
struct DruckerPragerCone {
  double slope = 0.0;            // M [-]
  double intercept = 0.0;        // k [Pa]
  double dilatancy_slope = 0.0;  // M_g [-]
};

class PerzynaDruckerPrager final : public Material {
 public:
  using Internal = FrictionalInternal;

  PerzynaDruckerPrager(double density, ElasticConstants elastic,
                       PerzynaDruckerPragerParameters parameters);
  /// Keys: density, young_modulus, poisson_ratio, cohesion, friction_angle, dilatancy_angle (0),
  /// matching (plane_strain), cohesion_hardening_modulus (0), friction_hardening_modulus (0),
  /// minimum_cohesion (0), minimum_friction_angle (0), fluidity, exponent (1), reference_stress
  /// (k of the initial cone; required if cohesion is 0), tension_cutoff (the apex).
  static std::unique_ptr<Material> from_parameters(ParameterReader& reader);

  std::string model_name() const override { return "perzyna_drucker_prager"; }
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
  /// gamma/F0 [(3G + K M M_g + hardening) N x^(N-1) + K N x_t^(N-1)] (docs/theory.md eq. 1.15),
  /// x = F/F0 and x_t = F_t/F0 floored at kOverstressFloor; the cut-off term only where F_t > 0.
  double source_stiffness(const SymmetricTensor& stress,
                          std::span<const double> internal) const override;

  const PerzynaDruckerPragerParameters& parameters() const { return parameters_; }
  /// M, k, M_g of c [Pa], phi, psi [rad] for a matching (docs/theory.md eq. 1.12).
  static DruckerPragerCone matched_cone(ConeMatching matching, double cohesion,
                                        double friction_angle, double dilatancy_angle);
  /// The cone of the current strength.
  DruckerPragerCone cone(std::span<const double> internal) const;
  /// F = q - M p - k [Pa].
  double yield_function(const SymmetricTensor& stress, std::span<const double> internal) const;
  /// F_t = tr(stress)/3 - sigma_t [Pa] (-inf without a limit).
  double cutoff_function(const SymmetricTensor& stress, std::span<const double> internal) const;

  /// Relative overstress below which the stiffness of an N < 1 source is no longer resolved (as
  /// PerzynaVonMises::kOverstressFloor).
  static constexpr double kOverstressFloor = 1e-6;

 private:
  PerzynaDruckerPragerParameters parameters_;
};

}  // namespace rktsph
