// The `loads` section (gravity and damping) and the `initial_conditions` section
// (docs/input-reference.md, "loads" and "initial_conditions").
#include "rktsph/case/sections/sections.hpp"
#include "rktsph/case/sections/value_readers.hpp"

namespace rktsph {

namespace {

/// DampingSpec::end when no end is given: damping stays on for the whole run.
constexpr double kForever = 1e300;

const KeyTable<GravitySpec>& gravity_keys() {
  static const KeyTable<GravitySpec> keys = {
      vector_key<GravitySpec>("acceleration", &GravitySpec::acceleration, "m/s²", "required",
                              "The gravity acceleration, e.g. [0, -9.81]."),
      Key<GravitySpec>{"factor", "time function", "–", "1", "any",
                       "Multiplies the acceleration (e.g. a ramp to apply gravity gently).", false,
                       [](const YamlNode& node, GravitySpec& gravity, Reading&) {
                         gravity.factor = read_time_function(node);
                       },
                       [](YAML::Emitter& out, const GravitySpec& gravity, const CaseDescription&) {
                         out << YAML::Key << "factor" << YAML::Value;
                         emit_time_function(out, gravity.factor);
                       }},
  };
  return keys;
}

const KeyTable<DampingSpec>& damping_keys() {
  static const KeyTable<DampingSpec> keys = {
      number_key<DampingSpec>("coefficient", &DampingSpec::coefficient, NumberRange::non_negative(),
                              "1/s", "ξ of the momentum source −ξ v.", true),
      number_key<DampingSpec>("start", &DampingSpec::start, NumberRange::non_negative(), "s",
                              "Time damping starts."),
      Key<DampingSpec>{"end", "number", "s", "never", "> start",
                       "Time damping stops (exclusive); leave out for until the end.", false,
                       [](const YamlNode& node, DampingSpec& damping, Reading&) {
                         NumberRange after_start = NumberRange::positive();
                         after_start.low = damping.start;
                         damping.end = to_number(node, after_start);
                       },
                       [](YAML::Emitter& out, const DampingSpec& damping, const CaseDescription&) {
                         if (damping.end < kForever)
                           out << YAML::Key << "end" << YAML::Value << number(damping.end);
                       }},
  };
  return keys;
}

/// A map key of `Owner` read by `keys` into an optional member, written when set.
template <typename Owner, typename Spec>
Key<Owner> optional_block_key(std::string name, std::optional<Spec> Owner::*member,
                              const KeyTable<Spec>& (*keys)(), std::string doc) {
  Key<Owner> key{name, "map", "", "none", "", std::move(doc), false, {}, {}};
  key.read = [member, keys](const YamlNode& node, Owner& owner, Reading& reading) {
    Spec spec;
    spec.where = YamlMap(node).where();
    read_keys(node, keys(), spec, reading);
    owner.*member = spec;
  };
  key.emit = [member, keys, name](YAML::Emitter& out, const Owner& owner,
                                  const CaseDescription& description) {
    if (!(owner.*member)) return;
    out << YAML::Key << name << YAML::Value << YAML::BeginMap;
    emit_keys(out, keys(), *(owner.*member), description);
    out << YAML::EndMap;
  };
  return key;
}

/// `key`, refused in 1D: `what` names it with its verb, e.g. "'bending_mode' is".
template <typename Owner>
Key<Owner> only_in_2d(Key<Owner> key, std::string what) {
  key.allowed = "2D only";
  key.read = [read = std::move(key.read), what = std::move(what)](const YamlNode& node,
                                                                  Owner& owner, Reading& reading) {
    reject_unless_2d(node, reading.so_far.dimension, what);
    read(node, owner, reading);
  };
  return key;
}

const KeyTable<CaseDescription>& loads_keys() {
  static const KeyTable<CaseDescription> keys = {
      optional_block_key<CaseDescription, GravitySpec>("gravity", &CaseDescription::gravity,
                                                       gravity_keys, "Body force per unit mass."),
      optional_block_key<CaseDescription, DampingSpec>(
          "damping", &CaseDescription::damping, damping_keys,
          "Viscous damping of the velocity, while start ≤ t < end."),
  };
  return keys;
}

const KeyTable<InitialConditionsSpec>& geostatic_keys() {
  static const KeyTable<InitialConditionsSpec> keys = {
      Key<InitialConditionsSpec>{
          "surface", "number", "m", "required", "any", "y of the free ground surface.", true,
          [](const YamlNode& node, InitialConditionsSpec& initial, Reading&) {
            initial.geostatic_surface = to_number(node);
          },
          [](YAML::Emitter& out, const InitialConditionsSpec& initial, const CaseDescription&) {
            out << YAML::Key << "surface" << YAML::Value << number(*initial.geostatic_surface);
          }},
      optional_number_key<InitialConditionsSpec>(
          "k0", &InitialConditionsSpec::k0, NumberRange::positive(), "–", "ν/(1−ν) of the material",
          "Ratio of horizontal to vertical effective stress."),
  };
  return keys;
}

const KeyTable<InitialRotationSpec>& initial_rotation_keys() {
  static const KeyTable<InitialRotationSpec> keys = {
      number_key<InitialRotationSpec>("rate", &InitialRotationSpec::rate, NumberRange::any(),
                                      "rad/s", "ω, counter-clockwise positive.", true),
      vector_key<InitialRotationSpec>("centre", &InitialRotationSpec::centre, "m", "required",
                                      "The centre c of the rotation."),
  };
  return keys;
}

const KeyTable<BendingModeSpec>& bending_mode_keys() {
  static const KeyTable<BendingModeSpec> keys = {
      number_key<BendingModeSpec>("root", &BendingModeSpec::root, NumberRange::any(), "m",
                                  "x of the clamped root.", true),
      number_key<BendingModeSpec>("length", &BendingModeSpec::length, NumberRange::positive(), "m",
                                  "Length L of the cantilever from its root.", true),
      number_key<BendingModeSpec>("tip_velocity", &BendingModeSpec::tip_velocity,
                                  NumberRange::any(), "m/s", "v_y at x = root + L.", true),
  };
  return keys;
}

/// The stress components a case may name; whether the model carries each is checked when the
/// model is built (docs/input-reference.md, "initial_conditions").
const std::vector<std::string>& stress_component_names() {
  static const std::vector<std::string> names = {"xx", "yy", "xy", "zz"};
  return names;
}

void read_initial_stress(const YamlNode& node, InitialConditionsSpec& initial, Reading&) {
  const YamlMap map(node);
  map.allow_only(stress_component_names());
  if (node.children.empty())
    fail_at(node, "no component given",
            fmt::format("at least one of {}", quoted_list(stress_component_names())));
  initial.stress.clear();
  for (const YamlNode& component : node.children)
    initial.stress[component.key] = Parameter{to_number(component), component.where};
}

void emit_initial_stress(YAML::Emitter& out, const InitialConditionsSpec& initial,
                         const CaseDescription&) {
  if (initial.stress.empty()) return;
  out << YAML::Key << "stress" << YAML::Value << YAML::Flow << YAML::BeginMap;
  for (const std::string& name : stress_component_names())
    if (const auto it = initial.stress.find(name); it != initial.stress.end())
      out << YAML::Key << name << YAML::Value << number(it->second.value);
  out << YAML::EndMap;
}

const KeyTable<InitialConditionsSpec>& initial_conditions_keys() {
  static const KeyTable<InitialConditionsSpec> keys = {
      vector_key<InitialConditionsSpec>("velocity", &InitialConditionsSpec::velocity, "m/s", "zero",
                                        "Uniform initial velocity."),
      Key<InitialConditionsSpec>{
          "geostatic", "map", "", "none", "", "Start from geostatic stress instead of zero stress.",
          false,
          [](const YamlNode& node, InitialConditionsSpec& initial, Reading& reading) {
            read_keys(node, geostatic_keys(), initial, reading);
          },
          [](YAML::Emitter& out, const InitialConditionsSpec& initial,
             const CaseDescription& description) {
            if (!initial.geostatic_surface) return;
            out << YAML::Key << "geostatic" << YAML::Value << YAML::BeginMap;
            emit_keys(out, geostatic_keys(), initial, description);
            out << YAML::EndMap;
          }},
      Key<InitialConditionsSpec>{"stress", "map of components", "Pa", "zero",
                                 "keys xx, yy, xy, zz; only components the model carries",
                                 "Uniform stress added to every node (after geostatic).", false,
                                 read_initial_stress, emit_initial_stress},
      only_in_2d(optional_block_key<InitialConditionsSpec, InitialRotationSpec>(
                     "angular_velocity", &InitialConditionsSpec::angular_velocity,
                     initial_rotation_keys, "Adds the rigid-rotation velocity ω e_z × (X − c)."),
                 "'angular_velocity' is"),
      only_in_2d(optional_block_key<InitialConditionsSpec, BendingModeSpec>(
                     "bending_mode", &InitialConditionsSpec::bending_mode, bending_mode_keys,
                     "Adds the first cantilever bending mode to v_y."),
                 "'bending_mode' is"),
  };
  return keys;
}

}  // namespace

Key<CaseDescription> loads_section() {
  return section_key<CaseDescription>(
      "loads", "map", "none", "", "Gravity and damping.",
      [](const YamlNode& node, CaseDescription& description, Reading& reading) {
        read_keys(node, loads_keys(), description, reading);
      },
      [](YAML::Emitter& out, const CaseDescription& description, const CaseDescription&) {
        if (!description.gravity && !description.damping) return;
        out << YAML::Key << "loads" << YAML::Value << YAML::BeginMap;
        emit_keys(out, loads_keys(), description, description);
        out << YAML::EndMap;
      });
}

Key<CaseDescription> initial_conditions_section() {
  return section_key<CaseDescription>(
      "initial_conditions", "map", "at rest", "", "The state at t = 0.",
      [](const YamlNode& node, CaseDescription& description, Reading& reading) {
        description.initial.where = YamlMap(node).where();
        read_keys(node, initial_conditions_keys(), description.initial, reading);
      },
      [](YAML::Emitter& out, const CaseDescription& description, const CaseDescription&) {
        out << YAML::Key << "initial_conditions" << YAML::Value << YAML::BeginMap;
        emit_keys(out, initial_conditions_keys(), description.initial, description);
        out << YAML::EndMap;
      });
}

void declare_loads_keys(std::vector<DeclaredKey>& list) {
  declare(list, "loads.", loads_keys());
  declare(list, "loads.gravity.", gravity_keys());
  declare(list, "loads.damping.", damping_keys());
  declare(list, "initial_conditions.", initial_conditions_keys());
  declare(list, "initial_conditions.geostatic.", geostatic_keys());
  declare(list, "initial_conditions.angular_velocity.", initial_rotation_keys());
  declare(list, "initial_conditions.bending_mode.", bending_mode_keys());
}

}  // namespace rktsph
