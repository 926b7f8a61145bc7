// The `materials` section: named blocks whose parameter names and ranges belong to each material
// model (docs/input-reference.md, "materials"); here they only have to be numbers, or names for
// the few word-valued keys of kMaterialWordKeys.
#include "rktsph/case/sections/sections.hpp"
#include "rktsph/case/sections/value_readers.hpp"

#include <set>
#include <string>

namespace rktsph {

namespace {

/// The keys of material blocks whose values are words, not numbers: `matching` of
/// perzyna_drucker_prager, `elasticity` of perzyna_modified_cam_clay. The material checks the
/// word; here it only has to be a name.
const std::set<std::string> kMaterialWordKeys = {"matching", "elasticity"};

ParameterBlock read_material(const YamlNode& entry, ErrorList& errors) {
  ParameterBlock parameters;
  errors.attempt([&] {
    read_label_key(entry);
    const YamlMap block(entry);
    parameters.path = entry.path;
    parameters.where = block.where();
    const YamlNode& model = block.require("model");
    parameters.words["model"] = {
        to_identifier(model, kFieldAlphabet, "a material model name such as linear_elastic"),
        model.where};
  });
  if (entry.is_map()) {
    for (const YamlNode& value : entry.children) {
      if (value.key == "model") continue;
      errors.attempt([&] {
        if (kMaterialWordKeys.count(value.key)) {
          parameters.words[value.key] = {
              to_identifier(value, kFieldAlphabet, "a word such as plane_strain"), value.where};
          return;
        }
        parameters.values[value.key] = Parameter{to_number(value), value.where};
      });
    }
  }
  return parameters;
}

void read_materials(const YamlNode& node, CaseDescription& description, Reading& reading) {
  const YamlMap materials(node);
  if (node.children.empty()) {
    fail_at(node, "no material is defined", "at least one named material block");
  }
  bool complete = true;
  for (const YamlNode& entry : node.children) {
    const std::size_t errors_before = reading.errors.size();
    description.materials[entry.key] = read_material(entry, reading.errors);
    if (reading.errors.size() != errors_before) complete = false;
  }
  reading.materials_complete = complete;
}

void emit_materials(YAML::Emitter& out, const CaseDescription& description,
                    const CaseDescription&) {
  out << YAML::Key << "materials" << YAML::Value << YAML::BeginMap;
  for (const auto& [name, block] : description.materials) {
    out << YAML::Key << name << YAML::Value << YAML::BeginMap;
    for (const auto& [key, word] : block.words) {
      out << YAML::Key << key << YAML::Value << word.first;
    }
    for (const auto& [key, parameter] : block.values) {
      out << YAML::Key << key << YAML::Value << number(parameter.value);
    }
    out << YAML::EndMap;
  }
  out << YAML::EndMap;
}

}  // namespace

Key<CaseDescription> materials_section() {
  return section_key<CaseDescription>("materials", "map", "required", "≥ 1 named block",
                                      "The materials by name; each block's keys belong to its "
                                      "model.",
                                      read_materials, emit_materials);
}

}  // namespace rktsph
