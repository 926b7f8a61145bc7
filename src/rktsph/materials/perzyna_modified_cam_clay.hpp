// Perzyna viscoplasticity with the Modified Cam-Clay ellipse (docs/theory.md §1.3, §1.5,
// eqs. 1.8–1.10):
//
//   f = q^2 + M(theta)^2 p (p - pc),  M(theta) = 6 sin(phi) / (3 - sin(phi) sin 3theta),
//   Psi = <f / pc^2>^N  (zero exactly on the ellipse, docs/theory.md §1.5),
//   eps_vp_rate = fluidity Psi m,  m = (M^2 / pc) dg'/dstress with g' = q^2 / M^2 + p (p - pc)
//   (M held fixed in the scaling). m equals the thesis's associated dg/dstress, g = f / pc
//   (eq. 1.8), on the ellipse, and unlike it stays bounded near the hydrostatic axis (see the
//   .cpp), pc_rate = -((1 + e0) / (lambda_c - kappa_c)) pc tr(eps_vp_rate)  (tension-positive
//   strain).
//
// Elasticity (key `elasticity`, docs/theory.md §1.5, eqs. 1.10a–1.10b): `constant` (the default),
// linear with constant E, nu; or `pressure_dependent`, the hypoelastic law of critical-state soil
// mechanics K = (1 + e0) p / kappa_c with G from a constant nu or a constant G, p clamped to
// [minimum_pressure, maximum_pressure]. The void ratio is held at e0 in both.
#pragma once

#include <limits>

#include "rktsph/materials/invariants.hpp"
#include "rktsph/materials/material.hpp"
#include "rktsph/materials/parameter_reader.hpp"

namespace rktsph {

struct PerzynaModifiedCamClayParameters {
  double friction_angle = 0.0;             // phi [deg], in (0, 90)
  double compression_index = 0.0;          // lambda_c [-], > kappa_c
  double swelling_index = 0.0;             // kappa_c [-], > 0
  double initial_void_ratio = 0.0;         // e0 [-], > 0
  double preconsolidation_pressure = 0.0;  // pc0 [Pa], > 0
  double fluidity = 0.0;                   // gamma [1/s], > 0
  double exponent = 1.0;                   // N [-], > 0
  /// The two elastic laws (see the top of this file).
  enum class Elasticity { Constant, PressureDependent };
  Elasticity elasticity = Elasticity::Constant;
  // Pressure-dependent elasticity only: exactly one of poisson_ratio and shear_modulus is given,
  // the other is NaN.
  double poisson_ratio = std::numeric_limits<double>::quiet_NaN();  // nu [-], in (-1, 0.5)
  double shear_modulus = std::numeric_limits<double>::quiet_NaN();  // G [Pa], > 0
  double minimum_pressure = 0.0;                                    // [Pa], > 0
  double maximum_pressure = 0.0;                                    // [Pa], > minimum_pressure
};

class PerzynaModifiedCamClay final : public Material {
 public:
  // Indices of the internal variables.
  static constexpr int kEquivalentStrain = 0;          // "eps_vp" [-]
  static constexpr int kPreconsolidationPressure = 1;  // "preconsolidation_pressure" [Pa]

  /// `elastic`: the constant E, nu; with pressure-dependent elasticity it is not used (elastic()
  /// is then the tangent at maximum_pressure, the stiffest state).
  PerzynaModifiedCamClay(double density, ElasticConstants elastic,
                         PerzynaModifiedCamClayParameters parameters);
  /// Keys: density, friction_angle, compression_index, swelling_index, initial_void_ratio,
  /// preconsolidation_pressure, fluidity, exponent (1), elasticity (constant); with constant
  /// elasticity young_modulus and poisson_ratio; with pressure_dependent exactly one of
  /// poisson_ratio and shear_modulus, and minimum_pressure (0.01 pc0), maximum_pressure (4 pc0).
  static std::unique_ptr<Material> from_parameters(ParameterReader& reader);

  std::string model_name() const override { return "perzyna_modified_cam_clay"; }
  int internal_count() const override { return 2; }
  std::vector<std::string> internal_names() const override;
  void initial_internal(std::span<double> internal) const override;
  bool is_elastic() const override { return false; }
  void viscoplastic_rate(const SymmetricTensor& stress, std::span<const double> internal,
                         SymmetricTensor& strain_rate,
                         std::span<double> internal_rate) const override;
  /// One-sided finite difference of the source of (stress, pc) along the direction in which the
  /// source moves them; see the .cpp for the two directions used. Positive whenever Psi > 0.
  double source_stiffness(const SymmetricTensor& stress,
                          std::span<const double> internal) const override;

  bool stress_dependent_elasticity() const override {
    return parameters_.elasticity ==
           PerzynaModifiedCamClayParameters::Elasticity::PressureDependent;
  }
  /// The tangent constants at `stress`: elastic() with constant elasticity, else those at the
  /// clamped mean pressure (pressure_dependent_elastic).
  ElasticConstants elastic_at(const SymmetricTensor& stress) const override;
  /// K = (1 + e0) p / kappa_c with p clamped to [minimum_pressure, maximum_pressure], G from nu
  /// (G = 3K(1 - 2nu) / (2(1 + nu))) or given (docs/theory.md eqs. 1.10a–1.10b).
  static ElasticConstants pressure_dependent_elastic(const PerzynaModifiedCamClayParameters& p,
                                                     double pressure);

  const PerzynaModifiedCamClayParameters& parameters() const { return parameters_; }
  /// M(theta) from sin 3theta (docs/theory.md §1.5); 6 sin(phi)/(3 - sin(phi)) in triaxial
  /// compression.
  double critical_state_ratio(double sin_3theta) const;
  /// f = q^2 + M^2 p (p - pc) [Pa^2]: < 0 inside the ellipse, 0 on it.
  double yield_function(const StressInvariants& invariants, double preconsolidation_pressure) const;
  /// Psi = <f / pc^2>^N.
  double overstress(const SymmetricTensor& stress, std::span<const double> internal) const;
  bool flows(const SymmetricTensor& stress, std::span<const double> internal) const override {
    return overstress(stress, internal) > 0.0;
  }
  bool has_flowed(std::span<const double> internal) const override {
    return internal[kEquivalentStrain] > 0.0;
  }
  /// C1, C2, C3 of m (docs/theory.md eqs. 1.9–1.10, with the regular potential above). The theta
  /// terms, which vanish like sqrt(J2) on the hydrostatic axis, are dropped where the
  /// Lode angle is undefined (StressInvariants::lode_defined).
  FlowCoefficients flow_coefficients(const StressInvariants& invariants,
                                     double preconsolidation_pressure) const;
  /// m = (M^2 / pc) dg'/dstress; equal to d(f / pc)/dstress on the ellipse f = 0.
  SymmetricTensor flow_direction(const SymmetricTensor& stress,
                                 double preconsolidation_pressure) const;
  /// (1 + e0) / (lambda_c - kappa_c).
  double hardening_factor() const;

  /// Finite-difference step of source_stiffness relative to pc. For N < 1 it also caps the
  /// stiffness near Psi = 0, like PerzynaVonMises::kOverstressFloor.
  static constexpr double kStiffnessStepRatio = 1e-6;

 private:
  struct SourceState {
    SymmetricTensor stress;
    double preconsolidation_pressure;
  };
  /// (stress_rate, pc_rate) of the source at a state: (-D^e : eps_vp_rate, pc_rate).
  SourceState source(const SourceState& state) const;

  PerzynaModifiedCamClayParameters parameters_;
  double sin_friction_angle_;
};

}  // namespace rktsph
