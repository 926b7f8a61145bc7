// The `boundary_conditions` section: a list of conditions, each on a group and of exactly one kind
// (docs/input-reference.md, "boundary_conditions").
#include <fmt/format.h>

#include "rktsph/case/sections/sections.hpp"
#include "rktsph/case/sections/value_readers.hpp"
#include "rktsph/core/axes.hpp"

namespace rktsph {

namespace {

using Condition = BoundaryConditionSpec;

const std::vector<std::string> kKinds = {"velocity",      "fixed",    "roller",     "traction",
                                         "pore_pressure", "rotation", "rigid_wall", "rigid_body"};

void read_roller(const YamlNode& kind, Condition& condition, Reading& reading) {
  const int dimension = reading.so_far.dimension;
  if (dimension == 1 && to_text(kind) == "y") {
    fail_at(kind, "a roller normal to y exists only in 2D", "'x'");
  }
  condition.kind = Condition::Kind::Roller;
  condition.axis = to_choice(kind, axis_names(dimension)) == "x" ? 0 : 1;
}

/// The keys of a `rotation` condition's map.
const KeyTable<Condition>& rotation_keys() {
  static const KeyTable<Condition> keys = {
      Key<Condition>{"angular_velocity", "number", "rad/s", "required", "≠ 0",
                     "ω of the rigid rotation, counter-clockwise positive.", true,
                     [](const YamlNode& node, Condition& condition, Reading&) {
                       const double omega = to_number(node);
                       // A zero rate is a fixed condition in disguise, and has no period for
                       // the harmonic velocity the rotation is compiled into.
                       if (omega == 0.0)
                         fail_at(node, "angular_velocity must be non-zero",
                                 "a non-zero number [rad/s]; for a still group use 'fixed: true'");
                       condition.angular_velocity = omega;
                     },
                     [](YAML::Emitter& out, const Condition& condition, const CaseDescription&) {
                       out << YAML::Key << "angular_velocity" << YAML::Value
                           << number(condition.angular_velocity);
                     }},
      vector_key<Condition>("centre", &Condition::centre, "m", "required",
                            "The fixed point [cx, cy]."),
  };
  return keys;
}

void read_rotation(const YamlNode& node, Condition& condition, Reading& reading) {
  reject_unless_2d(node, reading.so_far.dimension, "'rotation' conditions are");
  condition.kind = Condition::Kind::Rotation;
  read_keys(node, rotation_keys(), condition, reading);
}

/// The keys of a `rigid_wall` condition's map.
const KeyTable<Condition>& rigid_wall_keys() {
  static const KeyTable<Condition> keys = {
      vector_key<Condition>("point", &Condition::wall_point, "m", "required",
                            "A point of the wall's plane."),
      Key<Condition>{
          "normal", "vector", "–", "required", "non-zero",
          "The plane's normal, pointing into the body (any length).", true,
          [](const YamlNode& node, Condition& condition, Reading& reading) {
            const Vec3 normal = read_vector(node, reading.so_far.dimension);
            if (normal[0] == 0.0 && normal[1] == 0.0 && normal[2] == 0.0)
              fail_at(node, "the wall's normal must not be zero",
                      "a non-zero vector pointing into the body, e.g. [0, 1]");
            condition.wall_normal = normal;
          },
          [](YAML::Emitter& out, const Condition& condition, const CaseDescription& description) {
            out << YAML::Key << "normal" << YAML::Value;
            emit_vector(out, condition.wall_normal, description.dimension);
          }},
      choice_key<Condition, bool>("surface", &Condition::wall_rough,
                                  {{"rough", true}, {"smooth", false}},
                                  "rough: a node in contact does not slip; smooth: it slides "
                                  "freely along the wall."),
  };
  return keys;
}

void read_rigid_wall(const YamlNode& node, Condition& condition, Reading& reading) {
  condition.kind = Condition::Kind::RigidWall;
  read_keys(node, rigid_wall_keys(), condition, reading);
}

/// A rigid body's per-axis time functions (its velocity, its load): x, y components.
Key<Condition> body_components_key(const char* name,
                                   std::array<std::optional<TimeFunction>, 3> Condition::*member,
                                   const char* unit, const char* default_value, const char* doc) {
  return Key<Condition>{name,
                        "map of components",
                        unit,
                        default_value,
                        "keys x, y; each a time function",
                        doc,
                        false,
                        [member](const YamlNode& node, Condition& condition, Reading& reading) {
                          condition.*member = read_components(node, reading.so_far.dimension);
                        },
                        [member, name](YAML::Emitter& out, const Condition& condition,
                                       const CaseDescription& description) {
                          if (!(condition.*member)[0] && !(condition.*member)[1]) return;
                          out << YAML::Key << name << YAML::Value;
                          emit_components(out, condition.*member, description.dimension);
                        }};
}

/// The keys of a `rigid_body` condition's map (docs/theory.md §9.18).
const KeyTable<Condition>& rigid_body_keys() {
  static const KeyTable<Condition> keys = {
      Key<Condition>{"name", "word", "–", "required", "a name of letters, digits and _",
                     "The body's name: its columns in probes.csv are <name>.force_x, "
                     "<name>.force_y, <name>.displacement_x and <name>.displacement_y.",
                     true,
                     [](const YamlNode& node, Condition& condition, Reading&) {
                       const std::string name = to_text(node);
                       if (name.empty() || name.find_first_not_of(kLabelAlphabet) != name.npos)
                         fail_at(node, "not a valid body name", kLabelAlphabetName);
                       condition.body_name = name;
                     },
                     [](YAML::Emitter& out, const Condition& condition, const CaseDescription&) {
                       out << YAML::Key << "name" << YAML::Value << condition.body_name;
                     }},
      Key<Condition>{
          "polygon", "list of points", "m", "required",
          "3 to 10 000 vertices, non-zero area, simple",
          "The body's outline at t = 0; it moves rigidly with `velocity`.", true,
          [](const YamlNode& node, Condition& condition, Reading& reading) {
            condition.body_polygon = read_polygon(node, reading.so_far.dimension);
          },
          [](YAML::Emitter& out, const Condition& condition, const CaseDescription& description) {
            out << YAML::Key << "polygon" << YAML::Value << YAML::Flow << YAML::BeginSeq;
            for (const Vec3& vertex : condition.body_polygon)
              emit_vector(out, vertex, description.dimension);
            out << YAML::EndSeq;
          }},
      body_components_key("velocity", &Condition::body_velocity, "m/s", "still",
                          "The body's imposed velocity (a translation); components left out, "
                          "and not loaded, are 0."),
      body_components_key(
          "load", &Condition::body_load, "N/m", "none",
          "The force on the body besides the soil's, per metre of thickness, on the axes it "
          "gives: the body moves along them under that force, the soil's reaction and its weight "
          "(its own equation of motion, docs/theory.md eq. 9.17). Not on an axis of `velocity`; "
          "needs `mass`."),
      optional_number_key<Condition>(
          "mass", &Condition::body_mass, NumberRange::positive(), "kg/m", "required with load",
          "The body's mass per metre of thickness: its inertia under `load`, and its weight "
          "under the case's gravity. Only with `load`."),
      choice_key<Condition, bool>("surface", &Condition::wall_rough,
                                  {{"rough", true}, {"smooth", false}},
                                  "rough: a node in contact moves with the body along its "
                                  "surface; smooth: it slides freely. Not with `friction`."),
      optional_number_key<Condition>(
          "friction", &Condition::body_friction, NumberRange::non_negative(), "–",
          "none (the surface rule)",
          "Coulomb's coefficient mu: a node slides along the body once the tangential impulse "
          "that would hold it exceeds mu times the normal one. Not with `surface`."),
  };
  return keys;
}

/// Each axis of a rigid body is driven by a velocity or a load, not both; a load needs a mass to
/// move, and a mass means nothing without one (docs/theory.md §9.18).
void check_body_motion(const YamlMap& map, const Condition& condition) {
  const YamlNode* load = map.find("load");
  for (std::size_t a = 0; a < 2; ++a)
    if (condition.body_load[a] && condition.body_velocity[a])
      fail_at(*load, fmt::format("the body's {} motion is both imposed and loaded", "xy"[a]),
              "each axis in one of `velocity` and `load`", true);
  if (load != nullptr && !condition.body_mass)
    fail_at(*load, "a loaded body needs its mass to move", "mass: the body's mass in kg/m", true);
  if (load == nullptr && condition.body_mass)
    fail_at(*map.find("mass"), "a body's mass acts only under a load",
            "load: {y: ...} with the mass, or no mass", true);
}

void read_rigid_body(const YamlNode& node, Condition& condition, Reading& reading) {
  reject_unless_2d(node, reading.so_far.dimension, "'rigid_body' conditions are");
  condition.kind = Condition::Kind::RigidBody;
  const YamlMap map(node);
  if (map.find("surface") != nullptr && map.find("friction") != nullptr)
    fail_at(*map.find("friction"), "'friction' and 'surface' both say how the body holds a node",
            "one of them: surface: rough | smooth, or friction: mu (Coulomb)", true);
  read_keys(node, rigid_body_keys(), condition, reading);
  check_body_motion(map, condition);
}

/// Writes `name: value` when the condition is of `kind`.
template <typename Write>
auto emit_if(Condition::Kind kind, const char* name, Write write) {
  return [kind, name, write](YAML::Emitter& out, const Condition& condition,
                             const CaseDescription& description) {
    if (condition.kind != kind) return;
    out << YAML::Key << name << YAML::Value;
    write(out, condition, description.dimension);
  };
}

const KeyTable<Condition>& condition_keys() {
  static const KeyTable<Condition> keys = {
      section_key<Condition>(
          "group", "word", "required", "a built-in or defined group", "The nodes it acts on.",
          [](const YamlNode& node, Condition& condition, Reading& reading) {
            condition.group = read_group_reference(node, reading.so_far.groups);
          },
          [](YAML::Emitter& out, const Condition& condition, const CaseDescription&) {
            out << YAML::Key << "group" << YAML::Value << condition.group;
          }),
      in_unit(section_key<Condition>(
                  "velocity", "map of components", "one kind", "keys x (and y in 2D); at least one",
                  "Imposed velocity of the given components, each a time function; others free.",
                  [](const YamlNode& node, Condition& condition, Reading& reading) {
                    condition.kind = Condition::Kind::Velocity;
                    condition.velocity = read_components(node, reading.so_far.dimension);
                  },
                  emit_if(Condition::Kind::Velocity, "velocity",
                          [](YAML::Emitter& out, const Condition& condition, int dimension) {
                            emit_components(out, condition.velocity, dimension);
                          })),
              "m/s"),
      in_unit(section_key<Condition>(
                  "traction", "map of components", "one kind", "keys x (and y in 2D); at least one",
                  "Imposed traction of the given components (tension positive); others zero.",
                  [](const YamlNode& node, Condition& condition, Reading& reading) {
                    condition.kind = Condition::Kind::Traction;
                    condition.traction = read_components(node, reading.so_far.dimension);
                  },
                  emit_if(Condition::Kind::Traction, "traction",
                          [](YAML::Emitter& out, const Condition& condition, int dimension) {
                            emit_components(out, condition.traction, dimension);
                          })),
              "Pa"),
      section_key<Condition>(
          "fixed", "boolean", "one kind", "true", "v = 0: a rough rigid wall.",
          [](const YamlNode& node, Condition& condition, Reading&) {
            if (!to_bool(node)) fail_at(node, "'fixed' can only be true", "true (or leave it out)");
            condition.kind = Condition::Kind::Fixed;
          },
          emit_if(Condition::Kind::Fixed, "fixed",
                  [](YAML::Emitter& out, const Condition&, int) { out << "true"; })),
      in_unit(section_key<Condition>(
                  "pore_pressure", "time function", "one kind", "model: saturated_vpw only",
                  "Drained face: the excess pore pressure imposed on the group's nodes.",
                  [](const YamlNode& node, Condition& condition, Reading&) {
                    condition.kind = Condition::Kind::PorePressure;
                    condition.pore_pressure = read_time_function(node);
                  },
                  emit_if(Condition::Kind::PorePressure, "pore_pressure",
                          [](YAML::Emitter& out, const Condition& condition, int) {
                            emit_time_function(out, *condition.pore_pressure);
                          })),
              "Pa"),
      section_key<Condition>(
          "roller", "word", "one kind", "x, or y in 2D: the axis of the normal",
          "Smooth wall or symmetry plane: normal velocity and shear stress zero.", read_roller,
          emit_if(Condition::Kind::Roller, "roller",
                  [](YAML::Emitter& out, const Condition& condition, int) {
                    out << axis_letter(condition.axis);
                  })),
      section_key<Condition>(
          "rotation", "map", "one kind", "2D only; keys angular_velocity, centre",
          "Rigid rotation at a constant rate: both velocity components imposed.", read_rotation,
          [](YAML::Emitter& out, const Condition& condition, const CaseDescription& description) {
            if (condition.kind != Condition::Kind::Rotation) return;
            out << YAML::Key << "rotation" << YAML::Value << YAML::Flow << YAML::BeginMap;
            emit_keys(out, rotation_keys(), condition, description);
            out << YAML::EndMap;
          }),
      section_key<Condition>(
          "rigid_wall", "map", "one kind", "keys point, normal, surface",
          "A fixed plane the group's nodes cannot cross (contact: a node on it cannot move into "
          "it, and on a rough wall does not slip); it acts on whichever nodes reach it.",
          read_rigid_wall,
          [](YAML::Emitter& out, const Condition& condition, const CaseDescription& description) {
            if (condition.kind != Condition::Kind::RigidWall) return;
            out << YAML::Key << "rigid_wall" << YAML::Value << YAML::Flow << YAML::BeginMap;
            emit_keys(out, rigid_wall_keys(), condition, description);
            out << YAML::EndMap;
          }),
      section_key<Condition>(
          "rigid_body", "map", "one kind",
          "2D only; keys name, polygon, velocity, load, mass, surface or friction",
          "A rigid polygon moving at an imposed velocity, or under a load by its own equation of "
          "motion, that the group's nodes cannot enter (contact as rigid_wall, or Coulomb "
          "friction); the force the nodes exert on it is written to probes.csv.",
          read_rigid_body,
          [](YAML::Emitter& out, const Condition& condition, const CaseDescription& description) {
            if (condition.kind != Condition::Kind::RigidBody) return;
            out << YAML::Key << "rigid_body" << YAML::Value << YAML::Flow << YAML::BeginMap;
            emit_keys(out, rigid_body_keys(), condition, description);
            out << YAML::EndMap;
          }),
      section_key<Condition>(
          "mirror", "boolean", "true", "true, false; with roller only",
          "Fold mirror images of the neighbours into the operators (docs/theory.md §7.1).",
          [](const YamlNode& node, Condition& condition, Reading&) {
            condition.mirror = to_bool(node);
          },
          emit_if(Condition::Kind::Roller, "mirror",
                  [](YAML::Emitter& out, const Condition& condition, int) {
                    out << (condition.mirror ? "true" : "false");
                  })),
  };
  return keys;
}

const Key<Condition>& condition_key(const std::string& name) {
  for (const Key<Condition>& key : condition_keys())
    if (key.name == name) return key;
  return condition_keys().front();  // not reached: every name passed is in the table
}

Condition read_condition(const YamlNode& node, Reading& reading) {
  const YamlMap item(node);
  item.allow_only(key_names(condition_keys()));
  Condition condition;
  condition.where = item.where();
  condition_key("group").read(item.require("group"), condition, reading);
  const YamlNode& kind = item.require_one_of(kKinds);
  const YamlNode* mirror = item.find("mirror");
  if (mirror != nullptr && kind.key != "roller") {
    fail_at(*mirror, "'mirror' only applies to a 'roller' condition", "remove 'mirror'", true);
  }
  condition_key(kind.key).read(kind, condition, reading);
  if (mirror != nullptr) condition_key("mirror").read(*mirror, condition, reading);
  return condition;
}

void read_conditions(const YamlNode& node, CaseDescription& description, Reading& reading) {
  for (const YamlNode& item : to_sequence(node))
    reading.errors.attempt(
        [&] { description.boundary_conditions.push_back(read_condition(item, reading)); });
  for (const Condition& condition : description.boundary_conditions)
    if (condition.kind == Condition::Kind::PorePressure &&
        description.model != ModelKind::SaturatedVpw)
      reading.errors.add(InputError(condition.where, "boundary_conditions.pore_pressure", "",
                                    "a pore-pressure condition needs the saturated model",
                                    "model: saturated_vpw"));
  for (const Condition& condition : description.boundary_conditions)
    if (condition.kind == Condition::Kind::RigidBody &&
        description.model != ModelKind::DryLargeDeformation)
      reading.errors.add(InputError(
          condition.where, "boundary_conditions.rigid_body", "",
          "a rigid body moves into the soil, which only the large-deformation model follows",
          "model: dry_large_deformation"));
}

void emit_conditions(YAML::Emitter& out, const CaseDescription& description,
                     const CaseDescription&) {
  if (description.boundary_conditions.empty()) return;
  out << YAML::Key << "boundary_conditions" << YAML::Value << YAML::BeginSeq;
  for (const Condition& condition : description.boundary_conditions) {
    out << YAML::BeginMap;
    emit_keys(out, condition_keys(), condition, description);
    out << YAML::EndMap;
  }
  out << YAML::EndSeq;
}

}  // namespace

Key<CaseDescription> boundary_conditions_section() {
  return section_key<CaseDescription>("boundary_conditions", "list", "none", "",
                                      "Imposed velocities, tractions and pore pressures.",
                                      read_conditions, emit_conditions);
}

void declare_boundary_condition_keys(std::vector<DeclaredKey>& list) {
  declare(list, "boundary_conditions[].", condition_keys());
  declare(list, "boundary_conditions[].rotation.", rotation_keys());
  declare(list, "boundary_conditions[].rigid_wall.", rigid_wall_keys());
  declare(list, "boundary_conditions[].rigid_body.", rigid_body_keys());
}

}  // namespace rktsph
