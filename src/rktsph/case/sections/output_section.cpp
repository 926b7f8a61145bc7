// The `time`, `output` and `probes` sections: how long a run lasts and what it writes
// (docs/input-reference.md, "time", "output" and "probes").
#include <fmt/format.h>

#include <set>

#include "rktsph/case/sections/sections.hpp"
#include "rktsph/case/sections/value_readers.hpp"

namespace rktsph {

namespace {

/// Upper bound of integer counts; far beyond any run, and exactly representable as a double.
constexpr long kMaxCount = 1000000000000000L;

const std::vector<std::string> kOutputFields = {
    "velocity",      "displacement", "stress",   "pressure",     "deviatoric_stress", "eps_vp",
    "pore_pressure", "total_stress", "material", "free_surface", "surface_normal"};

const Choices<ProbeSpec::Reduction> kReductions = {{"mean", ProbeSpec::Reduction::Mean},
                                                   {"min", ProbeSpec::Reduction::Min},
                                                   {"max", ProbeSpec::Reduction::Max},
                                                   {"max_abs", ProbeSpec::Reduction::MaxAbs}};

const KeyTable<TimeSpec>& time_keys() {
  static const KeyTable<TimeSpec> keys = {
      number_key<TimeSpec>("end", &TimeSpec::end, NumberRange::positive(), "s",
                           "End time of the run.", true),
      integer_key<TimeSpec, long>("max_steps", &TimeSpec::max_steps, 1, kMaxCount,
                                  "The largest number of steps a run may need."),
      optional_number_key<TimeSpec>(
          "stop_when_at_rest", &TimeSpec::stop_when_at_rest, NumberRange{0.0, 1.0, true, true}, "",
          "off", "Ends the run at rest: the largest speed at most this fraction of its peak."),
  };
  return keys;
}

void read_output_fields(const YamlNode& node, OutputSpec& output, Reading&) {
  for (const YamlNode& field : to_sequence(node)) {
    const std::string name = to_choice(field, kOutputFields);
    if (contains(output.fields, name)) {
      fail_at(field, "field listed twice", "each field once");
    }
    output.fields.push_back(name);
  }
}

const KeyTable<OutputSpec>& output_keys() {
  using O = OutputSpec;
  static const KeyTable<OutputSpec> keys = {
      number_key<O>("interval", &O::interval, NumberRange::non_negative(), "s",
                    "Field output at the first step at or past each multiple; 0 = first and "
                    "last state only."),
      number_key<O>("probe_interval", &O::probe_interval, NumberRange::non_negative(), "s",
                    "Probe output at the first step at or past each multiple; 0 = every step."),
      number_key<O>("checkpoint_interval", &O::checkpoint_interval, NumberRange::non_negative(),
                    "s", "Write checkpoint.bin every so much simulated time; 0 = never."),
      Key<O>{"fields", "list of words", "", "all fields of the model",
             "each once, from: " + documented_words(kOutputFields),
             "Fields written to the field output.", false, read_output_fields,
             [](YAML::Emitter& out, const O& output, const CaseDescription&) {
               if (output.fields.empty()) return;
               out << YAML::Key << "fields" << YAML::Value << YAML::Flow << output.fields;
             }},
  };
  return keys;
}

const KeyTable<ProbeSpec>& probe_keys() {
  using P = ProbeSpec;
  static const KeyTable<ProbeSpec> keys = {
      Key<P>{"name", "word", "", "required", "letters, digits, _ and -; unique",
             "Column prefix in the probe file.", true,
             [](const YamlNode& node, P& probe, Reading&) {
               probe.name = to_identifier(node, kLabelAlphabet, kLabelAlphabetName);
             },
             [](YAML::Emitter& out, const P& probe, const CaseDescription&) {
               out << YAML::Key << "name" << YAML::Value << probe.name;
             }},
      Key<P>{"group", "word", "", "required", "a built-in or defined group",
             "Nodes the probe reads.", true,
             [](const YamlNode& node, P& probe, Reading& reading) {
               probe.group = read_group_reference(node, reading.so_far.groups);
             },
             [](YAML::Emitter& out, const P& probe, const CaseDescription&) {
               out << YAML::Key << "group" << YAML::Value << probe.group;
             }},
      // Which fields exist depends on the model; the model checks the names when it sets up
      // probes.
      Key<P>{"fields", "list of words", "", "required", "≥ 1; each [a-z0-9_]+",
             "Components, e.g. stress_xx, velocity_x, pore_pressure.", true,
             [](const YamlNode& node, P& probe, Reading&) {
               for (const YamlNode& field : to_sequence(node, 1)) {
                 probe.fields.push_back(to_identifier(
                     field, kFieldAlphabet, "a field name of a-z, 0-9 and '_' (e.g. stress_xx)"));
                 probe.field_where.push_back(field.where);
               }
             },
             [](YAML::Emitter& out, const P& probe, const CaseDescription&) {
               out << YAML::Key << "fields" << YAML::Value << YAML::Flow << probe.fields;
             }},
      choice_key<P, P::Reduction>("reduction", &P::reduction, kReductions,
                                  "How the group's node values become one number."),
  };
  return keys;
}

ProbeSpec read_probe(const YamlNode& node, Reading& reading) {
  const YamlMap item(node);
  ProbeSpec probe;
  probe.where = item.where();
  probe.path = node.path;
  ErrorList errors;
  Reading probe_reading{reading.so_far, errors, reading.materials_complete};
  read_keys(node, probe_keys(), probe, probe_reading);
  if (!errors.empty()) throw InputError::combine(errors.take());
  return probe;
}

void read_probes(const YamlNode& node, CaseDescription& description, Reading& reading) {
  std::set<std::string> names;
  for (const YamlNode& item : to_sequence(node)) {
    reading.errors.attempt([&] {
      ProbeSpec probe = read_probe(item, reading);
      if (!names.insert(probe.name).second) {
        fail_at(*YamlMap(item).find("name"), "a probe with this name is already defined",
                "a unique probe name");
      }
      description.probes.push_back(std::move(probe));
    });
  }
}

}  // namespace

Key<CaseDescription> time_section() {
  return section_key<CaseDescription>(
      "time", "map", "required", "", "How long the run lasts.",
      [](const YamlNode& node, CaseDescription& description, Reading& reading) {
        description.time.where = YamlMap(node).where();
        read_keys(node, time_keys(), description.time, reading);
      },
      [](YAML::Emitter& out, const CaseDescription& description, const CaseDescription&) {
        out << YAML::Key << "time" << YAML::Value << YAML::BeginMap;
        emit_keys(out, time_keys(), description.time, description);
        out << YAML::EndMap;
      });
}

Key<CaseDescription> output_section() {
  return section_key<CaseDescription>(
      "output", "map", "the defaults below", "", "What the run writes, and when.",
      [](const YamlNode& node, CaseDescription& description, Reading& reading) {
        description.output.where = YamlMap(node).where();
        read_keys(node, output_keys(), description.output, reading);
      },
      [](YAML::Emitter& out, const CaseDescription& description, const CaseDescription&) {
        out << YAML::Key << "output" << YAML::Value << YAML::BeginMap;
        emit_keys(out, output_keys(), description.output, description);
        out << YAML::EndMap;
      });
}

Key<CaseDescription> probes_section() {
  return section_key<CaseDescription>(
      "probes", "list", "none", "", "Time series of group values.", read_probes,
      [](YAML::Emitter& out, const CaseDescription& description, const CaseDescription&) {
        if (description.probes.empty()) return;
        out << YAML::Key << "probes" << YAML::Value << YAML::BeginSeq;
        for (const ProbeSpec& probe : description.probes) {
          out << YAML::Flow << YAML::BeginMap;
          emit_keys(out, probe_keys(), probe, description);
          out << YAML::EndMap;
        }
        out << YAML::EndSeq;
      });
}

void declare_output_keys(std::vector<DeclaredKey>& list) {
  declare(list, "time.", time_keys());
  declare(list, "output.", output_keys());
  declare(list, "probes[].", probe_keys());
}

}  // namespace rktsph
