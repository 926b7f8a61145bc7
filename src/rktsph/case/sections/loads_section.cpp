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
      Key<GravitySpec>{
          "acceleration", "vector", "m/s²", "required", "any",
          "The gravity acceleration, e.g. [0, -9.81].", true,
          [](const YamlNode& node, GravitySpec& gravity, Reading& reading) {
            gravity.acceleration = read_vector(node, reading.so_far.dimension);
          },
          [](YAML::Emitter& out, const GravitySpec& gravity, const CaseDescription& description) {
            out << YAML::Key << "acceleration" << YAML::Value;
            emit_vector(out, gravity.acceleration, description.dimension);
          }},
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

/// A map key of the description read by `keys` into an optional member, written when set.
template <typename Spec>
Key<CaseDescription> optional_block_key(std::string name,
                                        std::optional<Spec> CaseDescription::*member,
                                        const KeyTable<Spec>& (*keys)(), std::string doc) {
  Key<CaseDescription> key{name, "map", "", "none", "", std::move(doc), false, {}, {}};
  key.read = [member, keys](const YamlNode& node, CaseDescription& description, Reading& reading) {
    Spec spec;
    spec.where = YamlMap(node).where();
    read_keys(node, keys(), spec, reading);
    description.*member = spec;
  };
  key.emit = [member, keys, name](YAML::Emitter& out, const CaseDescription& description,
                                  const CaseDescription&) {
    if (!(description.*member)) return;
    out << YAML::Key << name << YAML::Value << YAML::BeginMap;
    emit_keys(out, keys(), *(description.*member), description);
    out << YAML::EndMap;
  };
  return key;
}

const KeyTable<CaseDescription>& loads_keys() {
  static const KeyTable<CaseDescription> keys = {
      optional_block_key<GravitySpec>("gravity", &CaseDescription::gravity, gravity_keys,
                                      "Body force per unit mass."),
      optional_block_key<DampingSpec>("damping", &CaseDescription::damping, damping_keys,
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

const KeyTable<InitialConditionsSpec>& initial_conditions_keys() {
  static const KeyTable<InitialConditionsSpec> keys = {
      Key<InitialConditionsSpec>{
          "velocity", "vector", "m/s", "zero", "any", "Uniform initial velocity.", false,
          [](const YamlNode& node, InitialConditionsSpec& initial, Reading& reading) {
            initial.velocity = read_vector(node, reading.so_far.dimension);
          },
          [](YAML::Emitter& out, const InitialConditionsSpec& initial,
             const CaseDescription& description) {
            out << YAML::Key << "velocity" << YAML::Value;
            emit_vector(out, initial.velocity, description.dimension);
          }},
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
}

}  // namespace rktsph
