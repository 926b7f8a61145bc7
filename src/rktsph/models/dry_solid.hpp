// V1 "dry solid", small deformation: velocity-stress first-order system (docs/theory.md §1.2).
//   rho dv/dt = div sigma + rho b - rho xi v
//   dsigma/dt = D^e : (sym grad v - eps_dot^vp(sigma, kappa))
// for the 1D bar (uniaxial stress), plane strain (sigma_zz carried) and plane stress.
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <vector>

#include "rktsph/core/time_function.hpp"
#include "rktsph/materials/material.hpp"
#include "rktsph/materials/overstress_integrator.hpp"
#include "rktsph/physics/field_layout.hpp"
#include "rktsph/physics/kinematics/kinematics.hpp"
#include "rktsph/physics/physics_model.hpp"

namespace rktsph {

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

class DrySolid : public PhysicsModel {
 public:
  DrySolid(Kinematics kinematics, std::vector<std::unique_ptr<Material>> materials, Loads loads,
           SourceIntegration integration);

  int dimension() const override { return layout_.dimension(); }
  int field_count() const override { return layout_.field_count(); }
  const std::vector<std::string>& field_names() const override { return layout_.names(); }
  std::span<const Parity> parities() const override { return layout_.parities(); }
  int internal_count() const override { return internal_count_; }
  const std::vector<std::string>& internal_names() const override { return internal_names_; }
  int velocity_field(int axis) const override { return layout_.velocity(axis); }
  int stress_field(int i, int j) const override { return layout_.stress(i, j); }
  int pore_pressure_field() const override { return layout_.pore_pressure(); }
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
  double elastic_energy_density(std::int32_t material, const FieldArray& values,
                                std::size_t i) const override;
  std::array<double, 3> body_force(double time) const override { return loads_.body_force(time); }
  double damping(double time) const override { return loads_.damping_at(time); }

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
  const FieldLayout& layout() const { return layout_; }
  /// The elastic stiffness of material m on the carried stress components (the kinematics'
  /// order, engineering shear strains).
  const StiffnessMatrix& stiffness(std::int32_t material) const {
    return stiffness_[static_cast<std::size_t>(material)];
  }
  const Material& material(std::int32_t index) const override { return *materials_[index]; }
  std::size_t material_count() const override { return materials_.size(); }
  const Loads& loads() const { return loads_; }

 protected:
  /// `pore_pressure`: the layout carries a pore pressure after the stresses (SaturatedVpw).
  DrySolid(Kinematics kinematics, std::vector<std::unique_ptr<Material>> materials, Loads loads,
           SourceIntegration integration, bool pore_pressure);

  /// The internal variables that scale the body force point by point (a water table, docs/theory.md
  /// eq. 6.8): b_i = (b_x + s_i b_y, w_i b_y) in 2D, w_i b_x in 1D, with w the internal variable
  /// `weight` and s the one after it (2D). -1: the body force is the same at every point.
  void set_body_force_weights(int weight) { body_force_weight_ = weight; }

 private:
  static constexpr int kMaxStress = KinematicAssumption::kMaxStress;

  /// flux_rate with the dimension and the number of stress components fixed at compile time and
  /// every field's array looked up once: the hot loop of the common settings.
  template <int Dimension, int StressCount>
  void flux_rate_fixed(std::span<const std::int32_t> material, const FieldArray& gradient,
                       FieldArray& rate) const;
  /// The body force and damping at the start, middle and end of one sub-step of the velocity.
  struct SubstepLoads {
    std::array<Vec3, 3> body;
    std::array<double, 3> damping;
  };
  /// Scratch of advance_velocities: the loads of each sub-step, evaluated once per call (it only
  /// grows, up to the largest sub-step count used; advance is not called concurrently).
  mutable std::vector<SubstepLoads> substep_loads_;
  /// The velocity part of advance(), points [0, n) of `values`.
  void advance_velocities(std::int64_t n, const FieldArray& rate, double time, double interval,
                          FieldArray& values, const FieldArray& internal) const;
  /// Its loop with the body force weighted point by point (set_body_force_weights).
  void advance_weighted_velocities(std::int64_t n, const FieldArray& rate, double delta,
                                   int substeps, double interval, FieldArray& values,
                                   const FieldArray& internal) const;
  // n (x) n as an engineering strain on the carried components.
  void normal_strain(const std::array<double, 3>& normal, double* strain) const;
  // Engineering strain rate of every carried component at point i (docs/theory.md eq. 1.4).
  void strain_rate(const FieldArray& gradient, std::int64_t i, double* strain_rate) const;

  // The gradient fields whose sum is the engineering strain rate of a carried component.
  struct StrainRateGradients {
    int count = 0;
    std::array<int, 2> field{};
  };

  Kinematics kinematics_;
  FieldLayout layout_;
  std::vector<std::unique_ptr<Material>> materials_;
  Loads loads_;
  SourceIntegration integration_;
  std::vector<std::string> internal_names_;
  int internal_count_ = 0;  // of the materials; a derived model may carry more after them
  int body_force_weight_ = -1;
  std::vector<StiffnessMatrix> stiffness_;   // of each material
  std::vector<StiffnessMatrix> compliance_;  // its inverse
  // The stress update of each material (the source, its sub-steps and the tension cut-off): the
  // material integrates its own stress, the model only gathers and scatters the fields.
  std::vector<OverstressIntegrator> integrators_;
  // Tables of the kinematics, read once so that the point loops only index arrays.
  // The SymmetricTensor slot and the shear factor (gamma = 2 eps) of each carried component.
  CarriedStress carried_;
  std::array<StrainRateGradients, kMaxStress> strain_rate_gradients_{};
  std::array<std::array<int, 3>, 3> divergence_gradients_{};  // d sigma_ab / dx_b of axis a
};

}  // namespace rktsph
