// Stiffness of the strain hourglass modes of nodal stress storage (docs/theory.md §3.4, eqs.
// 3.5-3.8).
//
// The stress lives on the SPH nodes and reaches the stress points by interpolation, so at rest the
// stress points see the strain only through S = I A (A: the lumped average of the stress points'
// strains at a node, I: the node -> stress point interpolation), and the static stiffness of the
// step is G^T W D S G instead of the one-point G^T W D G. S removes the strain patterns that
// alternate from cell to cell, so such a displacement costs no energy, and a load with a kink
// drives it for ever under damping. At a node whose stress components are imposed (a loaded or
// free face, a roller) the nodal stress does not see those strain components at all: there the
// strain the stress "received" is the one consistent with the imposed stress (eq. 3.8), so that
// the modes of a face are controlled too. The control adds the energy
//   E_s = (epsilon_s / 2) sum_P V_P r_P : D : r_P,   r = sym(G u) - I P(e)                 (3.5)
// with e the strain the nodal stress received (the integral of the nodal velocity gradient, which
// in the interior is A G u up to the Lax-Wendroff terms) and P the identity except at constrained
// nodes (eq. 3.8). Its force is the momentum closure applied to the stress-point stress
//   tau~ = tau - I P*(A tau),   tau = epsilon_s D : r                                     (3.6)
// (A is the volume-weighted adjoint of I, P* the transpose of P's linear part: the second term is
// the force through e's dependence on the motion, and the step stays stable up to eq. 3.7).
//
// The patch form (eqs. 3.12-3.13, the default on triangles) measures each cell's strain against
// the first-order fits of its corners' patches of cells (PatchFit) instead: the soft modes of the
// nodal strain average on triangles, whose strains the patch fits do not explain, get the stiffness
// beta D, and fields linear in space none. A fit's residual is orthogonal to what it fits, so
// tau = beta D : r is the gradient of that energy as it stands (no second term as in eq. 3.6).
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "rktsph/core/field_array.hpp"
#include "rktsph/geometry/node_sets.hpp"
#include "rktsph/sph/adjoint_operator.hpp"
#include "rktsph/sph/operators.hpp"
#include "rktsph/stabilisation/patch_fit.hpp"

namespace rktsph {

class PhysicsModel;

/// What the strain of a stress point is measured against (docs/theory.md §3.4): the strain the
/// nodal stress received (eqs. 3.5-3.8, for the lattice's strain modes), or the mean of its
/// corners' patches (eq. 3.12, the soft modes of the nodal strain average on triangles).
enum class StrainControl { Received, Patch };

/// r_P of eq. 3.14: the fraction of beta that the patch form keeps in cells of viscoplastic
/// materials around flow, present or past (docs/theory.md §3.4; psi times it where a cell flows).
inline constexpr double kPatchNearFlowFraction = 0.05;

class StrainHourglassStiffness {
 public:
  StrainHourglassStiffness() = default;
  /// `to_points` is the stress points' table (interpolation and gradient from the nodes), with
  /// `point_volume` the stress points' volumes; `mirror_axes[n]` has bit a set when node n lies on
  /// a mirror plane normal to a (one entry per node); `constrained` lists the (node, stress field)
  /// pairs the boundary conditions overwrite; `node_material` the nodes' materials; `epsilon` = 0
  /// makes the control inactive. Two-dimensional models only.
  StrainHourglassStiffness(const PhysicsModel& model, const WeightTable& to_points,
                           std::span<const double> point_volume,
                           std::span<const std::uint8_t> mirror_axes,
                           std::span<const std::pair<std::int32_t, int>> constrained,
                           std::span<const std::int32_t> node_material, const NodeSets& nodes,
                           double epsilon, StrainControl form = StrainControl::Received);

  bool active() const { return epsilon_ > 0.0; }
  /// The received form integrates e, the strain the nodal stress received (State::strain).
  bool needs_received_strain() const { return active() && form_ == StrainControl::Received; }

  /// The imposed stresses at t = 0 (the state after its conditions), against which eq. 3.8
  /// measures the imposed stress increments.
  void set_reference(const FieldArray& fields);

  /// Adds tau~ of eq. 3.6 (the patch form: tau of eq. 3.12 times factor_P, eq. 3.14) to the
  /// in-plane stress fields of `point_values` (the stress points' half-step values).
  /// `displacement` is u^{n+1/2} on the nodes (one field per axis), `fields` the nodal state (its
  /// imposed stresses enter eq. 3.8); `factor` is one per stress point, or empty for 1 everywhere.
  void add_stress(const PhysicsModel& model, const WeightTable& to_points,
                  std::span<const std::int32_t> point_material, const FieldArray& displacement,
                  const FieldArray& strain, const FieldArray& point_gradient, double dt,
                  const FieldArray& fields, std::span<const double> factor,
                  FieldArray& point_values);

  /// e += dt sym(grad v) with the nodal velocity gradient the nodal stress is updated with (the
  /// velocity slots of the model's step-2 gradient `node_gradient`); e has fields xx, yy, xy.
  void integrate_strain(const PhysicsModel& model, const FieldArray& node_gradient, double dt,
                        FieldArray& strain) const;

 private:
  struct ConstrainedNode {
    std::int32_t node = 0;
    std::array<bool, 3> imposed{};      // xx, yy, xy
    std::array<double, 3> reference{};  // their imposed values at t = 0
    std::array<double, 3> moduli{};     // M', lambda', G
  };
  // node_strain_ <- A x, zero where x is odd across a mirror plane the node lies on.
  void average_to_nodes(const FieldArray& x);
  // x <- x - I P*(A x) (eq. 3.6).
  void remove_received_stress(const WeightTable& to_points, FieldArray& x);
  void apply_face_rule(const ConstrainedNode& rule, const FieldArray* fields, bool transpose);
  // strain_ <- sym of the 2 x 2 gradient whose xx, xy, yx, yy entries are the fields `slot`.
  void symmetric_part(const FieldArray& gradient, const std::array<int, 4>& slot);
  // strain_ <- strain_ - I node_strain_.
  void subtract_interpolated_node_strain(const WeightTable& to_points);
  // strain_ <- epsilon D : strain_ with each stress point's elastic moduli.
  void elastic_stress_of_strain(const PhysicsModel& model, std::span<const std::int32_t> material);
  // The model's stress fields of point_values += strain_.
  void add_to(FieldArray& point_values) const;
  void add_patch_stress(const PhysicsModel& model, const WeightTable& to_points,
                        std::span<const std::int32_t> point_material,
                        const FieldArray& displacement, std::span<const double> factor,
                        FieldArray& point_values);

  double epsilon_ = 0.0;
  StrainControl form_ = StrainControl::Received;
  PatchFit patch_fit_;                 // the patch form's fits (eq. 3.13)
  AdjointOperator node_average_;       // A: b_Pn = V_P w_Pn / V_n over every node
  std::array<int, 3> stress_field_{};  // the model's xx, yy, xy fields
  std::vector<Parity> displacement_parity_;
  std::array<Parity, 3> strain_parity_{};
  std::array<std::uint8_t, 3> every_{1, 1, 1};
  std::vector<std::int32_t> mirror_nodes_;
  std::vector<std::uint8_t> mirror_bits_;
  std::vector<ConstrainedNode> constrained_;
  // Scratch, allocated once.
  FieldArray gradient_;        // G u at the stress points, a * 2 + c
  FieldArray strain_;          // r, then tau, then tau~ (xx, yy, xy) at the stress points
  FieldArray node_strain_;     // A of it (then P or P*)
  FieldArray point_strain_;    // I of that
  FieldArray model_gradient_;  // the model's gradient layout, velocity slots = epsilon r
  FieldArray rate_;            // the model's rate: D : r in the stress fields
};

}  // namespace rktsph
