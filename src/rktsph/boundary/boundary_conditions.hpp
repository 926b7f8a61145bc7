// Boundary conditions on SPH nodes (docs/theory.md §5.1): imposed velocities, fixed nodes,
// rollers / symmetry planes (mirror images, docs/theory.md §4.5), tractions, and the natural
// traction-free condition on every surface facet, of any unit normal (eq. 5.1a).
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "rktsph/boundary/perimeter_normals.hpp"
#include "rktsph/boundary/rigid_body.hpp"
#include "rktsph/boundary/surface_set.hpp"
#include "rktsph/boundary/surface_traction.hpp"
#include "rktsph/case/case_description.hpp"
#include "rktsph/core/checkpoint.hpp"
#include "rktsph/core/field_array.hpp"
#include "rktsph/geometry/node_sets.hpp"
#include "rktsph/physics/physics_model.hpp"
#include "rktsph/sph/operators.hpp"

namespace rktsph {

/// The boundary conditions of a case, compiled once from its `boundary_conditions` (docs/theory.md
/// §5.1): imposed velocities, fixed nodes, rollers and their mirror planes, drained pore pressure
/// and imposed tractions as functions of time. They act on a surface set (surface()): the faces of
/// the outline of the body's cells (docs/theory.md §3.5), built here once and turned with a moving
/// body (follow_configuration).
class BoundaryConditions {
 public:
  /// Validates the case's conditions against the groups and the cells (InputError at the
  /// condition's line on any inconsistency) and compiles them into per-node constraints. `time`
  /// is the time of the nodes' positions (the rigid bodies' contacts are found there).
  BoundaryConditions(std::span<const BoundaryConditionSpec> conditions, const NodeSets& nodes,
                     const std::map<std::string, std::vector<std::int32_t>>& groups,
                     const PhysicsModel& model, double time = 0.0);

  /// Mirror planes of the rollers with `mirror: true`; they enter every operator.
  const std::vector<MirrorPlane>& mirror_planes() const { return mirror_planes_; }
  /// Per node, bit a set when the node lies on a mirror plane normal to axis a.
  std::span<const std::uint8_t> mirror_axes() const { return mirror_axes_; }

  /// The surface nodes, their outward unit normals, which facets are projected traction-free and
  /// which traction components are reactions to imposed velocities.
  const SurfaceSet& surface() const { return surface_; }
  /// Takes `surface` (normals only; its flags are recomputed) as the surface the conditions act on
  /// from now on. Reuses the buffers: no allocation when the size does not grow.
  void replace_surface(const SurfaceSet& surface);
  /// Turns every facet of the surface to the outward normal of the body's perimeter on the moving
  /// configuration `nodes` (docs/theory.md §9.7); the facets, and which of them velocity
  /// conditions act on, stay those of the reference configuration.
  void follow_configuration(const PointCloud& nodes, double time);

  /// Imposes every constraint at time t on `values`. Row of node n is n, or node_to_row[n] when
  /// given (constraints of nodes with row -1 are skipped). Applied to the nodes' own rows, the
  /// rigid bodies' contacts measure the impulse they take from the nodes (RigidBody::force).
  void apply(double time, FieldArray& values, std::span<const std::int32_t> node_to_row = {}) const;

  /// Drained nodes (prescribed pore pressure) and their value at time t.
  const std::vector<std::int32_t>& drained_nodes() const { return drained_nodes_; }
  double drained_pressure(std::size_t k, double time) const {
    return functions_[static_cast<std::size_t>(drained_function_[k])](time);
  }

  /// Every (node, stress field) that a constraint overwrites (tractions, traction-free faces,
  /// roller shear), in no particular order.
  std::vector<std::pair<std::int32_t, int>> constrained_stress() const;

  /// Nodes in contact with a rigid wall after the last update (docs/theory.md §9.13).
  std::size_t nodes_in_contact() const;
  /// The deepest penetration of a rigid wall by a node of its group after the last update [m].
  double deepest_penetration() const { return deepest_penetration_; }

  /// The rigid bodies of `rigid_body` conditions, in the order written (docs/theory.md §9.18).
  const std::vector<RigidBody>& rigid_bodies() const { return bodies_; }
  /// The force the soil exerts on rigid body b at the last time the conditions were applied to
  /// the nodes' own rows [N per m of thickness] (docs/theory.md eq. 9.15).
  const Vec3& rigid_body_force(std::size_t b) const { return body_force_[b]; }

  /// Starts and ends a step of `length` at `time` for the loaded bodies (eq. 9.17): their
  /// acceleration over it from the soil's force measured at its start and `gravity` [m/s2].
  void begin_body_step(double time, double length, const Vec3& gravity);
  void end_body_step();
  /// Takes the loaded bodies' motions and forces of the conditions these replace (a forming of
  /// the cells), and finds the contacts at `time` where the bodies then are.
  void carry_bodies(const BoundaryConditions& earlier, double time);
  /// The bodies' motions and forces, for a restart (the contacts follow at the next move).
  void save_bodies(CheckpointOut& out) const;
  void restore_bodies(CheckpointIn& in);

  /// True if velocity component `axis` of `node` is imposed.
  bool velocity_imposed(std::int32_t node, int axis) const {
    return (velocity_axes_[node] >> axis) & 1u;
  }

 private:
  struct Constraint {
    std::int32_t node;
    int field;
    int function;  // index into functions_
    double scale;  // value = scale * functions_[function](t)
  };
  /// A traction condition's load on one node: sigma·n = share t(t) on the face of normal
  /// `normal`, share the part of the node's face that the loaded facets make up.
  struct ImposedTraction {
    std::int32_t node;
    Vec3 normal;
    std::array<int, 3> function;  // per global component, index into functions_; -1: not given
    double share;
  };
  /// A fixed plane its group's nodes may reach but not cross (docs/theory.md §9.13).
  struct RigidWall {
    Vec3 point{}, normal{};  // normal: unit, into the body
    bool rough = true;
    std::vector<std::int32_t> nodes;
    std::vector<std::uint8_t> contact;  // per node of `nodes`: on or beyond the plane
  };
  int add_function(const TimeFunction& f);
  /// Marks the nodes of every wall's group that are on or beyond its plane at `positions`.
  void update_contacts(const PointCloud& positions, double time);
  /// Facets of nodes in contact with a body, facing it, are not projected traction-free.
  void release_contact_facets(const PointCloud& positions);
  /// A node's share of the face of the body it touches [m] (eq. 9.15).
  double contact_share(std::size_t node, const PointCloud& positions) const;
  void measure_body_forces(const FieldArray& values) const;
  void impose_contacts(FieldArray& values, std::span<const std::int32_t> node_to_row) const;
  /// Marks the facets that velocity conditions act on: their imposed components are reactions,
  /// and a facet whose normal velocity is imposed is not projected.
  void classify(SurfaceSet& surface) const;
  bool driven(std::int32_t node, const Vec3& normal) const;
  StressTensor stress_at(const FieldArray& values, std::size_t row) const;
  void store_stress(const StressTensor& sigma, FieldArray& values, std::size_t row) const;
  std::optional<double> biot_pore_pressure(const FieldArray& values, std::size_t row) const;
  void append_overwritten(std::int32_t node, const Vec3& normal, std::uint8_t components,
                          std::vector<std::pair<std::int32_t, int>>& pairs) const;

  int dimension_ = 1;
  std::array<std::array<int, 3>, 3> stress_field_{};  // model field of sigma_ac, or -1
  std::vector<MirrorPlane> mirror_planes_;
  std::vector<std::uint8_t> mirror_axes_;
  std::vector<std::uint8_t> velocity_axes_;
  std::vector<std::vector<Vec3>> driven_normals_;  // per node: faces of its velocity conditions
  SurfaceSet surface_;
  std::optional<PerimeterNormals> perimeter_;  // of the reference surface, built on first use
  const NodeSets& nodes_;
  std::vector<TimeFunction> functions_;
  std::vector<Constraint> pressure_constraints_;  // drained nodes, applied first
  std::vector<Constraint> roller_shear_;          // after the traction-free facets
  std::vector<ImposedTraction> tractions_;        // then the loads, in the order written
  std::vector<std::int32_t> drained_nodes_;
  std::vector<int> drained_function_;
  int pore_pressure_field_ = -1;
  double biot_coefficient_ = 0.0;
  std::vector<Constraint> velocity_constraints_;    // then the velocities
  std::vector<RigidWall> walls_;                    // and last the contacts
  std::vector<RigidBody> bodies_;                   // with the walls' and the bodies'
  std::vector<std::uint8_t> classified_projected_;  // surface_.projected without the contacts
  std::vector<std::uint8_t> classified_reactions_;  // surface_.reactions without the contacts
  std::vector<Vec3> contact_normal_;                // per node: a body's normal at it, or 0
  std::vector<std::uint8_t> contact_reaction_;      // per node: the traction components it holds
  std::vector<std::int32_t> contact_body_;          // per node: the body it touches, or -1
  std::vector<double> contact_length_;              // per node: its share of a body's face [m]
  mutable std::vector<Vec3> body_force_;            // per body, measured by apply
  std::vector<double> node_mass_;                   // per node [kg/m], with a loaded body
  std::array<int, 3> velocity_field_{-1, -1, -1};
  double contact_tolerance_ = 0.0;  // [m]: a node this close to a wall touches it
  double deepest_penetration_ = 0.0;
};

}  // namespace rktsph
