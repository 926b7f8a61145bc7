// V1 "dry solid", small deformation: velocity-stress first-order system (docs/theory.md §1.2).
//   rho dv/dt = div sigma + rho b - rho xi v
//   dsigma/dt = D^e : (sym grad v - eps_dot^vp(sigma, kappa))
// for the 1D bar (uniaxial stress), plane strain (sigma_zz carried) and plane stress.
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <vector>

#include "rktsph/case/case_description.hpp"
#include "rktsph/materials/material.hpp"
#include "rktsph/physics/physics_model.hpp"

namespace rktsph {

enum class Kinematics { Bar1D, PlaneStrain, PlaneStress };

/// Body force and mass damping, evaluated in time (docs/theory.md §1.2, eq. 1.1).
struct Loads {
  Vec3 gravity{};
  TimeFunction gravity_factor = TimeFunction::constant(1.0);
  double damping = 0.0;  // xi [1/s]
  double damping_start = 0.0;
  double damping_end = 1e300;

  Vec3 body_force(double t) const;
  double damping_at(double t) const;
};

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

class DrySolid : public PhysicsModel {
 public:
  DrySolid(Kinematics kinematics, std::vector<std::unique_ptr<Material>> materials, Loads loads,
           SourceIntegration integration);

  int dimension() const override { return kinematics_ == Kinematics::Bar1D ? 1 : 2; }
  int field_count() const override { return static_cast<int>(names_.size()); }
  const std::vector<std::string>& field_names() const override { return names_; }
  std::span<const Parity> parities() const override { return parities_; }
  int internal_count() const override { return internal_count_; }
  const std::vector<std::string>& internal_names() const override { return internal_names_; }
  int velocity_field(int axis) const override { return axis < dimension() ? axis : -1; }
  int stress_field(int i, int j) const override;
  double max_wave_speed() const override;
  /// c_p of one material: sqrt(modulus / density) with the modulus of the kinematics.
  double wave_speed(std::int32_t material) const override;
  bool elastic(std::int32_t material) const override {
    return materials_[static_cast<std::size_t>(material)]->is_elastic();
  }
  double density(std::int32_t material) const override {
    return materials_[static_cast<std::size_t>(material)]->density();
  }
  std::array<double, 3> in_plane_moduli(std::int32_t material) const override;
  double divergence_bound(int field) const override;

  void flux_rate(std::span<const std::int32_t> material, const FieldArray& gradient,
                 FieldArray& rate) const override;
  void advance(std::span<const std::int32_t> material, const FieldArray& rate, double time,
               double interval, FieldArray& values, FieldArray& internal,
               AdvancedFields part = AdvancedFields::All) const override;
  void project_traction_free_increment(std::int32_t material, const SurfaceNormals& normals,
                                       std::span<const double> start, FieldArray& values,
                                       std::size_t i) const override;
  void add_artificial_viscosity(std::span<const std::int32_t> material, const FieldArray& gradient,
                                double alpha_dx, FieldArray& values) const override;
  void initial_internal(std::int32_t material, FieldArray& internal, std::size_t i) const override;
  void flowing(std::span<const std::int32_t> material, const FieldArray& values,
               const FieldArray& internal, std::span<std::uint8_t> flowing) const override;

  Kinematics kinematics() const { return kinematics_; }
  const Material& material(std::int32_t index) const override { return *materials_[index]; }
  std::size_t material_count() const override { return materials_.size(); }
  const Loads& loads() const { return loads_; }

 private:
  void advance_velocity(double rate_v[3], double time, double interval, double v[3]) const;
  void advance_stress(const Material& material, const double* rate_sigma, double time,
                      double interval, double* sigma, double* kappa) const;
  // Stress source -D^e : eps_dot^vp in the carried components.
  void stress_source(const Material& material, const double* sigma, const double* kappa,
                     double* sigma_rate, double* kappa_rate) const;

  Kinematics kinematics_;
  std::vector<std::unique_ptr<Material>> materials_;
  Loads loads_;
  SourceIntegration integration_;
  std::vector<std::string> names_;
  std::vector<Parity> parities_;
  std::vector<std::string> internal_names_;
  int internal_count_ = 0;
  int stress_count_ = 0;
  std::array<int, 4> stress_slot_{};  // SymmetricTensor slot of each carried stress component
};

}  // namespace rktsph
