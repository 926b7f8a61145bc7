#include "rktsph/boundary/rigid_body.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace rktsph {

RigidBody::RigidBody(std::string name, std::vector<Vec3> polygon,
                     std::array<std::optional<TimeFunction>, 3> velocity, ContactSurface surface,
                     std::vector<std::int32_t> nodes)
    : name_(std::move(name)),
      polygon_(std::move(polygon)),
      velocity_(std::move(velocity)),
      surface_(surface),
      nodes_(std::move(nodes)),
      contact_(nodes_.size(), 0),
      normal_(nodes_.size(), Vec3{}),
      moved_polygon_(polygon_) {}

Vec3 RigidBody::velocity(double time) const {
  Vec3 v{};
  for (std::size_t a = 0; a < 3; ++a)
    if (velocity_[a]) v[a] = (*velocity_[a])(time);
  return v;
}

Vec3 RigidBody::displacement(double time) const {
  Vec3 u{};
  for (std::size_t a = 0; a < 3; ++a)
    if (velocity_[a]) u[a] = velocity_[a]->integral(time);
  return u;
}

void RigidBody::place(double time, std::vector<Vec3>& polygon) const {
  const Vec3 offset = displacement(time);
  for (std::size_t k = 0; k < polygon_.size(); ++k)
    for (std::size_t a = 0; a < 2; ++a)
      polygon[k][a] = polygon_[k][a] + offset[a];
}

std::vector<Vec3> RigidBody::polygon_at(double time) const {
  std::vector<Vec3> moved = polygon_;
  place(time, moved);
  return moved;
}

void RigidBody::find_contacts(const PointCloud& positions, double time, double tolerance) {
  place(time, moved_polygon_);
  deepest_penetration_ = 0.0;
  for (std::size_t k = 0; k < nodes_.size(); ++k) {
    const auto node = static_cast<std::size_t>(nodes_[k]);
    const PolygonDistance where =
        polygon_distance(moved_polygon_, positions.position[0][node], positions.position[1][node]);
    contact_[k] = where.depth >= -tolerance ? 1 : 0;
    normal_[k] = where.normal;
    deepest_penetration_ = std::max(deepest_penetration_, where.depth);
  }
}

void RigidBody::impose(double time, std::span<const int> velocity_field, FieldArray& values,
                       std::span<const std::int32_t> node_to_row,
                       const NormalStress& normal_stress) const {
  // Eq. 9.14: with w = v - V the node's velocity relative to the body and n the body's outward
  // normal, the normal part of w may point away from the body but not into it; the correction
  // dn = max(-w.n, 0) is the normal impulse per unit mass, and the tangential part of w is kept
  // (smooth), removed (rough), or reduced by at most mu dn (Coulomb).
  const Vec3 body = velocity(time);
  for (std::size_t k = 0; k < nodes_.size(); ++k) {
    if (!contact_[k]) continue;
    const std::int32_t node = nodes_[k];
    const std::int32_t row =
        node_to_row.empty() ? node : node_to_row[static_cast<std::size_t>(node)];
    if (row < 0) continue;
    const auto r = static_cast<std::size_t>(row);
    const Vec3& n = normal_[k];
    Vec3 w{};
    for (std::size_t a = 0; a < 2; ++a)
      w[a] = values(velocity_field[a], r) - body[a];
    const double normal_speed = w[0] * n[0] + w[1] * n[1];
    // A node pressed against the body (its normal stress compressive) is held on it: its facet
    // carries the body's reaction, so letting it move away would leave that stress unbalanced
    // and push it off for ever. One under tension, or none, may leave.
    const bool pressed = normal_stress(r, n) < 0.0;
    const double correction = pressed ? -normal_speed : std::max(-normal_speed, 0.0);
    const double kept_normal = normal_speed + correction;
    Vec3 tangential{w[0] - normal_speed * n[0], w[1] - normal_speed * n[1], 0.0};
    if (surface_.friction) {
      const double slip = std::hypot(tangential[0], tangential[1]);
      const double held = slip > 0.0 ? std::min(1.0, *surface_.friction * correction / slip) : 0.0;
      tangential[0] *= 1.0 - held;
      tangential[1] *= 1.0 - held;
    } else if (surface_.rough) {
      tangential = Vec3{};
    }
    for (std::size_t a = 0; a < 2; ++a)
      values(velocity_field[a], r) = body[a] + kept_normal * n[a] + tangential[a];
  }
}

std::size_t RigidBody::nodes_in_contact() const {
  return static_cast<std::size_t>(std::count(contact_.begin(), contact_.end(), 1));
}

void RigidBody::contact_normals(std::span<Vec3> normal, std::span<std::uint8_t> reaction,
                                std::span<std::int32_t> body, std::int32_t index) const {
  const bool slides = !surface_.friction && !surface_.rough;
  for (std::size_t k = 0; k < nodes_.size(); ++k) {
    if (!contact_[k]) continue;
    const auto node = static_cast<std::size_t>(nodes_[k]);
    normal[node] = normal_[k];
    body[node] = index;
    // A smooth body holds the normal traction only: on a facet along an axis that is the
    // component of that axis; on a slanted facet both (the shear is then not held at zero).
    std::uint8_t held = 0b11;
    if (slides && std::abs(normal_[k][0]) > 0.99) held = 0b01;
    if (slides && std::abs(normal_[k][1]) > 0.99) held = 0b10;
    reaction[node] |= held;
  }
}

}  // namespace rktsph
