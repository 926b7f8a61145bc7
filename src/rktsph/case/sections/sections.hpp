// The sections of the case file, one file each (docs/input-reference.md has one heading each).
// Every section offers its entry in the top-level key table, which reads and writes the whole
// section, and adds its keys to the list the documentation check compares with the docs.
#pragma once

#include <vector>

#include "rktsph/case/key_spec.hpp"
#include "rktsph/case/sections/value_readers.hpp"

namespace rktsph {

// Top level: name, description, model, dimension, plane (header_section.cpp).
KeyTable<CaseDescription> header_keys();

Key<CaseDescription> materials_section();  // materials_section.cpp
Key<CaseDescription> geometry_section();   // geometry_section.cpp
Key<CaseDescription> groups_section();     // groups_section.cpp
/// Adds the built-in groups (all and the edges of the dimension) to description.groups, first, so
/// that later stages look every group name up in one list; before the `groups` section is read.
void add_built_in_groups(CaseDescription& description);
Key<CaseDescription> boundary_conditions_section();  // boundary_section.cpp
Key<CaseDescription> loads_section();                // loads_section.cpp
Key<CaseDescription> initial_conditions_section();   // loads_section.cpp
Key<CaseDescription> numerics_section();             // numerics_section.cpp
Key<CaseDescription> pore_fluid_section();           // pore_fluid_section.cpp
Key<CaseDescription> time_section();                 // output_section.cpp
Key<CaseDescription> output_section();               // output_section.cpp
Key<CaseDescription> probes_section();               // output_section.cpp

/// Every key of the case file's top level, in reading and writing order: the header first (the
/// dimension, on which vectors and shapes depend), materials before the shapes that name them,
/// groups before the conditions and probes that use them.
const KeyTable<CaseDescription>& top_level_keys();

// The keys inside each section, for the documentation check.
void declare_geometry_keys(std::vector<DeclaredKey>& list);
void declare_group_keys(std::vector<DeclaredKey>& list);
void declare_boundary_condition_keys(std::vector<DeclaredKey>& list);
void declare_loads_keys(std::vector<DeclaredKey>& list);
void declare_numerics_keys(std::vector<DeclaredKey>& list);
void declare_pore_fluid_keys(std::vector<DeclaredKey>& list);
void declare_output_keys(std::vector<DeclaredKey>& list);

/// A key whose value is a map or list read and written by its section's own functions; required
/// when `default_value` is "required".
template <typename Section>
Key<Section> section_key(
    std::string name, std::string type, std::string default_value, std::string allowed,
    std::string doc, std::function<void(const YamlNode&, Section&, Reading&)> read,
    std::function<void(YAML::Emitter&, const Section&, const CaseDescription&)> emit) {
  const bool required = default_value == "required";
  return Key<Section>{std::move(name),    std::move(type), "",       std::move(default_value),
                      std::move(allowed), std::move(doc),  required, std::move(read),
                      std::move(emit)};
}

/// `key` with its SI unit, for keys built by section_key whose value has one.
template <typename Section>
Key<Section> in_unit(Key<Section> key, std::string unit) {
  key.unit = std::move(unit);
  return key;
}

/// A vector of the case's dimension; `default_value` is "required" or what holds when left out.
template <typename Section>
Key<Section> vector_key(std::string name, Vec3 Section::*member, std::string unit,
                        std::string default_value, std::string doc) {
  const bool required = default_value == "required";
  Key<Section> key{std::move(name),
                   "vector",
                   std::move(unit),
                   std::move(default_value),
                   "any",
                   std::move(doc),
                   required,
                   {},
                   {}};
  key.read = [member](const YamlNode& node, Section& section, Reading& reading) {
    section.*member = read_vector(node, reading.so_far.dimension);
  };
  key.emit = [member, name = key.name](YAML::Emitter& out, const Section& section,
                                       const CaseDescription& description) {
    out << YAML::Key << name << YAML::Value;
    emit_vector(out, section.*member, description.dimension);
  };
  return key;
}

}  // namespace rktsph
