#include "rktsph/boundary/boundary_conditions.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>

#include "rktsph/core/axes.hpp"

namespace rktsph {

namespace {
const std::vector<std::int32_t>& group_nodes(
    const std::map<std::string, std::vector<std::int32_t>>& groups,
    const BoundaryConditionSpec& condition) {
  const auto it = groups.find(condition.group);
  if (it == groups.end())
    throw InputError(condition.where, "boundary_conditions.group", condition.group, "unknown group",
                     "a group defined under 'groups' or a built-in group");
  return it->second;
}

std::vector<Vec3> facet_normals(const SurfaceSet& surface,
                                const std::vector<std::int32_t>& surface_index, std::int32_t node) {
  std::vector<Vec3> normals;
  const std::int32_t k = surface_index[static_cast<std::size_t>(node)];
  if (k < 0) return normals;
  for (std::int32_t f = surface.facets_begin(static_cast<std::size_t>(k));
       f < surface.facets_end(static_cast<std::size_t>(k)); ++f)
    normals.push_back(surface.facet_normal(f));
  return normals;
}

// The outward normals shared by every node of a group: the face(s) the group lies on.
std::vector<Vec3> common_normals(const SurfaceSet& surface,
                                 const std::vector<std::int32_t>& surface_index,
                                 const std::vector<std::int32_t>& members) {
  std::vector<Vec3> common = facet_normals(surface, surface_index, members.front());
  for (std::int32_t node : members) {
    const std::vector<Vec3> own = facet_normals(surface, surface_index, node);
    std::erase_if(common, [&](const Vec3& c) {
      return std::none_of(own.begin(), own.end(),
                          [&](const Vec3& o) { return same_direction(o, c); });
    });
  }
  return common;
}

// The share of node's face of outward normal `normal` that the facets with all their nodes in the
// group make up: their measure over that of every outline facet of the face at the node.
double loaded_share(const SurfaceSet& surface, const std::vector<std::int32_t>& surface_index,
                    const Outline& outline, std::int32_t node, const Vec3& normal,
                    const std::vector<std::uint8_t>& in_group) {
  const std::int32_t k = surface_index[static_cast<std::size_t>(node)];
  if (k < 0) return 0.0;
  for (std::int32_t f = surface.facets_begin(static_cast<std::size_t>(k));
       f < surface.facets_end(static_cast<std::size_t>(k)); ++f) {
    if (!same_direction(surface.facet_normal(f), normal)) continue;
    double loaded = 0.0, total = 0.0;
    for (const std::int32_t piece : surface.pieces(f)) {
      const auto facet = static_cast<std::size_t>(piece);
      const double measure = outline.measure(facet);
      total += measure;
      if (in_group[static_cast<std::size_t>(outline.other_node(facet, node))]) loaded += measure;
    }
    return total > 0.0 ? loaded / total : 0.0;
  }
  return 0.0;
}

std::uint8_t all_components(int dimension) {
  return static_cast<std::uint8_t>((1u << dimension) - 1);
}

bool same_function(const TimeFunction& a, const TimeFunction& b) {
  return a.kind == b.kind && a.value == b.value && a.start == b.start && a.duration == b.duration &&
         a.table == b.table && a.amplitude == b.amplitude && a.period == b.period &&
         a.phase == b.phase && a.offset == b.offset;
}

std::string kind_name(const BoundaryConditionSpec& condition) {
  switch (condition.kind) {
    case BoundaryConditionSpec::Kind::Velocity:
      return "velocity";
    case BoundaryConditionSpec::Kind::Fixed:
      return "fixed";
    case BoundaryConditionSpec::Kind::Roller:
      return "roller";
    case BoundaryConditionSpec::Kind::Traction:
      return "traction";
    case BoundaryConditionSpec::Kind::Rotation:
      return "rotation";
    case BoundaryConditionSpec::Kind::RigidWall:
      return "rigid_wall";
    case BoundaryConditionSpec::Kind::RigidBody:
      return "rigid_body";
    case BoundaryConditionSpec::Kind::PorePressure:
      break;
  }
  return "pore_pressure";
}

std::string node_text(const NodeSets& nodes, std::int32_t node) {
  if (nodes.dimension == 1) return fmt::format("{}", nodes.sph_nodes.position[0][node]);
  return fmt::format("[{}, {}]", nodes.sph_nodes.position[0][node],
                     nodes.sph_nodes.position[1][node]);
}

/// Velocity component `axis` of a rotation condition at the node of reference position X:
/// v(t) = omega e_z x R(omega t) r with r = X - c, i.e.
///   v_x = -|omega| r_x sin(|omega| t) - omega r_y cos(|omega| t),
///   v_y = -|omega| r_y sin(|omega| t) + omega r_x cos(|omega| t)
/// (sin(omega t) = sign(omega) sin(|omega| t)), written as one harmonic A sin(|omega| t + phase) so
/// that apply() evaluates it like any imposed velocity.
TimeFunction rotation_velocity(const BoundaryConditionSpec& condition, const NodeSets& nodes,
                               std::int32_t node, int axis) {
  const double omega = condition.angular_velocity;
  const double rate = std::abs(omega);
  const double rx = nodes.sph_nodes.position[0][node] - condition.centre[0];
  const double ry = nodes.sph_nodes.position[1][node] - condition.centre[1];
  const double sine = axis == 0 ? -rate * rx : -rate * ry;
  const double cosine = axis == 0 ? -omega * ry : omega * rx;
  TimeFunction function;
  function.kind = TimeFunction::Kind::Harmonic;
  function.amplitude = std::hypot(sine, cosine);
  function.phase = std::atan2(cosine, sine);
  function.period = 2.0 * std::numbers::pi / rate;
  return function;
}

/// The velocity component `axis` that `condition` imposes on `node`, or nullopt.
std::optional<TimeFunction> imposed_velocity(const BoundaryConditionSpec& condition, int axis,
                                             const NodeSets& nodes, std::int32_t node) {
  switch (condition.kind) {
    case BoundaryConditionSpec::Kind::Fixed:
      return TimeFunction::constant(0.0);
    case BoundaryConditionSpec::Kind::Roller:
      if (condition.axis == axis) return TimeFunction::constant(0.0);
      return std::nullopt;
    case BoundaryConditionSpec::Kind::Velocity:
      return condition.velocity[static_cast<std::size_t>(axis)];
    case BoundaryConditionSpec::Kind::Rotation:
      return rotation_velocity(condition, nodes, node, axis);
    default:
      return std::nullopt;
  }
}

[[noreturn]] void refuse_conflict(const BoundaryConditionSpec& first,
                                  const BoundaryConditionSpec& second, const NodeSets& nodes,
                                  std::int32_t node, int axis, const std::string& what) {
  throw InputError(
      second.where, "boundary_conditions (group '" + second.group + "')", kind_name(second),
      fmt::format("conflicts with the '{}' condition on group '{}' at {}: on the node at {}, "
                  "{} {}",
                  kind_name(first), first.group, first.where.to_string(), node_text(nodes, node),
                  what, axis_letter(axis)),
      "one imposed velocity per node and component (the same value twice is accepted); narrow "
      "one of the groups or remove one condition");
}

/// The reader refuses these too; checked again for descriptions built in code, since a zero rate
/// would give the compiled harmonic an infinite period.
void check_rotations(std::span<const BoundaryConditionSpec> conditions, int dimension) {
  for (const BoundaryConditionSpec& condition : conditions) {
    if (condition.kind != BoundaryConditionSpec::Kind::Rotation) continue;
    if (dimension != 2)
      throw InputError(condition.where, "boundary_conditions.rotation", "",
                       "'rotation' conditions are only allowed in 2D cases",
                       "remove it, or set dimension: 2");
    if (condition.angular_velocity == 0.0 || !std::isfinite(condition.angular_velocity))
      throw InputError(condition.where, "boundary_conditions.rotation.angular_velocity",
                       fmt::format("{}", condition.angular_velocity),
                       "angular_velocity must be non-zero",
                       "a non-zero number [rad/s]; for a still group use 'fixed: true'");
  }
}

/// Two imposed velocities on one node and component, with different values, would leave the
/// result to the order of the conditions (the last one won, silently): refused. Equal values, such
/// as a roller and a fixed base meeting at a corner, both impose zero and are accepted.
/// Returns, per node and axis, the index of the first condition imposing that velocity (or -1).
std::vector<int> refuse_conflicting_velocities(
    std::span<const BoundaryConditionSpec> conditions, const NodeSets& nodes,
    const std::map<std::string, std::vector<std::int32_t>>& groups) {
  const int d = nodes.dimension;
  std::vector<int> owner(nodes.sph_nodes.size() * static_cast<std::size_t>(d), -1);
  for (std::size_t k = 0; k < conditions.size(); ++k) {
    const auto found = groups.find(conditions[k].group);
    if (found == groups.end()) continue;  // reported where the conditions are compiled
    for (int a = 0; a < d; ++a) {
      for (std::int32_t node : found->second) {
        const std::optional<TimeFunction> value = imposed_velocity(conditions[k], a, nodes, node);
        if (!value) break;  // the same for every node of the group
        int& first = owner[static_cast<std::size_t>(node) * d + a];
        if (first < 0) {
          first = static_cast<int>(k);
          continue;
        }
        const auto& earlier = conditions[static_cast<std::size_t>(first)];
        if (!same_function(*imposed_velocity(earlier, a, nodes, node), *value))
          refuse_conflict(earlier, conditions[k], nodes, node, a,
                          "they impose different velocities along");
      }
    }
  }
  return owner;
}
}  // namespace

int BoundaryConditions::add_function(const TimeFunction& f) {
  functions_.push_back(f);
  return static_cast<int>(functions_.size()) - 1;
}

BoundaryConditions::BoundaryConditions(
    std::span<const BoundaryConditionSpec> conditions, const NodeSets& nodes,
    const std::map<std::string, std::vector<std::int32_t>>& groups, const PhysicsModel& model,
    double time)
    : nodes_(nodes) {
  const int d = nodes.dimension;
  const std::size_t n = nodes.sph_nodes.size();
  const double tolerance = 1e-6 * nodes.spacing;
  check_rotations(conditions, d);
  const std::vector<int> velocity_owner = refuse_conflicting_velocities(conditions, nodes, groups);
  dimension_ = d;
  for (int a = 0; a < 3; ++a)
    for (int c = 0; c < 3; ++c)
      stress_field_[static_cast<std::size_t>(a)][static_cast<std::size_t>(c)] =
          model.stress_field(a, c);
  velocity_axes_.assign(n, 0);
  pore_pressure_field_ = model.pore_pressure_field();
  biot_coefficient_ = model.biot_coefficient();

  // Mirror planes first: they decide which faces of the outline are real faces.
  std::vector<std::pair<int, std::int32_t>> rollers;  // (axis, node)
  for (const BoundaryConditionSpec& condition : conditions) {
    if (condition.kind != BoundaryConditionSpec::Kind::Roller) continue;
    const auto& members = group_nodes(groups, condition);
    const int axis = condition.axis;
    if (axis >= d)
      throw InputError(condition.where, "boundary_conditions.roller", axis_letter(axis),
                       "axis beyond the case dimension", d == 1 ? "x" : "x, y");
    const double plane = nodes.sph_nodes.position[axis][members.front()];
    for (std::int32_t node : members)
      if (std::abs(nodes.sph_nodes.position[axis][node] - plane) > tolerance)
        throw InputError(condition.where, "boundary_conditions.group", condition.group,
                         fmt::format("a roller needs its nodes on one plane {} = const, but they "
                                     "span {} = {} .. {}",
                                     axis_letter(axis), axis_letter(axis), plane,
                                     nodes.sph_nodes.position[axis][node]),
                         "a group lying on one lattice line (e.g. an edge group)");
    if (condition.mirror) {
      const bool known =
          std::any_of(mirror_planes_.begin(), mirror_planes_.end(), [&](const MirrorPlane& m) {
            return m.axis == axis && std::abs(m.coordinate - plane) <= tolerance;
          });
      if (!known) mirror_planes_.push_back(MirrorPlane{axis, plane});
    }
    for (std::int32_t node : members)
      rollers.emplace_back(axis, node);
  }

  mirror_axes_.assign(n, 0);
  for (std::size_t i = 0; i < n; ++i)
    for (const MirrorPlane& m : mirror_planes_)
      if (std::abs(nodes.sph_nodes.position[m.axis][i] - m.coordinate) <= tolerance)
        mirror_axes_[i] |= static_cast<std::uint8_t>(1u << m.axis);

  // The body's faces from the outline of its cells, unless a mirror plane closes them.
  outline_surface(nodes.cells, nodes.outline, nodes.sph_nodes, mirror_axes_, surface_);
  std::vector<std::int32_t> surface_index(n, -1);
  for (std::size_t k = 0; k < surface_.size(); ++k)
    surface_index[static_cast<std::size_t>(surface_.node[k])] = static_cast<std::int32_t>(k);

  // Which velocity components are imposed where, and on which faces: a velocity condition acts
  // on the face its group lies on; the node's other faces stay traction-free. This matters at a
  // corner where a fixed face meets a free one: treating the free face's traction there as a
  // reaction gives a growing corner mode (found by the step-matrix test, docs/theory.md §5.1).
  driven_normals_.assign(n, {});
  for (const auto& [axis, node] : rollers)
    velocity_axes_[node] |= static_cast<std::uint8_t>(1u << axis);
  for (const BoundaryConditionSpec& condition : conditions) {
    const auto& members = group_nodes(groups, condition);
    std::uint8_t axes = 0;
    if (condition.kind == BoundaryConditionSpec::Kind::Fixed ||
        condition.kind == BoundaryConditionSpec::Kind::Rotation)
      axes = all_components(d);
    if (condition.kind == BoundaryConditionSpec::Kind::Velocity)
      for (int a = 0; a < d; ++a)
        if (condition.velocity[a]) axes |= static_cast<std::uint8_t>(1u << a);
    if (axes == 0) continue;
    const std::vector<Vec3> faces = common_normals(surface_, surface_index, members);
    for (std::int32_t node : members) {
      velocity_axes_[node] |= axes;
      // A group on no common face (a point, a region): all of its nodes' faces are driven.
      const auto driven_faces =
          faces.empty() ? facet_normals(surface_, surface_index, node) : faces;
      auto& driven = driven_normals_[static_cast<std::size_t>(node)];
      driven.insert(driven.end(), driven_faces.begin(), driven_faces.end());
    }
  }
  classify(surface_);
  classified_projected_ = surface_.projected;
  classified_reactions_ = surface_.reactions;

  // Stress constraints besides the traction-free facets: roller shear, then tractions.
  const int zero = add_function(TimeFunction::constant(0.0));
  for (const auto& [axis, node] : rollers)
    for (int c = 0; c < d; ++c)
      if (c != axis) {
        const int field = model.stress_field(axis, c);
        if (field >= 0) roller_shear_.push_back({node, field, zero, 1.0});
      }

  for (const BoundaryConditionSpec& condition : conditions) {
    if (condition.kind != BoundaryConditionSpec::Kind::Traction) continue;
    const auto& members = group_nodes(groups, condition);
    // The face the traction acts on: the outward normal shared by every node of the group.
    const std::vector<Vec3> common = common_normals(surface_, surface_index, members);
    if (common.size() != 1)
      throw InputError(condition.where, "boundary_conditions.group", condition.group,
                       common.empty() ? "the group's nodes share no free face, so the traction "
                                        "has no face to act on"
                                      : "the group's nodes share more than one face normal",
                       "a group of nodes on one straight free face (e.g. an edge group)");
    std::array<int, 3> function{-1, -1, -1};
    for (int c = 0; c < d; ++c) {
      if (!condition.traction[c]) continue;
      // On a face whose velocity component c is imposed, sigma.n is the reaction to that
      // velocity: a traction there would be dropped silently, so it is refused.
      for (std::int32_t node : members) {
        const int owner = velocity_owner[static_cast<std::size_t>(node) * d + c];
        if (owner >= 0 && driven(node, common.front()) && ((velocity_axes_[node] >> c) & 1u))
          refuse_conflict(conditions[static_cast<std::size_t>(owner)], condition, nodes, node, c,
                          "a traction and an imposed velocity act on the same face along");
      }
      function[static_cast<std::size_t>(c)] = add_function(*condition.traction[c]);
    }
    // The load acts on the outline facets whose nodes all belong to the group: a node gets the
    // share of its face that such facets make up (1 inside the loaded width, 1/2 at its edge on a
    // uniform spacing), so the nodal tractions integrate to the load over the group's width.
    std::vector<std::uint8_t> in_group(n, 0);
    for (std::int32_t node : members)
      in_group[static_cast<std::size_t>(node)] = 1;
    const std::size_t first_load = tractions_.size();
    for (std::int32_t node : members) {
      const double share =
          loaded_share(surface_, surface_index, nodes.outline, node, common.front(), in_group);
      if (share > 0.0) tractions_.push_back({node, common.front(), function, share});
    }
    if (tractions_.size() == first_load)
      throw InputError(condition.where, "boundary_conditions.group", condition.group,
                       "the group holds no whole facet of the surface (a traction acts on the "
                       "facets whose nodes all belong to its group; a single node carries none)",
                       "a group of neighbouring nodes along one free face, e.g. a box over the "
                       "loaded width with both edge nodes in it");
  }

  // Drained faces: prescribed pore pressure (a Dirichlet row of the pressure solve too).
  for (const BoundaryConditionSpec& condition : conditions) {
    if (condition.kind != BoundaryConditionSpec::Kind::PorePressure) continue;
    const auto& members = group_nodes(groups, condition);
    const int function = add_function(*condition.pore_pressure);
    for (std::int32_t node : members) {
      if (std::find(drained_nodes_.begin(), drained_nodes_.end(), node) != drained_nodes_.end())
        continue;
      drained_nodes_.push_back(node);
      drained_function_.push_back(function);
      pressure_constraints_.push_back({node, pore_pressure_field_, function, 1.0});
    }
  }
  // A water table (docs/theory.md §6.8): the soil at and above it is drained, its excess pore
  // pressure held at 0, which makes the table itself the drained boundary of the saturated soil
  // below it. Below it, a free face (no velocity imposed on it) touches the free water of the
  // table, a submerged face or a pond: drained too. A drained face keeps its own value.
  if (const WaterTable* water_table = model.water_table()) {
    const WaterTable& table = *water_table;
    std::vector<char> drained(n, 0), free_face(n, 0);
    for (std::int32_t node : drained_nodes_)
      drained[static_cast<std::size_t>(node)] = 1;
    for (std::size_t k = 0; k < surface_.size(); ++k)
      for (std::int32_t f = surface_.facets_begin(k); f < surface_.facets_end(k); ++f)
        if (surface_.reactions[static_cast<std::size_t>(f)] == 0)
          free_face[static_cast<std::size_t>(surface_.node[k])] = 1;
    const int no_excess = add_function(TimeFunction::constant(0.0));
    for (std::size_t i = 0; i < n; ++i) {
      const double x = d == 2 ? nodes.sph_nodes.position[0][i] : 0.0;
      const double y = nodes.sph_nodes.position[static_cast<std::size_t>(d - 1)][i];
      if (drained[i] || (y < table.height(x) - tolerance && !free_face[i])) continue;
      const auto node = static_cast<std::int32_t>(i);
      drained_nodes_.push_back(node);
      drained_function_.push_back(no_excess);
      pressure_constraints_.push_back({node, pore_pressure_field_, no_excess, 1.0});
    }
  }

  // Rigid walls: the nodes of their groups that touch them, here on the reference configuration
  // and then at every move of the large-deformation model (follow_configuration).
  for (int a = 0; a < d; ++a)
    velocity_field_[static_cast<std::size_t>(a)] = model.velocity_field(a);
  contact_tolerance_ = 1e-6 * nodes.spacing;
  for (const BoundaryConditionSpec& condition : conditions) {
    if (condition.kind != BoundaryConditionSpec::Kind::RigidWall) continue;
    RigidWall wall;
    double length = 0.0;
    for (int a = 0; a < 3; ++a)
      length += condition.wall_normal[a] * condition.wall_normal[a];
    length = std::sqrt(length);
    for (std::size_t a = 0; a < 3; ++a) {
      wall.point[a] = condition.wall_point[a];
      wall.normal[a] = condition.wall_normal[a] / length;
    }
    wall.rough = condition.wall_rough;
    wall.nodes = group_nodes(groups, condition);
    wall.contact.assign(wall.nodes.size(), 0);
    walls_.push_back(std::move(wall));
  }
  for (const BoundaryConditionSpec& condition : conditions) {
    if (condition.kind != BoundaryConditionSpec::Kind::RigidBody) continue;
    bodies_.emplace_back(
        condition.body_name, condition.body_polygon,
        BodyDrive{condition.body_velocity, condition.body_load, condition.body_mass.value_or(0.0)},
        ContactSurface{condition.wall_rough, condition.body_friction},
        group_nodes(groups, condition));
  }
  body_force_.assign(bodies_.size(), Vec3{});
  if (std::any_of(bodies_.begin(), bodies_.end(),
                  [](const RigidBody& body) { return body.loaded(); })) {
    // The nodes' masses rho0 V0, exact through every forming (eq. 9.11), for the mass a loaded
    // body's contacts hold (eq. 9.17).
    node_mass_.resize(nodes.sph_nodes.size());
    for (std::size_t i = 0; i < node_mass_.size(); ++i)
      node_mass_[i] = model.density(nodes.node_material[i]) * nodes.sph_nodes.volume[i];
  }
  update_contacts(nodes.sph_nodes, time);

  // Velocities: rollers, then fixed and imposed in the order written.
  for (const auto& [axis, node] : rollers)
    velocity_constraints_.push_back({node, model.velocity_field(axis), zero, 1.0});
  for (const BoundaryConditionSpec& condition : conditions) {
    const auto& members = group_nodes(groups, condition);
    if (condition.kind == BoundaryConditionSpec::Kind::Fixed) {
      for (std::int32_t node : members)
        for (int a = 0; a < d; ++a)
          velocity_constraints_.push_back({node, model.velocity_field(a), zero, 1.0});
    } else if (condition.kind == BoundaryConditionSpec::Kind::Velocity) {
      for (int a = 0; a < d; ++a) {
        if (!condition.velocity[a]) continue;
        const int function = add_function(*condition.velocity[a]);
        for (std::int32_t node : members)
          velocity_constraints_.push_back({node, model.velocity_field(a), function, 1.0});
      }
    } else if (condition.kind == BoundaryConditionSpec::Kind::Rotation) {
      // One function per node and component: each node has its own amplitude and phase.
      for (std::int32_t node : members)
        for (int a = 0; a < d; ++a)
          velocity_constraints_.push_back(
              {node, model.velocity_field(a),
               add_function(rotation_velocity(condition, nodes, node, a)), 1.0});
    }
  }
}

bool BoundaryConditions::driven(std::int32_t node, const Vec3& normal) const {
  const auto& faces = driven_normals_[static_cast<std::size_t>(node)];
  return std::any_of(faces.begin(), faces.end(),
                     [&](const Vec3& f) { return same_direction(f, normal); });
}

void BoundaryConditions::classify(SurfaceSet& surface) const {
  const std::uint8_t every = all_components(dimension_);
  for (std::size_t k = 0; k < surface.size(); ++k) {
    const std::int32_t node = surface.node[k];
    for (std::int32_t f = surface.facets_begin(k); f < surface.facets_end(k); ++f) {
      const Vec3 n = surface.facet_normal(f);
      const auto i = static_cast<std::size_t>(f);
      surface.reactions[i] =
          driven(node, n) ? static_cast<std::uint8_t>(velocity_axes_[node] & every) : 0;
      // Projected unless the whole normal velocity is imposed on this face.
      bool normal_velocity_imposed = true;
      for (int c = 0; c < dimension_; ++c)
        if (n[static_cast<std::size_t>(c)] != 0.0 && !((surface.reactions[i] >> c) & 1u))
          normal_velocity_imposed = false;
      surface.projected[i] = normal_velocity_imposed ? 0 : 1;
    }
  }
}

void BoundaryConditions::begin_body_step(double time, double length, const Vec3& gravity) {
  for (std::size_t b = 0; b < bodies_.size(); ++b)
    bodies_[b].begin_step(time, length, body_force_[b], gravity, node_mass_);
}

void BoundaryConditions::end_body_step() {
  for (RigidBody& body : bodies_)
    body.end_step();
}

void BoundaryConditions::carry_bodies(const BoundaryConditions& earlier, double time) {
  for (std::size_t b = 0; b < bodies_.size(); ++b) {
    bodies_[b].set_motion(earlier.bodies_[b].motion());
    body_force_[b] = earlier.body_force_[b];
  }
  // The contacts where the loaded bodies are, not where the constructor put them (at rest).
  update_contacts(nodes_.sph_nodes, time);
}

void BoundaryConditions::save_bodies(CheckpointOut& out) const {
  for (std::size_t b = 0; b < bodies_.size(); ++b) {
    const BodyMotion& motion = bodies_[b].motion();
    out.put_f64(motion.start);
    out.put_f64(motion.length);
    const std::array<const Vec3*, 4> vectors = {&motion.displacement, &motion.velocity,
                                                &motion.end_velocity, &body_force_[b]};
    for (const Vec3* vector : vectors)
      for (double value : *vector)
        out.put_f64(value);
  }
}

void BoundaryConditions::restore_bodies(CheckpointIn& in) {
  for (std::size_t b = 0; b < bodies_.size(); ++b) {
    BodyMotion motion;
    motion.start = in.get_f64();
    motion.length = in.get_f64();
    const std::array<Vec3*, 4> vectors = {&motion.displacement, &motion.velocity,
                                          &motion.end_velocity, &body_force_[b]};
    for (Vec3* vector : vectors)
      for (double& value : *vector)
        value = in.get_f64();
    bodies_[b].set_motion(motion);
  }
}

void BoundaryConditions::follow_configuration(const PointCloud& nodes, double time) {
  // Built on the first call, while surface_ still holds the reference facets and their normals.
  if (!perimeter_) perimeter_.emplace(nodes_.outline, nodes_.sph_nodes, surface_);
  perimeter_->update(nodes, surface_);
  update_contacts(nodes, time);
}

// A node this close to a rigid body, in spacings, touches it. A node held at the body's normal
// speed keeps whatever gap it had when it was caught (the nodes follow the body with the
// trapezoidal rule of their velocities, which lags an accelerating body's exact displacement by
// a fraction of a step's motion); with a tolerance of round-off it then drops out of contact
// on one evaluation and back in on the next, and its facets switch between traction-free and
// reaction (measured on the quick strip footing: the contact pressure fell to a third). §9.18.
constexpr double kBodyContactTolerance = 0.02;

void BoundaryConditions::update_contacts(const PointCloud& positions, double time) {
  deepest_penetration_ = 0.0;
  for (RigidBody& body : bodies_) {
    body.find_contacts(positions, time, kBodyContactTolerance * nodes_.spacing);
    deepest_penetration_ = std::max(deepest_penetration_, body.deepest_penetration());
  }
  if (!bodies_.empty()) release_contact_facets(positions);
  for (RigidWall& wall : walls_)
    for (std::size_t k = 0; k < wall.nodes.size(); ++k) {
      const auto node = static_cast<std::size_t>(wall.nodes[k]);
      double distance = 0.0;  // from the plane, positive inside the body
      for (int a = 0; a < dimension_; ++a)
        distance += (positions.position[static_cast<std::size_t>(a)][node] -
                     wall.point[static_cast<std::size_t>(a)]) *
                    wall.normal[static_cast<std::size_t>(a)];
      wall.contact[k] = distance <= contact_tolerance_ ? 1 : 0;
      deepest_penetration_ = std::max(deepest_penetration_, -distance);
    }
}

double BoundaryConditions::contact_share(std::size_t node, const PointCloud& positions) const {
  // Node i's share of the body's face (eq. 9.15): half the way along the face to each neighbour
  // on the outline that touches the same body, and on a side with none, the face up to the
  // body's corner if that lies within 1.5 spacings (the soil that wraps the corner has no node
  // between the last one in contact and the corner: without it the loaded width jumped by that
  // gap whenever a forming changed which outline facet left the last node, and a punch's force
  // fell by 30 % at one forming and rose again at the next). A side whose face runs on for 1.5
  // spacings with no node on it (a node that has left the body) adds nothing.
  const Vec3& n = contact_normal_[node];
  const std::int32_t body = contact_body_[node];
  const double tx = -n[1], ty = n[0];  // the face's tangent
  double share = 0.0;
  bool covered[2] = {false, false};  // sides -t, +t
  for (std::int32_t piece : nodes_.outline.facets_at(node)) {
    const auto other = static_cast<std::size_t>(nodes_.outline.other_node(
        static_cast<std::size_t>(piece), static_cast<std::int32_t>(node)));
    if (contact_body_[other] != body) continue;
    const double along = tx * (positions.position[0][other] - positions.position[0][node]) +
                         ty * (positions.position[1][other] - positions.position[1][node]);
    share += 0.5 * std::abs(along);
    covered[along > 0.0 ? 1 : 0] = true;
  }
  const std::vector<Vec3>& polygon = bodies_[static_cast<std::size_t>(body)].outline();
  const double band = kBodyContactTolerance * nodes_.spacing;
  const double reach = 1.5 * nodes_.spacing;
  for (int side = 0; side < 2; ++side) {
    if (covered[side]) continue;
    const double sign = side == 1 ? 1.0 : -1.0;
    auto on_face = [&](double distance) {
      const double depth =
          polygon_distance(polygon, positions.position[0][node] + sign * distance * tx,
                           positions.position[1][node] + sign * distance * ty)
              .depth;
      return depth >= -band && depth <= band;
    };
    if (on_face(reach)) continue;    // the face runs on: no corner within reach
    double low = 0.0, high = reach;  // on the face at low, past its corner at high
    for (int k = 0; k < 30; ++k) {
      const double middle = 0.5 * (low + high);
      (on_face(middle) ? low : high) = middle;
    }
    share += std::max(low - band, 0.0);  // a point leaves the band `band` past the corner
  }
  return share;
}

void BoundaryConditions::release_contact_facets(const PointCloud& positions) {
  // A facet pressed against a rigid body carries the body's reaction while its node is in
  // contact: its stress increment is not projected traction-free, and the traction components the
  // contact holds (all on a rough or frictional body, the normal one on a smooth body) are
  // reactions, not zero (docs/theory.md §9.18).
  if (classified_projected_.size() != surface_.projected.size()) return;  // not classified yet
  surface_.projected = classified_projected_;
  surface_.reactions = classified_reactions_;
  contact_normal_.assign(nodes_.sph_nodes.size(), Vec3{});
  contact_reaction_.assign(nodes_.sph_nodes.size(), 0);
  contact_body_.assign(nodes_.sph_nodes.size(), -1);
  contact_length_.assign(nodes_.sph_nodes.size(), 0.0);
  for (std::size_t b = 0; b < bodies_.size(); ++b)
    bodies_[b].contact_normals(contact_normal_, contact_reaction_, contact_body_,
                               static_cast<std::int32_t>(b));
  // Each node's share of the body's face, from every outline facet at it (eq. 9.15): a node at
  // a re-entrant corner of the outline (the soil wrapping the body's edge) has no facet in the
  // surface set, but it carries the body's load all the same.
  for (std::size_t node = 0; node < contact_body_.size(); ++node)
    if (contact_body_[node] >= 0) contact_length_[node] = contact_share(node, positions);
  for (std::size_t k = 0; k < surface_.size(); ++k) {
    const auto touching = static_cast<std::size_t>(surface_.node[k]);
    const Vec3& body_normal = contact_normal_[touching];
    if (body_normal[0] == 0.0 && body_normal[1] == 0.0) continue;
    for (std::int32_t f = surface_.facets_begin(k); f < surface_.facets_end(k); ++f) {
      const Vec3 n = surface_.facet_normal(f);
      if (n[0] * body_normal[0] + n[1] * body_normal[1] >= -0.5) continue;
      surface_.projected[static_cast<std::size_t>(f)] = 0;
      surface_.reactions[static_cast<std::size_t>(f)] |= contact_reaction_[touching];
    }
  }
}

std::size_t BoundaryConditions::nodes_in_contact() const {
  std::size_t count = 0;
  for (const RigidWall& wall : walls_)
    count += static_cast<std::size_t>(std::count(wall.contact.begin(), wall.contact.end(), 1));
  for (const RigidBody& body : bodies_)
    count += body.nodes_in_contact();
  return count;
}

void BoundaryConditions::impose_contacts(FieldArray& values,
                                         std::span<const std::int32_t> node_to_row) const {
  // A node on a wall may leave it but not move into it (v.n >= 0); on a rough wall it does not
  // slip either, v = max(v.n, 0) n (docs/theory.md §9.13).
  for (const RigidWall& wall : walls_)
    for (std::size_t k = 0; k < wall.nodes.size(); ++k) {
      if (!wall.contact[k]) continue;
      const std::int32_t node = wall.nodes[k];
      const std::int32_t row =
          node_to_row.empty() ? node : node_to_row[static_cast<std::size_t>(node)];
      if (row < 0) continue;
      const auto r = static_cast<std::size_t>(row);
      double normal_speed = 0.0;
      for (int a = 0; a < dimension_; ++a)
        normal_speed += values(velocity_field_[static_cast<std::size_t>(a)], r) *
                        wall.normal[static_cast<std::size_t>(a)];
      const double kept = std::max(normal_speed, 0.0);
      for (int a = 0; a < dimension_; ++a) {
        double& v = values(velocity_field_[static_cast<std::size_t>(a)], r);
        const double n = wall.normal[static_cast<std::size_t>(a)];
        v = wall.rough ? kept * n : v - (normal_speed - kept) * n;
      }
    }
}

void BoundaryConditions::replace_surface(const SurfaceSet& surface) {
  surface_.node = surface.node;
  surface_.first_facet = surface.first_facet;
  surface_.normal = surface.normal;
  surface_.reactions = surface.reactions;
  surface_.projected = surface.projected;
  surface_.first_piece = surface.first_piece;
  surface_.piece = surface.piece;
  classify(surface_);
  classified_projected_ = surface_.projected;
  classified_reactions_ = surface_.reactions;
}

StressTensor BoundaryConditions::stress_at(const FieldArray& values, std::size_t row) const {
  StressTensor sigma{};
  for (std::size_t a = 0; a < 3; ++a)
    for (std::size_t c = 0; c < 3; ++c)
      if (stress_field_[a][c] >= 0) sigma[a][c] = values(stress_field_[a][c], row);
  return sigma;
}

void BoundaryConditions::store_stress(const StressTensor& sigma, FieldArray& values,
                                      std::size_t row) const {
  for (std::size_t a = 0; a < 3; ++a)
    for (std::size_t c = a; c < 3; ++c)
      if (stress_field_[a][c] >= 0) values(stress_field_[a][c], row) = sigma[a][c];
}

std::optional<double> BoundaryConditions::biot_pore_pressure(const FieldArray& values,
                                                             std::size_t row) const {
  if (pore_pressure_field_ < 0) return std::nullopt;
  return biot_coefficient_ * values(pore_pressure_field_, row);
}

void BoundaryConditions::append_overwritten(
    std::int32_t node, const Vec3& normal, std::uint8_t components,
    std::vector<std::pair<std::int32_t, int>>& pairs) const {
  const auto on_axis = as_axis_normal(normal);
  for (int a = 0; a < dimension_; ++a)
    for (int c = 0; c < dimension_; ++c) {
      // On an axis only row a of sigma changes; on any other normal the whole in-plane tensor.
      const bool changed = on_axis ? a == on_axis->axis && ((components >> c) & 1u) : c >= a;
      const int field = stress_field_[static_cast<std::size_t>(a)][static_cast<std::size_t>(c)];
      if (changed && field >= 0) pairs.emplace_back(node, field);
    }
}

std::vector<std::pair<std::int32_t, int>> BoundaryConditions::constrained_stress() const {
  std::vector<std::pair<std::int32_t, int>> pairs;
  const std::uint8_t every = all_components(dimension_);
  for (std::size_t k = 0; k < surface_.size(); ++k)
    for (std::int32_t f = surface_.facets_begin(k); f < surface_.facets_end(k); ++f)
      append_overwritten(surface_.node[k], surface_.facet_normal(f),
                         every & ~surface_.reactions[static_cast<std::size_t>(f)], pairs);
  for (const Constraint& c : roller_shear_)
    pairs.emplace_back(c.node, c.field);
  for (const ImposedTraction& load : tractions_) {
    std::uint8_t given = 0;
    for (int c = 0; c < dimension_; ++c)
      if (load.function[static_cast<std::size_t>(c)] >= 0)
        given |= static_cast<std::uint8_t>(1u << c);
    append_overwritten(load.node, load.normal, given, pairs);
  }
  return pairs;
}

void BoundaryConditions::apply(double time, FieldArray& values,
                               std::span<const std::int32_t> node_to_row) const {
  // Evaluate each time function once per call.
  double function_value[64];
  std::vector<double> many;
  double* value = function_value;
  if (functions_.size() > 64) {
    many.resize(functions_.size());
    value = many.data();
  }
  for (std::size_t f = 0; f < functions_.size(); ++f)
    value[f] = functions_[f](time);
  auto row_of = [&](std::int32_t node) {
    return node_to_row.empty() ? node : node_to_row[static_cast<std::size_t>(node)];
  };
  auto impose = [&](const std::vector<Constraint>& list) {
    for (const Constraint& c : list) {
      const std::int32_t row = row_of(c.node);
      if (row >= 0) values(c.field, static_cast<std::size_t>(row)) = c.scale * value[c.function];
    }
  };
  impose(pressure_constraints_);
  // Stress, weakest first: traction-free facets, roller shear, then the imposed tractions. The
  // saturated model's tractions act on the total stress, read after p_w is imposed (§5.1).
  const std::uint8_t every = all_components(dimension_);
  for (std::size_t k = 0; k < surface_.size(); ++k) {
    const std::int32_t row = row_of(surface_.node[k]);
    if (row < 0) continue;
    const auto r = static_cast<std::size_t>(row);
    StressTensor sigma = stress_at(values, r);
    TractionCondition free_facet;
    free_facet.biot_pore_pressure = biot_pore_pressure(values, r);
    for (std::int32_t f = surface_.facets_begin(k); f < surface_.facets_end(k); ++f) {
      free_facet.normal = surface_.facet_normal(f);
      free_facet.components = every & ~surface_.reactions[static_cast<std::size_t>(f)];
      impose_traction(free_facet, dimension_, sigma);
    }
    store_stress(sigma, values, r);
  }
  impose(roller_shear_);
  for (const ImposedTraction& load : tractions_) {
    const std::int32_t row = row_of(load.node);
    if (row < 0) continue;
    const auto r = static_cast<std::size_t>(row);
    TractionCondition condition;
    condition.normal = load.normal;
    condition.biot_pore_pressure = biot_pore_pressure(values, r);
    for (std::size_t c = 0; c < 3; ++c) {
      if (load.function[c] < 0) continue;
      condition.traction[c] = load.share * value[load.function[c]];
      condition.components |= static_cast<std::uint8_t>(1u << c);
    }
    StressTensor sigma = stress_at(values, r);
    impose_traction(condition, dimension_, sigma);
    store_stress(sigma, values, r);
  }
  impose(velocity_constraints_);
  impose_contacts(values, node_to_row);
  const auto normal_stress = [&](std::size_t row, const Vec3& n) {
    const StressTensor sigma = stress_at(values, row);
    double sum = 0.0;
    for (std::size_t a = 0; a < 2; ++a)
      for (std::size_t c = 0; c < 2; ++c)
        sum += n[a] * sigma[a][c] * n[c];
    return sum;
  };
  for (const RigidBody& body : bodies_)
    body.impose(time, velocity_field_, values, node_to_row, normal_stress);
  if (node_to_row.empty() && !bodies_.empty()) measure_body_forces(values);
}

void BoundaryConditions::measure_body_forces(const FieldArray& values) const {
  // The force on each body: the traction sigma.n of every node in contact on the body's face
  // (n the body's outward normal there) times the node's share of the face (eq. 9.15).
  std::fill(body_force_.begin(), body_force_.end(), Vec3{});
  if (contact_length_.size() != nodes_.sph_nodes.size()) return;
  for (std::size_t node = 0; node < contact_length_.size(); ++node) {
    if (contact_body_[node] < 0 || contact_length_[node] == 0.0) continue;
    const StressTensor sigma = stress_at(values, node);
    const Vec3& n = contact_normal_[node];
    Vec3& force = body_force_[static_cast<std::size_t>(contact_body_[node])];
    for (std::size_t a = 0; a < 2; ++a)
      force[a] += (sigma[a][0] * n[0] + sigma[a][1] * n[1]) * contact_length_[node];
  }
}

}  // namespace rktsph
