#include "rktsph/boundary/boundary_conditions.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
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
bool same_normal(const FaceNormal& a, const FaceNormal& b) {
  return a.axis == b.axis && a.sign == b.sign;
}

// The outward normals shared by every node of a group: the face(s) the group lies on.
std::vector<FaceNormal> common_normals(const std::vector<std::vector<FaceNormal>>& normals,
                                       const std::vector<std::int32_t>& members) {
  std::vector<FaceNormal> common = normals[static_cast<std::size_t>(members.front())];
  for (std::int32_t node : members) {
    const auto& own = normals[static_cast<std::size_t>(node)];
    std::erase_if(common, [&](const FaceNormal& c) {
      return std::none_of(own.begin(), own.end(),
                          [&](const FaceNormal& o) { return same_normal(o, c); });
    });
  }
  return common;
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

/// The velocity component `axis` that `condition` imposes, or nullopt.
std::optional<TimeFunction> imposed_velocity(const BoundaryConditionSpec& condition, int axis) {
  switch (condition.kind) {
    case BoundaryConditionSpec::Kind::Fixed:
      return TimeFunction::constant(0.0);
    case BoundaryConditionSpec::Kind::Roller:
      if (condition.axis == axis) return TimeFunction::constant(0.0);
      return std::nullopt;
    case BoundaryConditionSpec::Kind::Velocity:
      return condition.velocity[static_cast<std::size_t>(axis)];
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

/// Two imposed velocities on one node and component, with different values, would leave the
/// result to the order of the conditions (the last one won, silently): refused. Equal values, such
/// as a roller and a fixed base meeting at a corner, both impose zero and are accepted.
/// Returns, per node and axis, the index of the first condition imposing that velocity (or -1).
std::vector<int> refuse_conflicting_velocities(
    const CaseDescription& description, const NodeSets& nodes,
    const std::map<std::string, std::vector<std::int32_t>>& groups) {
  const int d = nodes.dimension;
  std::vector<int> owner(nodes.sph_nodes.size() * static_cast<std::size_t>(d), -1);
  const auto& conditions = description.boundary_conditions;
  for (std::size_t k = 0; k < conditions.size(); ++k) {
    const auto found = groups.find(conditions[k].group);
    if (found == groups.end()) continue;  // reported where the conditions are compiled
    for (int a = 0; a < d; ++a) {
      const std::optional<TimeFunction> value = imposed_velocity(conditions[k], a);
      if (!value) continue;
      for (std::int32_t node : found->second) {
        int& first = owner[static_cast<std::size_t>(node) * d + a];
        if (first < 0) {
          first = static_cast<int>(k);
          continue;
        }
        const auto& earlier = conditions[static_cast<std::size_t>(first)];
        if (!same_function(*imposed_velocity(earlier, a), *value))
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
    const CaseDescription& description, const NodeSets& nodes,
    const std::map<std::string, std::vector<std::int32_t>>& groups, const PhysicsModel& model) {
  const int d = nodes.dimension;
  const std::size_t n = nodes.sph_nodes.size();
  const double tolerance = 1e-6 * nodes.spacing;
  const std::vector<int> velocity_owner = refuse_conflicting_velocities(description, nodes, groups);
  velocity_axes_.assign(n, 0);
  projected_axes_.assign(n, 0);
  pore_pressure_field_ = model.pore_pressure_field();
  biot_coefficient_ = model.biot_coefficient();
  face_normals_.assign(n, {});

  // Mirror planes first: they decide which lattice faces are real faces.
  std::vector<std::pair<int, std::int32_t>> rollers;  // (axis, node)
  for (const BoundaryConditionSpec& condition : description.boundary_conditions) {
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

  // Faces: lattice directions with no neighbour node, unless a mirror plane closes them.
  for (std::size_t i = 0; i < n; ++i) {
    for (int a = 0; a < d; ++a)
      for (int sign : {-1, 1}) {
        LatticeIndex neighbour = nodes.node_index[i];
        neighbour[a] += sign;
        if (nodes.node_at(neighbour) >= 0) continue;
        if (!((mirror_axes_[i] >> a) & 1u)) face_normals_[i].push_back(FaceNormal{a, sign});
      }
  }

  // Which velocity components are imposed where, and on which faces: a velocity condition acts
  // on the face its group lies on; the node's other faces stay traction-free. This matters at a
  // corner where a fixed face meets a free one: treating the free face's traction there as a
  // reaction gives a growing corner mode (found by the step-matrix test, docs/theory.md §5.1).
  std::vector<std::vector<FaceNormal>> velocity_faces(n);
  for (const auto& [axis, node] : rollers)
    velocity_axes_[node] |= static_cast<std::uint8_t>(1u << axis);
  for (const BoundaryConditionSpec& condition : description.boundary_conditions) {
    const auto& members = group_nodes(groups, condition);
    std::uint8_t axes = 0;
    if (condition.kind == BoundaryConditionSpec::Kind::Fixed)
      axes = static_cast<std::uint8_t>((1u << d) - 1);
    if (condition.kind == BoundaryConditionSpec::Kind::Velocity)
      for (int a = 0; a < d; ++a)
        if (condition.velocity[a]) axes |= static_cast<std::uint8_t>(1u << a);
    if (axes == 0) continue;
    const std::vector<FaceNormal> faces = common_normals(face_normals_, members);
    for (std::int32_t node : members) {
      velocity_axes_[node] |= axes;
      // A group on no common face (a point, a region): all of its nodes' faces are driven.
      const auto& driven = faces.empty() ? face_normals_[node] : faces;
      for (const FaceNormal& f : driven)
        velocity_faces[node].push_back(f);
    }
  }
  auto is_driven = [&](std::int32_t node, const FaceNormal& normal) {
    const auto& driven = velocity_faces[static_cast<std::size_t>(node)];
    return std::any_of(driven.begin(), driven.end(),
                       [&](const FaceNormal& f) { return same_normal(f, normal); });
  };

  // Stress constraints, weakest first: natural traction-free faces, roller shear, then tractions.
  const int zero = add_function(TimeFunction::constant(0.0));
  auto add_face_stress = [&](std::int32_t node, const FaceNormal& normal, int component,
                             int function) {
    // Traction t = sigma . n: on a face with outward normal sign*e_a, sigma_(a,c) = sign * t_c.
    if (is_driven(node, normal) && ((velocity_axes_[node] >> component) & 1u))
      return;  // a reaction on the driven face, not a traction
    const int field = model.stress_field(normal.axis, component);
    // Saturated model: the traction acts on the total stress, sigma'_nn = t_n + alpha p_w.
    if (field >= 0)
      stress_constraints_.push_back({node, field, function, static_cast<double>(normal.sign),
                                     pore_pressure_field_ >= 0 && component == normal.axis});
  };
  for (std::size_t i = 0; i < n; ++i) {
    const auto node = static_cast<std::int32_t>(i);
    for (const FaceNormal& normal : face_normals_[i]) {
      for (int c = 0; c < d; ++c)
        add_face_stress(node, normal, c, zero);
      if (!(is_driven(node, normal) && ((velocity_axes_[i] >> normal.axis) & 1u)))
        projected_axes_[i] |= static_cast<std::uint8_t>(1u << normal.axis);
    }
  }
  for (const auto& [axis, node] : rollers)
    for (int c = 0; c < d; ++c)
      if (c != axis) {
        const int field = model.stress_field(axis, c);
        if (field >= 0) stress_constraints_.push_back({node, field, zero, 1.0});
      }

  for (const BoundaryConditionSpec& condition : description.boundary_conditions) {
    if (condition.kind != BoundaryConditionSpec::Kind::Traction) continue;
    const auto& members = group_nodes(groups, condition);
    // The face the traction acts on: the outward normal shared by every node of the group.
    const std::vector<FaceNormal> common = common_normals(face_normals_, members);
    if (common.size() != 1)
      throw InputError(condition.where, "boundary_conditions.group", condition.group,
                       common.empty() ? "the group's nodes share no free face, so the traction "
                                        "has no face to act on"
                                      : "the group's nodes share more than one face normal",
                       "a group of nodes on one straight free face (e.g. an edge group)");
    for (int c = 0; c < d; ++c) {
      if (!condition.traction[c]) continue;
      // On a face whose velocity component c is imposed, sigma.n is the reaction to that
      // velocity: a traction there would be dropped silently, so it is refused.
      for (std::int32_t node : members) {
        const int owner = velocity_owner[static_cast<std::size_t>(node) * d + c];
        if (owner >= 0 && is_driven(node, common.front()) && ((velocity_axes_[node] >> c) & 1u))
          refuse_conflict(description.boundary_conditions[static_cast<std::size_t>(owner)],
                          condition, nodes, node, c,
                          "a traction and an imposed velocity act on the same face along");
      }
      const int function = add_function(*condition.traction[c]);
      for (std::int32_t node : members)
        add_face_stress(node, common.front(), c, function);
    }
  }

  // Drained faces: prescribed pore pressure (a Dirichlet row of the pressure solve too).
  for (const BoundaryConditionSpec& condition : description.boundary_conditions) {
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

  // Velocities: rollers, then fixed and imposed in the order written.
  for (const auto& [axis, node] : rollers)
    velocity_constraints_.push_back({node, model.velocity_field(axis), zero, 1.0});
  for (const BoundaryConditionSpec& condition : description.boundary_conditions) {
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
    }
  }
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
  for (const auto* list : {&pressure_constraints_, &stress_constraints_, &velocity_constraints_})
    for (const Constraint& c : *list) {
      const std::int32_t row = row_of(c.node);
      if (row < 0) continue;
      const auto r = static_cast<std::size_t>(row);
      double v = c.scale * value[c.function];
      if (c.plus_pore_pressure) v += biot_coefficient_ * values(pore_pressure_field_, r);
      values(c.field, r) = v;
    }
}

}  // namespace rktsph
