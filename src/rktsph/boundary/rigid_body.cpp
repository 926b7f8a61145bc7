#include "rktsph/boundary/rigid_body.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace rktsph {

RigidBody::RigidBody(std::string name, std::vector<Vec3> polygon, BodyDrive drive,
                     ContactSurface surface, std::vector<std::int32_t> nodes)
    : name_(std::move(name)),
      polygon_(std::move(polygon)),
      drive_(std::move(drive)),
      surface_(surface),
      nodes_(std::move(nodes)),
      contact_(nodes_.size(), 0),
      normal_(nodes_.size(), Vec3{}),
      moved_polygon_(polygon_) {}

bool RigidBody::loaded() const {
  return std::any_of(drive_.load.begin(), drive_.load.end(),
                     [](const std::optional<TimeFunction>& load) { return load.has_value(); });
}

Vec3 RigidBody::velocity(double time) const {
  Vec3 v{};
  // On a loaded axis the velocity is linear over the step (eq. 9.17); before the first step
  // (length 0) it is the initial one.
  const double fraction = motion_.length > 0.0 ? (time - motion_.start) / motion_.length : 0.0;
  for (std::size_t a = 0; a < 3; ++a) {
    if (drive_.velocity[a]) v[a] = (*drive_.velocity[a])(time);
    if (drive_.load[a])
      v[a] = motion_.velocity[a] + fraction * (motion_.end_velocity[a] - motion_.velocity[a]);
  }
  return v;
}

Vec3 RigidBody::displacement(double time) const {
  Vec3 u{};
  const double elapsed = time - motion_.start;
  const double fraction = motion_.length > 0.0 ? elapsed / motion_.length : 0.0;
  for (std::size_t a = 0; a < 3; ++a) {
    if (drive_.velocity[a]) u[a] = drive_.velocity[a]->integral(time);
    if (drive_.load[a])
      u[a] = motion_.displacement[a] +
             elapsed * (motion_.velocity[a] +
                        0.5 * fraction * (motion_.end_velocity[a] - motion_.velocity[a]));
  }
  return u;
}

void RigidBody::begin_step(double time, double length, const Vec3& soil_force, const Vec3& gravity,
                           std::span<const double> node_mass) {
  motion_.start = time;
  motion_.length = length;
  if (!loaded()) return;
  // Eq. 9.17: (M + m_c) dV/dt = P(t) + M g + F, explicit in the soil's force F. The nodes the
  // contact holds move with the body along the axes it holds them on, so their mass m_c rides
  // with it: it keeps the body's step stable whatever its own mass (a plate lighter than the row
  // of soil under it would otherwise oscillate against that row's stiffness and grow), and at
  // rest it changes nothing.
  const bool slides = !surface_.friction && !surface_.rough;
  Vec3 held_mass{};
  for (std::size_t k = 0; k < nodes_.size(); ++k) {
    if (!contact_[k]) continue;
    const double mass = node_mass[static_cast<std::size_t>(nodes_[k])];
    for (std::size_t a = 0; a < 2; ++a)
      held_mass[a] += slides ? mass * normal_[k][a] * normal_[k][a] : mass;
  }
  for (std::size_t a = 0; a < 3; ++a) {
    motion_.end_velocity[a] = motion_.velocity[a];
    if (!drive_.load[a]) continue;
    const double force =
        (*drive_.load[a])(time + 0.5 * length) + drive_.mass * gravity[a] + soil_force[a];
    motion_.end_velocity[a] += length * force / (drive_.mass + held_mass[a]);
  }
}

void RigidBody::end_step() {
  if (!loaded()) return;
  for (std::size_t a = 0; a < 3; ++a)
    motion_.displacement[a] +=
        0.5 * motion_.length * (motion_.velocity[a] + motion_.end_velocity[a]);
  motion_.velocity = motion_.end_velocity;
  motion_.start += motion_.length;
  motion_.length = 0.0;
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
