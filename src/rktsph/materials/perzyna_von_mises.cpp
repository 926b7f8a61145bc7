#include "rktsph/materials/perzyna_von_mises.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "rktsph/materials/linear_elastic.hpp"
#include "rktsph/materials/perzyna_overstress.hpp"

namespace rktsph {

PerzynaVonMises::PerzynaVonMises(double density, ElasticConstants elastic,
                                 PerzynaVonMisesParameters parameters)
    : Material(density, elastic), parameters_(parameters) {}

std::unique_ptr<Material> PerzynaVonMises::from_parameters(ParameterReader& reader) {
  constexpr double infinity = std::numeric_limits<double>::infinity();
  const ElasticParameters elastic = read_elastic_parameters(reader);
  PerzynaVonMisesParameters p;
  p.yield_stress = reader.required("yield_stress", 0.0, infinity, true);
  p.hardening_modulus = reader.optional("hardening_modulus", 0.0, -infinity, infinity);
  p.fluidity = reader.required("fluidity", 0.0, infinity, true);
  p.exponent = reader.optional("exponent", 1.0, 0.0, infinity, true);
  // Open at 0: a zero floor would let softening drive F0 to 0 and Psi to infinity.
  p.minimum_yield_stress =
      reader.optional("minimum_yield_stress", 0.01 * p.yield_stress, 0.0, p.yield_stress, true);
  // Off unless given: a soil with cohesion carries some tension, and how much is the user's call.
  p.tension_cutoff = reader.optional("tension_cutoff", infinity, 0.0, infinity);
  return std::make_unique<PerzynaVonMises>(elastic.density, elastic.elastic, p);
}

std::vector<std::string> PerzynaVonMises::internal_names() const {
  return {"eps_vp", "yield_stress"};
}

void PerzynaVonMises::initial_internal(std::span<double> internal) const {
  internal[kEquivalentStrain] = 0.0;
  internal[kYieldStress] = parameters_.yield_stress;
}

double PerzynaVonMises::effective_yield_stress(std::span<const double> internal) const {
  return std::max(internal[kYieldStress], parameters_.minimum_yield_stress);
}

double PerzynaVonMises::overstress(const SymmetricTensor& stress,
                                   std::span<const double> internal) const {
  const double yield = effective_yield_stress(internal);
  return macaulay_power((von_mises_stress(stress) - yield) / yield, parameters_.exponent);
}

FlowCoefficients PerzynaVonMises::flow_coefficients() {
  return {0.0, std::sqrt(3.0), 0.0};
}

SymmetricTensor PerzynaVonMises::flow_direction(const SymmetricTensor& stress) {
  const StressInvariants invariants = stress_invariants(stress);
  if (invariants.q <= 0.0) return SymmetricTensor{};
  return flow_vector(invariants, flow_coefficients());
}

void PerzynaVonMises::viscoplastic_rate(const SymmetricTensor& stress,
                                        std::span<const double> internal,
                                        SymmetricTensor& strain_rate,
                                        std::span<double> internal_rate) const {
  const double psi = overstress(stress, internal);
  strain_rate.fill(0.0);
  internal_rate[kEquivalentStrain] = 0.0;
  internal_rate[kYieldStress] = 0.0;
  if (psi <= 0.0) return;
  const double flow_magnitude = parameters_.fluidity * psi;
  const SymmetricTensor direction = flow_direction(stress);
  for (int i = 0; i < 6; ++i)
    strain_rate[i] = flow_magnitude * direction[i];
  // With m = (3/2) s/q, sqrt(2/3 m:m) = 1, so the equivalent rate is gamma Psi (docs/theory.md
  // §1.4).
  internal_rate[kEquivalentStrain] = flow_magnitude;
  const bool at_softening_floor = parameters_.hardening_modulus < 0.0 &&
                                  internal[kYieldStress] <= parameters_.minimum_yield_stress;
  if (!at_softening_floor)
    internal_rate[kYieldStress] = parameters_.hardening_modulus * flow_magnitude;
}

double PerzynaVonMises::source_stiffness(const SymmetricTensor& stress,
                                         std::span<const double> internal) const {
  // The overstress q - Y relaxes as -(3G + H) gamma Psi (m:D:m = 3G, Y_rate = H gamma Psi), whose
  // derivative with respect to q is (3G + H) gamma N x^(N-1) / Y with x = (q - Y)/Y = Psi^(1/N).
  // The first proposal kept 3G only; hardening (H > 0) stiffens the source, so it is added, while
  // softening is left out to keep the estimate an upper bound (docs/theory.md eq. 2.7).
  const double yield = effective_yield_stress(internal);
  const double relative_overstress =
      std::max((von_mises_stress(stress) - yield) / yield, kOverstressFloor);
  const double exponent = parameters_.exponent;
  const double slope =
      exponent == 1.0 ? 1.0 : exponent * std::pow(relative_overstress, exponent - 1.0);
  const double modulus =
      3.0 * elastic().shear_modulus() + std::max(parameters_.hardening_modulus, 0.0);
  return modulus * parameters_.fluidity * slope / yield;
}

}  // namespace rktsph
