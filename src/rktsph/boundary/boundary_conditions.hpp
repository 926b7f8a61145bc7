// Boundary conditions on SPH nodes (docs/theory.md §5.1): imposed velocities, fixed nodes,
// rollers / symmetry planes (mirror images, docs/theory.md §4.5), tractions, and the natural
// traction-free condition on every face that has no other condition.
#pragma once

#include <cstdint>
#include <map>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "rktsph/case/case_description.hpp"
#include "rktsph/core/field_array.hpp"
#include "rktsph/geometry/node_sets.hpp"
#include "rktsph/physics/physics_model.hpp"
#include "rktsph/sph/operators.hpp"

namespace rktsph {

/// An outward face normal along a lattice axis.
struct FaceNormal {
  int axis = 0;
  int sign = 1;
};

class BoundaryConditions {
 public:
  /// Validates the case's conditions against the groups and the lattice (InputError at the
  /// condition's line on any inconsistency) and compiles them into per-node constraints.
  BoundaryConditions(const CaseDescription& description, const NodeSets& nodes,
                     const std::map<std::string, std::vector<std::int32_t>>& groups,
                     const PhysicsModel& model);

  /// Mirror planes of the rollers with `mirror: true`; they enter every operator.
  const std::vector<MirrorPlane>& mirror_planes() const { return mirror_planes_; }
  /// Per node, bit a set when the node lies on a mirror plane normal to axis a.
  std::span<const std::uint8_t> mirror_axes() const { return mirror_axes_; }

  /// Bit a set: node's stress increments are projected so that sigma_aa is kept (a face with
  /// normal along a whose normal velocity is not imposed; docs/theory.md eq. 5.1).
  std::uint8_t projected_axes(std::int32_t node) const { return projected_axes_[node]; }

  /// Outward normals of the faces a node lies on (lattice directions with no neighbour and no
  /// mirror image).
  const std::vector<FaceNormal>& face_normals(std::int32_t node) const {
    return face_normals_[node];
  }

  /// Imposes every constraint at time t on `values`. Row of node n is n, or node_to_row[n] when
  /// given (constraints of nodes with row -1 are skipped).
  void apply(double time, FieldArray& values, std::span<const std::int32_t> node_to_row = {}) const;

  /// Drained nodes (prescribed pore pressure) and their value at time t.
  const std::vector<std::int32_t>& drained_nodes() const { return drained_nodes_; }
  double drained_pressure(std::size_t k, double time) const {
    return functions_[static_cast<std::size_t>(drained_function_[k])](time);
  }

  /// Every (node, stress field) that a constraint overwrites (tractions, traction-free faces,
  /// roller shear), in no particular order.
  std::vector<std::pair<std::int32_t, int>> constrained_stress() const {
    std::vector<std::pair<std::int32_t, int>> pairs;
    for (const Constraint& c : stress_constraints_)
      pairs.emplace_back(c.node, c.field);
    return pairs;
  }

  /// True if velocity component `axis` of `node` is imposed.
  bool velocity_imposed(std::int32_t node, int axis) const {
    return (velocity_axes_[node] >> axis) & 1u;
  }

 private:
  struct Constraint {
    std::int32_t node;
    int field;
    int function;                     // index into functions_
    double scale;                     // value = scale * functions_[function](t)
    bool plus_pore_pressure = false;  // + alpha p_w: a traction on the total stress (§5.1)
  };
  int add_function(const TimeFunction& f);

  std::vector<MirrorPlane> mirror_planes_;
  std::vector<std::uint8_t> mirror_axes_;
  std::vector<std::vector<FaceNormal>> face_normals_;
  std::vector<std::uint8_t> velocity_axes_;
  std::vector<std::uint8_t> projected_axes_;
  std::vector<TimeFunction> functions_;
  std::vector<Constraint> pressure_constraints_;  // drained nodes, applied first
  std::vector<Constraint> stress_constraints_;
  std::vector<std::int32_t> drained_nodes_;
  std::vector<int> drained_function_;
  int pore_pressure_field_ = -1;
  double biot_coefficient_ = 0.0;
  std::vector<Constraint> velocity_constraints_;  // applied last: velocity wins
};

}  // namespace rktsph
