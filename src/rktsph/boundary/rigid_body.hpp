// A rigid polygon in contact with the nodes of a moving body (docs/theory.md §9.18): it moves at an
// imposed velocity; the nodes of its group that reach it may not enter it, and those pressed
// against it move with it along its normal.
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

class RigidBody {
 public:
  /// `nodes` may touch it.
  RigidBody(std::string name, std::vector<Vec3> polygon,
            std::array<std::optional<TimeFunction>, 3> velocity, ContactSurface surface,
            std::vector<std::int32_t> nodes);

  const std::string& name() const { return name_; }
  /// The body's velocity and its displacement from t = 0 at `time`.
  Vec3 velocity(double time) const;
  Vec3 displacement(double time) const;
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
  std::array<std::optional<TimeFunction>, 3> velocity_;
  ContactSurface surface_;
  std::vector<std::int32_t> nodes_;
  std::vector<std::uint8_t> contact_;  // per node of nodes_
  std::vector<Vec3> normal_;           // outward normal of the body at it, where in contact
  std::vector<Vec3> moved_polygon_;    // where the last find_contacts placed it
  double deepest_penetration_ = 0.0;
};

}  // namespace rktsph
