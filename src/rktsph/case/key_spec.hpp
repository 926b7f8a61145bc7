// One declaration per case-file key (docs/input-reference.md): its name, type, SI unit, default,
// allowed values and a one-line meaning, together with how it is read into and written from its
// section of the CaseDescription. A section of the case file is a table of these; the reader
// (allowed keys, required keys, parsing, range checks), the resolved case the run writes and the
// documentation check (tests/case/input_reference_test.cpp) all walk the same table.
#pragma once

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "rktsph/case/case_description.hpp"
#include "rktsph/case/yaml_reader.hpp"

namespace rktsph {

/// Runs independent parts of the reading; an InputError of one part is kept and the reading goes
/// on, so that one pass reports every mistake (the reader throws them all together).
class ErrorList {
 public:
  template <typename Part>
  void attempt(Part&& part) {
    try {
      part();
    } catch (const InputError& error) {
      errors_.push_back(error);
    }
  }
  void add(InputError error) { errors_.push_back(std::move(error)); }
  std::size_t size() const { return errors_.size(); }
  bool empty() const { return errors_.empty(); }
  std::vector<InputError> take() { return std::move(errors_); }

 private:
  std::vector<InputError> errors_;
};

/// What the reading of one key may look at besides its own value: the sections read before it
/// (the dimension, the model, the groups, the materials) and where to keep its mistakes.
struct Reading {
  const CaseDescription& so_far;
  ErrorList& errors;
  /// False once a material block failed: a shape naming a material is then not checked against
  /// the list, which would only repeat that mistake.
  bool materials_complete = false;
};

/// The shortest text that reads back to the same double ("0.5", "2.2e+09").
inline std::string number(double value) {
  return fmt::format("{}", value);
}

/// A number as the documentation writes it: as number(), without the exponent's '+' and leading
/// zeros ("2.2e9", "1e-8").
std::string documented_number(double value);

/// One key of a map of the case file, read into and written from a `Section`.
template <typename Section>
struct Key {
  std::string name;
  std::string type;           ///< number, integer, boolean, word, text, vector, map, list, ...
  std::string unit;           ///< SI unit; "–" for a ratio, empty where no unit applies
  std::string default_value;  ///< "required", the value, or how it is found when left out
  std::string allowed;        ///< range or values
  std::string doc;            ///< one line
  bool required = false;
  /// Parses and checks the value into the section; throws InputError.
  std::function<void(const YamlNode&, Section&, Reading&)> read;
  /// Writes "name: value" of the resolved case, or nothing when the key has no value to write.
  std::function<void(YAML::Emitter&, const Section&, const CaseDescription&)> emit;
};

template <typename Section>
using KeyTable = std::vector<Key<Section>>;

template <typename Section>
std::vector<std::string> key_names(const KeyTable<Section>& keys) {
  std::vector<std::string> names;
  for (const Key<Section>& key : keys)
    names.push_back(key.name);
  return names;
}

/// Reads the map `node` into `section` by its table: unknown keys, missing required keys and each
/// key's own mistakes are collected in reading.errors, one per key.
template <typename Section>
void read_keys(const YamlNode& node, const KeyTable<Section>& keys, Section& section,
               Reading& reading) {
  const YamlMap map(node);
  reading.errors.attempt([&] { map.allow_only(key_names(keys)); });
  for (const Key<Section>& key : keys) {
    reading.errors.attempt([&] {
      if (const YamlNode* value = map.find(key.name)) {
        key.read(*value, section, reading);
      } else if (key.required) {
        map.require(key.name);  // throws the missing-key error, or the misspelling's
      }
    });
  }
}

/// Writes every key of the table that has a value, in table order.
template <typename Section>
void emit_keys(YAML::Emitter& out, const KeyTable<Section>& keys, const Section& section,
               const CaseDescription& description) {
  for (const Key<Section>& key : keys)
    key.emit(out, section, description);
}

// ---------------------------------------------------------------------------------------------
// Keys of the common kinds. Their default is the Section's default member value, so that the
// struct's initialiser stays the one place a default is set.

/// "(0, 1]", "> 0", "≥ 0", "any": a NumberRange as the documentation writes it.
std::string documented_range(const NumberRange& range);

template <typename Section>
Key<Section> number_key(std::string name, double Section::*member, NumberRange range,
                        std::string unit, std::string doc, bool required = false) {
  Key<Section> key{std::move(name),
                   "number",
                   std::move(unit),
                   required ? "required" : documented_number(Section{}.*member),
                   documented_range(range),
                   std::move(doc),
                   required,
                   {},
                   {}};
  key.read = [member, range](const YamlNode& node, Section& section, Reading&) {
    section.*member = to_number(node, range);
  };
  key.emit = [member, name = key.name](YAML::Emitter& out, const Section& section,
                                       const CaseDescription&) {
    out << YAML::Key << name << YAML::Value << number(section.*member);
  };
  return key;
}

/// A number that may be left out; `default_value` says what holds then.
template <typename Section>
Key<Section> optional_number_key(std::string name, std::optional<double> Section::*member,
                                 NumberRange range, std::string unit, std::string default_value,
                                 std::string doc) {
  Key<Section> key{std::move(name),
                   "number",
                   std::move(unit),
                   std::move(default_value),
                   documented_range(range),
                   std::move(doc),
                   false,
                   {},
                   {}};
  key.read = [member, range](const YamlNode& node, Section& section, Reading&) {
    section.*member = to_number(node, range);
  };
  key.emit = [member, name = key.name](YAML::Emitter& out, const Section& section,
                                       const CaseDescription&) {
    if (section.*member) out << YAML::Key << name << YAML::Value << number(*(section.*member));
  };
  return key;
}

/// "0, 1" for a few values, "≥ 1" without a practical upper bound, else "[low, high]".
std::string documented_integer_range(long low, long high);

template <typename Section, typename Integer>
Key<Section> integer_key(std::string name, Integer Section::*member, long low, long high,
                         std::string doc) {
  Key<Section> key{std::move(name),
                   "integer",
                   "",
                   fmt::format("{}", Section{}.*member),
                   documented_integer_range(low, high),
                   std::move(doc),
                   false,
                   {},
                   {}};
  key.read = [member, low, high](const YamlNode& node, Section& section, Reading&) {
    section.*member = static_cast<Integer>(to_integer(node, low, high));
  };
  key.emit = [member, name = key.name](YAML::Emitter& out, const Section& section,
                                       const CaseDescription&) {
    out << YAML::Key << name << YAML::Value << section.*member;
  };
  return key;
}

template <typename Section>
Key<Section> boolean_key(std::string name, bool Section::*member, std::string doc) {
  Key<Section> key{std::move(name),
                   "boolean",
                   "",
                   (Section{}.*member) ? "true" : "false",
                   "true, false",
                   std::move(doc),
                   false,
                   {},
                   {}};
  key.read = [member](const YamlNode& node, Section& section, Reading&) {
    section.*member = to_bool(node);
  };
  key.emit = [member, name = key.name](YAML::Emitter& out, const Section& section,
                                       const CaseDescription&) {
    out << YAML::Key << name << YAML::Value << ((section.*member) ? "true" : "false");
  };
  return key;
}

/// The words of a word-valued key and the value each stands for.
template <typename Value>
using Choices = std::vector<std::pair<std::string, Value>>;

template <typename Value>
std::vector<std::string> choice_words(const Choices<Value>& choices) {
  std::vector<std::string> words;
  for (const auto& [word, value] : choices)
    words.push_back(word);
  return words;
}

template <typename Value>
std::string choice_word(const Choices<Value>& choices, const Value& value) {
  for (const auto& [word, candidate] : choices)
    if (candidate == value) return word;
  return {};
}

template <typename Value>
Value chosen_value(const Choices<Value>& choices, const YamlNode& node) {
  const std::string word = to_choice(node, choice_words(choices));
  for (const auto& [candidate, value] : choices)
    if (candidate == word) return value;
  return choices.front().second;  // not reached: to_choice accepted one of the words
}

/// "a, b, c"
std::string documented_words(const std::vector<std::string>& words);

template <typename Section, typename Value>
Key<Section> choice_key(std::string name, Value Section::*member, Choices<Value> choices,
                        std::string doc) {
  Key<Section> key{std::move(name),
                   "word",
                   "",
                   choice_word(choices, Section{}.*member),
                   documented_words(choice_words(choices)),
                   std::move(doc),
                   false,
                   {},
                   {}};
  key.read = [member, choices](const YamlNode& node, Section& section, Reading&) {
    section.*member = chosen_value(choices, node);
  };
  key.emit = [member, choices, name = key.name](YAML::Emitter& out, const Section& section,
                                                const CaseDescription&) {
    out << YAML::Key << name << YAML::Value << choice_word(choices, section.*member);
  };
  return key;
}

/// A word that may be left out; unset, the resolved case gets `computed(description)`.
template <typename Section, typename Value>
Key<Section> computed_choice_key(std::string name, std::optional<Value> Section::*member,
                                 Choices<Value> choices, std::string default_value,
                                 std::function<Value(const CaseDescription&)> computed,
                                 std::string doc) {
  Key<Section> key{std::move(name),
                   "word",
                   "",
                   std::move(default_value),
                   documented_words(choice_words(choices)),
                   std::move(doc),
                   false,
                   {},
                   {}};
  key.read = [member, choices](const YamlNode& node, Section& section, Reading&) {
    section.*member = chosen_value(choices, node);
  };
  key.emit = [member, choices, computed, name = key.name](
                 YAML::Emitter& out, const Section& section, const CaseDescription& description) {
    const Value value = (section.*member) ? *(section.*member) : computed(description);
    out << YAML::Key << name << YAML::Value << choice_word(choices, value);
  };
  return key;
}

// ---------------------------------------------------------------------------------------------
// The declarations, for the documentation check.

/// One declared key with its dotted path as docs/input-reference.md writes it: list items as
/// "[]" and named entries as "<name>", e.g. "boundary_conditions[].group".
struct DeclaredKey {
  std::string path;
  std::string type;
  std::string unit;
  std::string default_value;
  std::string allowed;
  std::string doc;
};

template <typename Section>
void declare(std::vector<DeclaredKey>& list, const std::string& prefix,
             const KeyTable<Section>& keys) {
  for (const Key<Section>& key : keys)
    list.push_back(
        {prefix + key.name, key.type, key.unit, key.default_value, key.allowed, key.doc});
}

/// Every key of every section of the case file, in the order of docs/input-reference.md.
std::vector<DeclaredKey> declared_case_keys();

}  // namespace rktsph
