// A material seen at one material point: elastic constants, and (for viscoplastic materials) the
// viscoplastic strain rate and internal-variable rates at a given stress. Materials know nothing
// about SPH; that is why each one is tested alone on a single point (tests/materials/).
//
// Stress and strain are full 3D symmetric tensors in the order (xx, yy, zz, xy, yz, zx), tensor
// (not engineering) shear components, tension positive (docs/theory.md §1.1).
#pragma once

#include <array>
#include <limits>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "rktsph/core/small_tensor.hpp"

namespace rktsph {

struct ElasticConstants {
  double young_modulus = 0.0;  // E [Pa]
  double poisson_ratio = 0.0;  // nu [-]
  double lame_lambda() const {
    return young_modulus * poisson_ratio / ((1.0 + poisson_ratio) * (1.0 - 2.0 * poisson_ratio));
  }
  double shear_modulus() const { return young_modulus / (2.0 * (1.0 + poisson_ratio)); }
  double bulk_modulus() const { return young_modulus / (3.0 * (1.0 - 2.0 * poisson_ratio)); }
  /// Constrained (oedometric) modulus lambda + 2G.
  double constrained_modulus() const { return lame_lambda() + 2.0 * shear_modulus(); }
  /// Plane-stress modulus E' = E / (1 - nu^2).
  double plane_stress_modulus() const {
    return young_modulus / (1.0 - poisson_ratio * poisson_ratio);
  }
};

class Material {
 public:
  virtual ~Material() = default;

  /// The name the case file uses for this model, e.g. "linear_elastic".
  virtual std::string model_name() const = 0;
  double density() const { return density_; }
  /// The elastic constants; for a material whose elasticity depends on the stress, the stiffest
  /// ones it reaches, so that the time step (Courant) and the wave speeds built on them bound
  /// every state.
  const ElasticConstants& elastic() const { return elastic_; }
  /// True if the tangent elastic constants depend on the stress (elastic_at differs from
  /// elastic()): the stress update then integrates sigma' = D(sigma) : (eps_dot - eps_dot^vp).
  virtual bool stress_dependent_elasticity() const { return false; }
  /// The tangent elastic constants at `stress`; elastic() unless stress_dependent_elasticity().
  virtual ElasticConstants elastic_at(const SymmetricTensor& stress) const {
    (void)stress;
    return elastic_;
  }

  /// Number of internal variables (equivalent viscoplastic strain, yield stress, ...).
  virtual int internal_count() const { return 0; }
  virtual std::vector<std::string> internal_names() const { return {}; }
  /// Initial values of the internal variables.
  virtual void initial_internal(std::span<double> internal) const { (void)internal; }
  /// True if the material never flows (its source term is zero).
  virtual bool is_elastic() const { return true; }

  /// Viscoplastic strain rate at `stress` with internal variables `internal`, and the rates of the
  /// internal variables. Elastic materials return zeros.
  virtual void viscoplastic_rate(const SymmetricTensor& stress, std::span<const double> internal,
                                 SymmetricTensor& strain_rate,
                                 std::span<double> internal_rate) const {
    (void)stress;
    (void)internal;
    strain_rate.fill(0.0);
    for (double& r : internal_rate)
      r = 0.0;
  }

  /// True if the stress lies outside the elastic domain (the viscoplastic flow is non-zero).
  /// The domain is convex, so a straight stress path between two states that do not flow does
  /// not flow either. The default is the safe answer for a material that does not say: it may
  /// flow, so its source is always integrated.
  virtual bool flows(const SymmetricTensor& stress, std::span<const double> internal) const {
    (void)stress;
    (void)internal;
    return !is_elastic();
  }

  /// True if a point with these internal variables has flowed at some time (its equivalent
  /// viscoplastic strain is above 0): the cells' hourglass strength follows it (docs/theory.md
  /// eq. 3.10). Every material says it itself, elastic ones false: a default of false let
  /// Drucker-Prager and Mohr-Coulomb forget their flow, which the zero-energy controls then
  /// switched on and off at yield (theory §3.4, after eq. 3.10).
  virtual bool has_flowed(std::span<const double> internal) const = 0;

  /// The largest mean stress p = tr(stress)/3 the material carries [Pa] (tension positive): a
  /// stress update that ends above it is returned onto it (docs/theory.md §1.7). +infinity: no
  /// cut-off.
  virtual double tension_cutoff() const { return std::numeric_limits<double>::infinity(); }
  /// Relaxation rate of the source [1/s] (for RK sub-stepping); 0 for elastic materials.
  virtual double source_stiffness(const SymmetricTensor& stress,
                                  std::span<const double> internal) const {
    (void)stress;
    (void)internal;
    return 0.0;
  }

 protected:
  Material(double density, ElasticConstants elastic) : density_(density), elastic_(elastic) {}

 private:
  double density_;
  ElasticConstants elastic_;
};

}  // namespace rktsph
