// A rigid polygon in contact with the nodes of a moving body (docs/theory.md §9.18): it moves at an
// imposed velocity, or under an imposed load by its own equation of motion (eq. 9.17); the nodes
// of its group that reach it may not enter it, and those pressed against it move with it along its
// normal.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "rktsph/core/field_array.hpp"
#include "rktsph/core/point_cloud.hpp"
#include "rktsph/core/small_tensor.hpp"
#include "rktsph/core/time_function.hpp"
#include "rktsph/mesh/polygon_distance.hpp"

namespace rktsph {

/// How a node in contact moves along the body's surface (docs/theory.md eq. 9.14).
struct ContactSurface {
  bool rough = true;               ///< without `friction`: no slip (true) or free slip (false)
  std::optional<double> friction;  ///< Coulomb's mu; replaces `rough` when given
};

/// What moves a rigid body along each axis: an imposed velocity, or a load under which it moves by
/// its own equation of motion (eq. 9.17); an axis with neither is held.
struct BodyDrive {
  std::array<std::optional<TimeFunction>, 3> velocity;  ///< [m/s]
  std::array<std::optional<TimeFunction>, 3> load;      ///< besides the soil's [N/m]
  double mass = 0.0;                                    ///< [kg/m], > 0 when loaded
};

/// A loaded body's motion over the step in progress, [start, start + length]: on its loaded axes
/// the velocity varies linearly from `velocity` to `end_velocity` (eq. 9.17).
struct BodyMotion {
  double start = 0.0, length = 0.0;  ///< [s]
  Vec3 displacement{};               ///< from t = 0, at `start` [m]
  Vec3 velocity{}, end_velocity{};   ///< [m/s]
};

class RigidBody {
 public:
  /// `nodes` may touch it.
  RigidBody(std::string name, std::vector<Vec3> polygon, BodyDrive drive, ContactSurface surface,
            std::vector<std::int32_t> nodes);

  const std::string& name() const { return name_; }
  /// The body's velocity and its displacement from t = 0 at `time` (on a loaded axis, a time
  /// within the step in progress).
  Vec3 velocity(double time) const;
  Vec3 displacement(double time) const;
  /// True when a load moves it along some axis.
  bool loaded() const;
  /// Starts a step of `length` at `time` (eq. 9.17): along each loaded axis the velocity at its
  /// end from the load at mid-step, the weight under `gravity` [m/s2] and the soil's force
  /// `soil_force` [N/m] at its start, over the body's mass and the mass its contacts hold
  /// (`node_mass` [kg/m] per node), from which the nodes in contact cannot part along that axis.
  void begin_step(double time, double length, const Vec3& soil_force, const Vec3& gravity,
                  std::span<const double> node_mass);
  /// Ends the step begun: the displacement by the trapezoidal rule, exact for the linear velocity.
  void end_step();
  /// The state of a loaded body's motion, to carry across a forming of the cells and a restart.
  const BodyMotion& motion() const { return motion_; }
  void set_motion(const BodyMotion& motion) { motion_ = motion; }
  /// Its outline at `time`.
  std::vector<Vec3> polygon_at(double time) const;
  /// Its outline where the last find_contacts placed it.
  const std::vector<Vec3>& outline() const { return moved_polygon_; }

  /// Marks the nodes that are on or inside the body at `time` at `positions` (within
  /// `tolerance` [m]), with the outward normal of the body's nearest facet.
  void find_contacts(const PointCloud& positions, double time, double tolerance);
  /// The normal stress n.sigma.n at a row of the values, for the unit normal n.
  using NormalStress = std::function<double(std::size_t row, const Vec3& normal)>;
  /// Keeps the relative velocity of every node in contact from pointing into the body, and of a
  /// node pressed against it (normal stress < 0) from leaving it (eq. 9.14). Row of node n is n,
  /// or node_to_row[n].
  void impose(double time, std::span<const int> velocity_field, FieldArray& values,
              std::span<const std::int32_t> node_to_row, const NormalStress& normal_stress) const;

  std::size_t nodes_in_contact() const;
  /// normal[node] = the body's outward normal at each node in contact, reaction[node] the
  /// traction components (bit a: axis a) the contact holds there, and body[node] = `index`
  /// (others untouched).
  void contact_normals(std::span<Vec3> normal, std::span<std::uint8_t> reaction,
                       std::span<std::int32_t> body, std::int32_t index) const;
  /// The deepest a node of the group lay inside the body at the last find_contacts [m].
  double deepest_penetration() const { return deepest_penetration_; }

 private:
  /// `polygon` (sized as the body's) <- its outline at `time`.
  void place(double time, std::vector<Vec3>& polygon) const;

  std::string name_;
  std::vector<Vec3> polygon_;  // at t = 0
  BodyDrive drive_;
  BodyMotion motion_;
  ContactSurface surface_;
  std::vector<std::int32_t> nodes_;
  std::vector<std::uint8_t> contact_;  // per node of nodes_
  std::vector<Vec3> normal_;           // outward normal of the body at it, where in contact
  std::vector<Vec3> moved_polygon_;    // where the last find_contacts placed it
  double deepest_penetration_ = 0.0;
};

}  // namespace rktsph
