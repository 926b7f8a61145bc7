// The seam between the one RK-TSPH step and the physics it advances (docs/theory.md §2).
//
// A physics model says which fields it carries (and their mirror parities), turns gradients into
// the flux rate R(grad Phi), and advances values over a time interval with the flux rate frozen
// (y' = R + S(y, kappa, t), docs/theory.md §2.8). V1 (dry solid), V2 (dry solid with Jaumann
// terms and moving nodes) and V3 (saturated, plus a pressure projection) differ only here.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "rktsph/core/field_array.hpp"
#include "rktsph/materials/material.hpp"
#include "rktsph/physics/surface_normals.hpp"
#include "rktsph/physics/water_table.hpp"
#include "rktsph/sph/operators.hpp"

namespace rktsph {

/// Which unknowns PhysicsModel::advance advances.
enum class AdvancedFields { All, Velocity, Others };

class PhysicsModel {
 public:
  virtual ~PhysicsModel() = default;

  virtual int dimension() const = 0;
  /// Number of unknowns per point (velocity components, stress components, ...).
  virtual int field_count() const = 0;
  /// Names of the unknowns, e.g. "velocity_x", "stress_xy" (also the probe field names).
  virtual const std::vector<std::string>& field_names() const = 0;
  /// Mirror parity of each unknown.
  virtual std::span<const Parity> parities() const = 0;
  /// Number of internal variables carried per SPH node.
  virtual int internal_count() const = 0;
  virtual const std::vector<std::string>& internal_names() const = 0;

  /// Index of velocity component `axis` among the unknowns.
  virtual int velocity_field(int axis) const = 0;
  /// Index of stress component (i, j) among the unknowns, or -1 if it is not carried.
  virtual int stress_field(int i, int j) const = 0;

  /// True for the unknowns whose gradient enters the flux rate only through the momentum balance
  /// (stress, pore pressure); the velocity's gradient drives the constitutive rates instead. The
  /// step closes the two kinds differently at incomplete nodes (docs/theory.md §5.3).
  virtual bool feeds_momentum_only(int field) const {
    for (int a = 0; a < dimension(); ++a)
      if (velocity_field(a) == field) return false;
    return true;
  }

  /// Index of the pore pressure among the unknowns, or -1 for a dry model.
  virtual int pore_pressure_field() const { return -1; }
  /// Biot coefficient alpha of the saturated model (0 for a dry one): total stress
  /// sigma = sigma' - alpha p_w I.
  virtual double biot_coefficient() const { return 0.0; }
  /// The water table of the pore pressure (docs/theory.md §6.8), or nullptr: with one the carried
  /// field is the excess over the hydrostatic p_h, and p_w = p_h + the field.
  virtual const WaterTable* water_table() const { return nullptr; }
  bool has_water_table() const { return water_table() != nullptr; }
  /// p_h [Pa] at SPH node `node` and time `time` (eq. 6.6); 0 without a water table.
  virtual double hydrostatic_pore_pressure(std::size_t node, double time) const {
    (void)node, (void)time;
    return 0.0;
  }

  /// Largest wave speed of the model [m/s] (the drained P-wave speed), for the Courant rule.
  virtual double max_wave_speed() const = 0;

  /// Number of materials, and material m (in the order of the case's material names).
  virtual std::size_t material_count() const = 0;
  virtual const Material& material(std::int32_t material) const = 0;
  /// P-wave speed of material m [m/s] (drained), with the modulus of the model's kinematics.
  virtual double wave_speed(std::int32_t material) const = 0;

  /// True if material m is elastic (never flows).
  virtual bool elastic(std::int32_t material) const = 0;
  /// Mass density of material m [kg/m3] (the mixture density in the saturated model).
  virtual double density(std::int32_t material) const = 0;
  /// In-plane elastic moduli of material m [Pa] (drained): {M', lambda', G} with
  /// sigma_aa = M' eps_aa + lambda' eps_bb (a != b in the plane) and sigma_ab = 2G eps_ab;
  /// M' = lambda + 2G, lambda' = lambda in plane strain, M' = E/(1 - nu^2), lambda' = nu M' in
  /// plane stress. The scale of the zero-energy controls (docs/theory.md §3.4).
  virtual std::array<double, 3> in_plane_moduli(std::int32_t material) const = 0;

  /// Complementary elastic energy density 1/2 sigma : C^-1 : sigma of point i of `values`
  /// [J/m3], with the elastic compliance of the model's kinematics on the carried stress (the
  /// effective stress in the saturated model; sigma^2 / (2E) in the 1D bar).
  virtual double elastic_energy_density(std::int32_t material, const FieldArray& values,
                                        std::size_t i) const = 0;

  /// The loads of the momentum balance rho dv/dt = div sigma + rho b - rho xi v: the body force
  /// per unit mass b(t) [m/s2] and the mass-damping coefficient xi(t) [1/s].
  virtual std::array<double, 3> body_force(double time) const = 0;
  virtual double damping(double time) const = 0;

  /// Magnitude beyond which field f can only come from a diverging run (a strain of order 10);
  /// the loop stops there, while the output is still finite.
  virtual double divergence_bound(int field) const = 0;

  /// Flux rate R at each point from the gradients (field f along axis c at f * dimension + c).
  /// `material[i]` is the material of point i; rate has field_count() fields.
  virtual void flux_rate(std::span<const std::int32_t> material, const FieldArray& gradient,
                         FieldArray& rate) const = 0;

  /// Advances `values` and `internal` of points [0, material.size()) from `time` over `interval`
  /// with the flux rate frozen: y' = rate + S(y, kappa, t).
  /// `part` restricts the advance to the velocity, or to every other field and the internal
  /// variables (the mean-velocity stress update advances them apart, docs/theory.md eq. 2.5).
  virtual void advance(std::span<const std::int32_t> material, const FieldArray& rate, double time,
                       double interval, FieldArray& values, FieldArray& internal,
                       AdvancedFields part = AdvancedFields::All) const = 0;

  /// Makes the stress increment of point i (now `values`, before `start`) traction-free on the
  /// surfaces of unit normals `normals` (docs/theory.md §5.1): a normal strain along each normal
  /// is added so that every sigma_nn keeps its start value, and every carried stress component
  /// moves by the elastic stiffness times that strain.
  virtual void project_traction_free_increment(std::int32_t material, const SurfaceNormals& normals,
                                               std::span<const double> start, FieldArray& values,
                                               std::size_t i) const = 0;

  /// True for a model on the moving configuration (V2): its stress rate is objective, so the step
  /// rotates the stress with the spin before each advance (rotate_stress), and its momentum
  /// balance uses the current density.
  virtual bool objective_stress_rate() const { return false; }

  /// Rotates the carried stress of points [0, count) of `values` by the incremental rotation of
  /// the spin skw(grad v) over `interval` (docs/theory.md eq. 9.2), the corotational part of the
  /// Jaumann rate. The field of `gradient` holding dv_a/dx_c is velocity_gradient[a * d + c].
  /// Nothing for a small-deformation model.
  virtual void rotate_stress(const FieldArray& gradient, std::span<const int> velocity_gradient,
                             double interval, std::size_t count, FieldArray& values) const {
    (void)gradient, (void)velocity_gradient, (void)interval, (void)count, (void)values;
  }

  /// Adds the artificial viscous stress q = alpha rho c_p dx sym(grad v) (docs/theory.md §2.7) to
  /// the half-step stresses of points [0, material.size()), which feed only the momentum corrector.
  virtual void add_artificial_viscosity(std::span<const std::int32_t> material,
                                        const FieldArray& gradient, double alpha_dx,
                                        FieldArray& values) const = 0;

  /// flowing[i] = 1 where the material of point i is in viscoplastic flow at `values` and
  /// `internal`, 2 where it is not but has flowed before (Material::has_flowed), 0 elsewhere
  /// (elastic materials).
  virtual void flowing(std::span<const std::int32_t> material, const FieldArray& values,
                       const FieldArray& internal, std::span<std::uint8_t> flowing) const {
    (void)material, (void)values, (void)internal;
    std::fill(flowing.begin(), flowing.end(), std::uint8_t{0});
  }

  /// The carried stress components of point i of `values` as a 3D tensor (zeros where not
  /// carried; the effective stress in the saturated model).
  SymmetricTensor stress_tensor(const FieldArray& values, std::size_t i) const {
    // Slots of SymmetricTensor: xx, yy, zz, xy, yz, zx.
    constexpr int kRow[6] = {0, 1, 2, 0, 1, 2}, kColumn[6] = {0, 1, 2, 1, 2, 0};
    SymmetricTensor sigma{};
    for (std::size_t slot = 0; slot < 6; ++slot)
      if (const int f = stress_field(kRow[slot], kColumn[slot]); f >= 0) sigma[slot] = values(f, i);
    return sigma;
  }

  /// Initial internal variables of point i.
  virtual void initial_internal(std::int32_t material, FieldArray& internal,
                                std::size_t i) const = 0;
};

}  // namespace rktsph
